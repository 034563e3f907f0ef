// The OCCL section: the depth pass's simplified occluder (bake/occluder.h; issue 9 item 5),
// triangles over a subset of the MESH section's vertices, drawn instead of the full mesh by a
// depth-only pass (runtime/renderer_occluder.cpp). Validated in place: the triangle count is
// 1 .. the mesh's triangle count, the indices fill the section exactly, each index is a mesh
// vertex and the deviation is finite and not negative.
#include <cmath>

#include "runtime/asset_parse.h"

namespace stipple::detail {

Status parse_occluder(Reader r, Asset* a) {
    const uint32_t count = r.u32();
    const float* deviation = r.take<float>(1);
    if (!r.ok || !deviation)
        return load_failure(LoadError::malformed_section,
                            "OCCL: %zu bytes, shorter than its header", r.size);
    if (count == 0) return load_failure(LoadError::zero_count, "OCCL: no triangles");
    if (count > a->mesh.triangle_count)
        return load_failure(LoadError::count_over_limit,
                            "OCCL: %u triangles, more than the mesh's %u", count,
                            a->mesh.triangle_count);
    if (!std::isfinite(*deviation) || *deviation < 0.0f)
        return load_failure(LoadError::bad_value, "OCCL: deviation %g not finite and >= 0",
                            double(*deviation));
    const uint32_t* indices = r.take<uint32_t>(size_t(count) * 3);
    if (!indices || r.at != r.size)
        return load_failure(LoadError::malformed_section,
                            "OCCL: %u triangles do not fill its %zu bytes", count, r.size);
    for (size_t i = 0; i < size_t(count) * 3; ++i)
        if (indices[i] >= a->mesh.vertex_count)
            return load_failure(LoadError::out_of_range, "OCCL: index %u >= vertex count %u",
                                indices[i], a->mesh.vertex_count);
    a->occluder_indices = indices;
    a->occluder_triangle_count = count;
    a->occluder_deviation = *deviation;
    return {};
}

}  // namespace stipple::detail
