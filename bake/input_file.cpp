#include "bake/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cassert>
#include <cerrno>
#include <cstring>

namespace stipple::bake {

namespace {

BakeError check_stat(const struct stat& st, uint64_t cap, uint64_t* size) {
    if (S_ISDIR(st.st_mode)) return bake_error(BakeErrorCode::unsupported, "is a directory");
    if (!S_ISREG(st.st_mode)) {
        return bake_error(BakeErrorCode::unsupported,
                          "is not a regular file (a device, FIFO or socket)");
    }
    const uint64_t n = uint64_t(st.st_size);
    if (n > cap) {
        return bake_error(
            BakeErrorCode::unsupported,
            "is " + std::to_string(n) + " bytes, over the " + byte_size_text(cap) + " cap");
    }
    *size = n;
    return BakeError();
}

}  // namespace

std::string byte_size_text(uint64_t bytes) {
    if (bytes >= (uint64_t(1) << 30) && bytes % (uint64_t(1) << 30) == 0)
        return std::to_string(bytes >> 30) + " GiB";
    if (bytes >= (uint64_t(1) << 20) && bytes % (uint64_t(1) << 20) == 0)
        return std::to_string(bytes >> 20) + " MiB";
    return std::to_string(bytes) + " bytes";
}

BakeError check_input_file(const std::string& path, uint64_t cap, uint64_t* size) {
    assert(size != nullptr);
    struct stat st = {};
    if (::stat(path.c_str(), &st) != 0) {
        return bake_error(BakeErrorCode::io,
                          std::string("cannot open file: ") + std::strerror(errno));
    }
    return check_stat(st, cap, size);
}

BakeError read_input_file(const std::string& path, uint64_t cap,
                          std::vector<unsigned char>* bytes) {
    assert(bytes != nullptr);
    bytes->clear();
    uint64_t size = 0;
    BakeError error = check_input_file(path, cap, &size);
    if (!error.ok()) return error;
    // O_NONBLOCK: a FIFO swapped in after the check must not block the open.
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
    if (fd < 0) {
        return bake_error(BakeErrorCode::io,
                          std::string("cannot open file: ") + std::strerror(errno));
    }
    struct stat st = {};
    if (::fstat(fd, &st) != 0) {
        error =
            bake_error(BakeErrorCode::io, std::string("cannot stat file: ") + std::strerror(errno));
    } else {
        error = check_stat(st, cap, &size);
    }
    if (error.ok()) {
        bytes->resize(size_t(size));
        size_t done = 0;
        while (done < bytes->size()) {
            const ssize_t n = ::read(fd, bytes->data() + done, bytes->size() - done);
            if (n < 0 && errno == EINTR) continue;
            if (n < 0) {
                error = bake_error(BakeErrorCode::io,
                                   std::string("cannot read file: ") + std::strerror(errno));
                break;
            }
            if (n == 0) {
                error = bake_error(BakeErrorCode::io, "file shrank while it was read");
                break;
            }
            done += size_t(n);
        }
    }
    ::close(fd);
    if (!error.ok()) bytes->clear();
    return error;
}

}  // namespace stipple::bake
