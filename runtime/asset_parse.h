// Internal to the asset loader (runtime/asset*.cpp): the bounds-checked section reader, the
// decoded-size budget, and the section parsers that live outside asset.cpp.
#pragma once
#include <cstddef>
#include <cstdint>

#include "runtime/asset.h"

namespace stipple::detail {

// Bounds-checked cursor over one section. Every take() checks the remaining size first,
// so a lying count can only produce an error, never an out-of-bounds view.
struct Reader {
    const uint8_t* data;
    size_t size;
    size_t at = 0;
    bool ok = true;

    template <typename T>
    const T* take(size_t count) {
        size_t align = alignof(T);
        size_t start = (at + align - 1) / align * align;
        if (!ok || start > size || count > (size - start) / sizeof(T)) {
            ok = false;
            return nullptr;
        }
        at = start + count * sizeof(T);
        return reinterpret_cast<const T*>(data + start);
    }
    uint32_t u32() {
        const uint32_t* p = take<uint32_t>(1);
        return p ? *p : 0;
    }
};

// Memory the loader may take beyond the file's own copy. Every allocation is charged here,
// with a size computed from counts already checked against the section's bytes, before it
// is made: an asset over the limit fails with LoadError::decoded_size_limit having
// allocated nothing large.
struct DecodeBudget {
    uint64_t limit = 0;
    uint64_t used = 0;
};
[[nodiscard]] Status charge(DecodeBudget* budget, uint64_t bytes, const char* section);

// A count above its limit (runtime/asset_limits.h): LoadError::count_over_limit.
[[nodiscard]] Status check_limit(const char* section, const char* what, uint64_t count,
                                 uint64_t limit);

// CLIP section (runtime/asset_clips.cpp): validates, then decodes the key values.
Status parse_clips(Reader r, uint32_t node_count, uint32_t morph_slots, DecodeBudget* budget,
                   Asset* a);
// PNTQ section (runtime/asset_points.cpp): the coded point hierarchy.
Status parse_point_stream(Reader r, uint32_t triangle_count, DecodeBudget* budget, Asset* a);
// STRK section (runtime/asset_strokes.cpp): paintstrokes, validated in place against the
// mesh, skin and point hierarchy already in `a` (parse it after them).
Status parse_strokes(Reader r, Asset* a);
// LOOK section (runtime/asset_looks.cpp): point colours, parts, creases, validated in place
// against the mesh and point hierarchy already in `a` (parse it after them).
Status parse_looks(Reader r, Asset* a);
// PTRE section (runtime/asset_particles.cpp): the particle tree, validated against the point
// hierarchy already in `a` (a parent precedes its child).
Status parse_particles(Reader r, Asset* a);
// CURV section (runtime/asset_curvature.cpp): principal curvature directions, one per point of
// the hierarchy already in `a`.
Status parse_curvature(Reader r, Asset* a);
// OCCL section (runtime/asset_occluder.cpp): the depth pass's occluder, triangles over the mesh
// already in `a`.
Status parse_occluder(Reader r, Asset* a);

}  // namespace stipple::detail
