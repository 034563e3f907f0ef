// glTF 2.0 accessors (§3.6.2): typed, normalized, strided and sparse element data read into
// plain arrays, with every index, offset and length checked against the file, because
// tinygltf checks little beyond the JSON schema. Section numbers refer to the glTF 2.0
// specification, https://registry.khronos.org/glTF/specs/2.0/glTF-2.0.html
#pragma once
#include <tiny_gltf.h>

#include <cstddef>
#include <cstdint>
#include <vector>

#include "bake/bake_error.h"

namespace stipple::bake::gltf {

// Element formats a caller accepts: component type plus the `normalized` flag, as a bit set.
enum Format : unsigned {
    kF32 = 1u << 0,
    kI8 = 1u << 1,
    kI8N = 1u << 2,
    kU8 = 1u << 3,
    kU8N = 1u << 4,
    kI16 = 1u << 5,
    kI16N = 1u << 6,
    kU16 = 1u << 7,
    kU16N = 1u << 8,
    kU32 = 1u << 9,
};

// Every integer format, plain and normalized: KHR_mesh_quantization positions and deltas.
constexpr unsigned kAnyQuantized = kF32 | kI8 | kI8N | kU8 | kU8N | kI16 | kI16N | kU16 | kU16N;

// An accessor without a bufferView is all zeros (§3.6.2.3), so its count is not bounded by
// the file size; this caps what such an accessor may make us allocate.
constexpr size_t kMaxZeroFilledElements = size_t(1) << 24;

// Reads accessor `index` into `out` (count * components values), applying sparse
// substitution (§3.6.2.3). `type` is the required element type (TINYGLTF_TYPE_*) and
// `formats` the accepted component formats. Only 4-byte components are accepted for
// matrices, so the column padding of small matrix components (§3.6.2.4) never applies.
// Errors: malformed_input (index, type, format, ranges, sparse indices), unsupported (a
// zero-filled accessor over kMaxZeroFilledElements). Instantiated for float and uint32_t.
template <typename T>
[[nodiscard]] BakeError read_accessor(const tinygltf::Model& model, int index, int type,
                                      unsigned formats, std::vector<T>* out);

extern template BakeError read_accessor<float>(const tinygltf::Model&, int, int, unsigned,
                                               std::vector<float>*);
extern template BakeError read_accessor<uint32_t>(const tinygltf::Model&, int, int, unsigned,
                                                  std::vector<uint32_t>*);

}  // namespace stipple::bake::gltf
