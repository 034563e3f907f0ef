// What files a glTF may make the bake read (glTF 2.0 §3.6.1 buffers, §3.8 images): tinygltf's
// default file callbacks read any path a URI names (`../../etc/passwd`, `/etc/shadow`, a
// symlink to anywhere, `/dev/zero`) and expand `~` and `$VAR` with wordexp. These callbacks
// replace them for one load:
//   - a URI is resolved only inside the model's folder: no absolute path, no `..` that
//     climbs above the folder, and its realpath (symlinks resolved) must still lie inside
//     the folder's realpath; no expansion of any kind;
//   - only regular files, each at most kMaxGltfExternalFileBytes, all of them together at
//     most kMaxGltfExternalTotalBytes; checked with stat() before a byte is read;
//   - nothing is ever written.
// A refused URI is recorded with a one-line reason; gltf_import reports it in place of
// tinygltf's "File not found". Data URIs are capped by check_data_uris before parsing.
#pragma once
#include <tiny_gltf.h>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "bake/bake_error.h"

namespace stipple::bake::gltf {

// One external buffer or image file: 1 GiB (a glTF buffer's byteLength is read as an int
// by tinygltf's accessors anyway, and a bake of more than ~50 M triangles is out of reach).
constexpr uint64_t kMaxGltfExternalFileBytes = uint64_t(1) << 30;
// All external files of one model together: 2 GiB.
constexpr uint64_t kMaxGltfExternalTotalBytes = uint64_t(2) << 30;
// One data URI's text: 256 MiB (about 192 MiB decoded). tinygltf's base64 decoding needs
// about 7.5 times the text in memory and ~0.1 s per MiB, so this bounds a data URI at
// about 2 GB and half a minute; bigger buffers belong in a .bin file.
constexpr uint64_t kMaxGltfDataUriBytes = uint64_t(256) << 20;

// Base colour textures (stipple-bake --looks; bake/gltf_materials.cpp): an image is decoded
// only if each side is at most kMaxTextureSide pixels and all decoded images together stay
// within kMaxTextureBytes (RGBA8); stb_image's header is read first, so a small file
// claiming a huge image allocates nothing. A larger image is skipped with a warning. The
// import copies each used texture out of tinygltf's model, so the peak is at most twice this.
constexpr uint64_t kMaxTextureSide = 16384;
constexpr uint64_t kMaxTextureBytes = uint64_t(1) << 30;

class FileAccess {
  public:
    // `model_path` is the .gltf/.glb file; its folder is the only one URIs may name.
    explicit FileAccess(const std::string& model_path);

    // The folder passed to tinygltf as base_dir (never empty, no trailing '/').
    const std::string& base_dir() const { return base_dir_; }
    tinygltf::FsCallbacks callbacks();

    // The reason a URI named in tinygltf's error `error` was refused; empty if none was.
    std::string refusal_in(const std::string& error) const;

  private:
    static bool exists(const std::string& path, void* self);
    static std::string expand(const std::string& path, void* self);
    static bool read(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                     void* self);
    static bool write(std::string* err, const std::string& path,
                      const std::vector<unsigned char>& bytes, void* self);

    // Applies the rules to a path tinygltf built as base_dir + "/" + URI: on success the
    // file's realpath and size, else a refusal (recorded) or a plain "not found".
    bool resolve(const std::string& path, std::string* real, uint64_t* size);
    void refuse(const std::string& uri, const std::string& why);

    std::string base_dir_;
    std::string folder_real_;  // realpath of base_dir_, empty if it cannot be resolved
    uint64_t total_ = 0;
    std::vector<std::pair<std::string, std::string>> refusals_;  // (URI, reason)
};

// Refuses a glTF whose JSON text (`json`, the whole .gltf or a GLB's JSON chunk) holds a
// data URI longer than `cap` bytes, before tinygltf decodes it. Errors: unsupported.
[[nodiscard]] BakeError check_data_uris(const unsigned char* json, size_t size,
                                        uint64_t cap = kMaxGltfDataUriBytes);

}  // namespace stipple::bake::gltf
