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

// Level of detail (runtime/point_clusters.h): place_points for the points list[0 ..
// list_count) only; the others' outputs are left as they were.
void place_listed_points(const PointsView& points, const uint32_t* indices, const float* positions,
                         const float* normals, const uint32_t* list, uint32_t list_count,
                         float* out_positions, float* out_normals);

// Mean distance from each point to its relevant neighbours (§4.5) in the pose given by
// point_positions; 0 for points without neighbours.
void mean_neighbour_distance(const PointsView& points, const float* point_positions,
                             float* out_distance);

// Per-point factor that turns the neighbour measure into the baked radius in the bake's (bind)
// pose, computed once at load. The measure is I2^(1/4) of the neighbour offsets' second moment
// (its square follows the local area exactly under linear deformation); points whose
// neighbours are nearly collinear use the mean neighbour distance instead (stored negated).
// Points without neighbours get 0.
void relevance_scale(const PointsView& points, const float* bind_point_positions, float* out_scale);

// Thesis Alg. 6.4: re-scales every point's relevance radius by how its relevant neighbours
// lie now: radius = scale * measure in the current pose, so the region of influence (radius^2)
// grows and shrinks with the surface area around the point. Points without neighbours keep
// `fallback_radius`.
void recompute_relevance(const PointsView& points, const float* point_positions, const float* scale,
                         const float* fallback_radius, float* out_radius);

// recompute_relevance for the points begin .. end - 1 only (a thread's range,
// runtime/point_stages.h); every point must have been placed this frame.
void recompute_relevance_range(const PointsView& points, const float* point_positions,
                               const float* scale, const float* fallback_radius, uint32_t begin,
                               uint32_t end, float* out_radius);

// recompute_relevance for the points list[0 .. list_count) only; their relevant neighbours
// must have been placed this frame.
void recompute_listed_relevance(const PointsView& points, const float* point_positions,
                                const float* scale, const float* fallback_radius,
                                const uint32_t* list, uint32_t list_count, float* out_radius);

}  // namespace stipple
