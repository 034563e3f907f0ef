// Checked reads of the bake's input files: only regular files are read, each under a size
// cap, and every refusal is one line naming the problem (callers prefix the path).
// The glTF importer's buffer files go through bake/gltf_file_access.h, which adds the
// "stay inside the model's folder" rules on top of these checks.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "bake/bake_error.h"

namespace stipple::bake {

// A model file (.gltf, .glb, .obj, .ply, .stl) larger than this is refused before it is
// read: 2 GiB, the most tinygltf can parse from memory (it takes sizes as unsigned int
// below 4 GiB, and its JSON parser needs several times the text in memory), and far beyond
// any mesh the point hierarchy can use.
constexpr uint64_t kMaxModelFileBytes = uint64_t(2) << 30;

// stat()s `path`: it must exist, be a regular file (not a directory, device, FIFO or
// socket; symlinks are followed) and hold at most `cap` bytes. *size gets its size.
// Errors: io (cannot stat), unsupported (not a regular file, over the cap).
[[nodiscard]] BakeError check_input_file(const std::string& path, uint64_t cap, uint64_t* size);

// check_input_file, then reads the whole file into *bytes (re-checked on the open
// descriptor, so a file swapped after the check is caught too). Errors as above, plus io
// for read errors (with strerror).
[[nodiscard]] BakeError read_input_file(const std::string& path, uint64_t cap,
                                        std::vector<unsigned char>* bytes);

// "2 GiB", "512 MiB", "1234 bytes": a cap for messages.
std::string byte_size_text(uint64_t bytes);

}  // namespace stipple::bake
