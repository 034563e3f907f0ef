// Back-to-front order of tessellated paintstroke segments (the compositing of
// runtime/stroke_renderer.h): a stable LSD radix sort on the segments' eye distances, into
// caller-owned buffers, so a frame allocates nothing.
#pragma once
#include <cstdint>

#include "runtime/paintstroke.h"

namespace stipple {

// Writes the indices of mesh.segments in back-to-front order (largest depth first; equal
// depths keep their tessellation order) to `order`; `scratch` holds 2 * segment_count u32.
void sort_segments_back_to_front(const StrokeMesh& mesh, uint32_t* order, uint32_t* scratch);

// Gathers the segments' triangles in `order` into `out_indices` (mesh.index_count entries).
void gather_sorted_indices(const StrokeMesh& mesh, const uint32_t* order, uint32_t* out_indices);

}  // namespace stipple
