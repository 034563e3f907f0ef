#include "bake/gltf_file_access.h"

#include <limits.h>
#include <stdlib.h>
#include <sys/stat.h>

#include <cerrno>
#include <cstring>

#include "bake/input_file.h"

namespace stipple::bake::gltf {

namespace {

// True if the relative path `rel` climbs above its start at some point ("../x", "a/../../x").
bool climbs_out(const std::string& rel) {
    long depth = 0;
    size_t begin = 0;
    while (begin <= rel.size()) {
        size_t end = rel.find('/', begin);
        if (end == std::string::npos) end = rel.size();
        const std::string part = rel.substr(begin, end - begin);
        if (part == "..") {
            if (--depth < 0) return true;
        } else if (!part.empty() && part != ".") {
            ++depth;
        }
        begin = end + 1;
    }
    return false;
}

std::string real_path(const std::string& path) {
    char buffer[PATH_MAX];
    return ::realpath(path.c_str(), buffer) ? std::string(buffer) : std::string();
}

}  // namespace

FileAccess::FileAccess(const std::string& model_path) {
    const size_t slash = model_path.find_last_of('/');
    if (slash == std::string::npos)
        base_dir_ = ".";
    else if (slash == 0)
        base_dir_ = "/";
    else
        base_dir_ = model_path.substr(0, slash);
    folder_real_ = real_path(base_dir_);
}

tinygltf::FsCallbacks FileAccess::callbacks() {
    tinygltf::FsCallbacks fs;
    fs.FileExists = &FileAccess::exists;
    fs.ExpandFilePath = &FileAccess::expand;
    fs.ReadWholeFile = &FileAccess::read;
    fs.WriteWholeFile = &FileAccess::write;
    fs.user_data = this;
    return fs;
}

std::string FileAccess::refusal_in(const std::string& error) const {
    for (const auto& r : refusals_) {
        if (error.find(r.first) != std::string::npos) return r.second;
    }
    return std::string();
}

void FileAccess::refuse(const std::string& uri, const std::string& why) {
    std::string shown = uri.size() > 100 ? uri.substr(0, 100) + "..." : uri;
    for (char& c : shown) {
        if (c < 0x20 || c > 0x7e) c = '?';
    }
    refusals_.emplace_back(uri, "URI '" + shown + "' " + why);
}

bool FileAccess::resolve(const std::string& path, std::string* real, uint64_t* size) {
    // tinygltf tries base_dir + "/" + URI, then "./" + URI (the working directory): only
    // the first is ours.
    const std::string prefix = base_dir_ == "/" ? base_dir_ : base_dir_ + "/";
    if (path.compare(0, prefix.size(), prefix) != 0) return false;
    const std::string uri = path.substr(prefix.size());
    if (uri.empty()) return false;
    if (uri[0] == '/') {
        refuse(uri, "is an absolute path; only files in the model's folder are read");
        return false;
    }
    if (climbs_out(uri)) {
        refuse(uri, "climbs out of the model's folder ('..')");
        return false;
    }
    struct stat st = {};
    if (::lstat(path.c_str(), &st) != 0) return false;  // not found: tinygltf says so
    *real = real_path(path);
    if (folder_real_.empty() || real->empty()) {
        refuse(uri, std::string("cannot be resolved: ") + std::strerror(errno));
        return false;
    }
    const std::string inside = folder_real_ == "/" ? folder_real_ : folder_real_ + "/";
    if (real->compare(0, inside.size(), inside) != 0) {
        refuse(uri, "resolves outside the model's folder (symlink to '" + *real + "')");
        return false;
    }
    const BakeError checked = check_input_file(*real, kMaxGltfExternalFileBytes, size);
    if (!checked.ok()) {
        refuse(uri, checked.message);
        return false;
    }
    if (total_ + *size > kMaxGltfExternalTotalBytes) {
        refuse(uri, "would take the model's external files over the " +
                        byte_size_text(kMaxGltfExternalTotalBytes) + " total cap");
        return false;
    }
    return true;
}

bool FileAccess::exists(const std::string& path, void* self) {
    std::string real;
    uint64_t size = 0;
    return static_cast<FileAccess*>(self)->resolve(path, &real, &size);
}

std::string FileAccess::expand(const std::string& path, void*) {
    return path;  // no '~', no $VAR, no wordexp
}

bool FileAccess::read(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                      void* self) {
    FileAccess* access = static_cast<FileAccess*>(self);
    std::string real;
    uint64_t size = 0;
    if (!access->resolve(path, &real, &size)) {
        if (err) *err += "refused";
        return false;
    }
    const BakeError read = read_input_file(real, kMaxGltfExternalFileBytes, out);
    if (!read.ok()) {
        if (err) *err += read.message;
        return false;
    }
    access->total_ += out->size();
    return true;
}

bool FileAccess::write(std::string* err, const std::string&, const std::vector<unsigned char>&,
                       void*) {
    if (err) *err += "the bake writes no glTF files";
    return false;
}

BakeError check_data_uris(const unsigned char* json, size_t size, uint64_t cap) {
    static const char kOpen[] = "\"data:";
    const size_t open = sizeof(kOpen) - 1;
    const unsigned char* end = json + size;
    const unsigned char* at = json;
    while (size_t(end - at) >= open) {
        const void* hit = std::memchr(at, '"', size_t(end - at));
        if (!hit) break;
        at = static_cast<const unsigned char*>(hit);
        if (size_t(end - at) < open || std::memcmp(at, kOpen, open) != 0) {
            ++at;
            continue;
        }
        const void* close = std::memchr(at + 1, '"', size_t(end - at - 1));
        const size_t length = close ? size_t(static_cast<const unsigned char*>(close) - at - 1)
                                    : size_t(end - at - 1);
        if (length > cap) {
            return bake_error(BakeErrorCode::unsupported,
                              "a data URI of " + std::to_string(length) + " bytes is over the " +
                                  byte_size_text(cap) + " cap (store big buffers in a .bin file)");
        }
        at = close ? static_cast<const unsigned char*>(close) + 1 : end;
    }
    return BakeError();
}

}  // namespace stipple::bake::gltf
