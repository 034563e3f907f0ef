// Per-frame point stages that run on the CPU over flat arrays (structure of arrays).
#pragma once
#include <cstdint>

#include "runtime/asset.h"

namespace stipple {

// Thesis Alg. 6.3: each point follows its host triangle. Writes 3 floats per point into
// out_positions and a unit normal (barycentric blend of the vertex normals, i.e. Gouraud
// normals, §4.5.1) into out_normals. `positions`/`normals` are the current (skinned)
// mesh vertices, 3 floats each.
void place_points(const PointsView& points, const uint32_t* indices, const float* positions,
                  const float* normals, float* out_positions, float* out_normals);

// Thesis Alg. 6.4: the relevance radius of every point, recomputed in the current pose as
// the mean distance to its relevant neighbours (§4.5). Points without neighbours keep
// `fallback_radius`.
void recompute_relevance(const PointsView& points, const float* point_positions,
                         const float* fallback_radius, float* out_radius);

}  // namespace stipple
