// The order in which triangles receive their first extra point (runtime/point_refinement.h).
//
// On a fine mesh the run-time refinement starts with less than one extra point per triangle:
// which triangles get one first decides how even the frame looks. Taking them at random lays
// dots down like a Poisson process (16% of them closer than half the median spacing).
// Instead, at load, the triangles are ranked by farthest-point order of their first extra
// point, starting from the baked points as already placed: each next triangle is the one
// whose first point is farthest from the baked points and the points ranked before it. So the
// first extra points fill the largest holes between the baked points, and every prefix of the
// order is evenly spread (the thesis's coarse-to-fine property, §4.5, continued).
#pragma once
#include <cstdint>

namespace stipple {

// Writes phase[t] in (0, 1]: (rank of triangle t + 0.5) / triangle_count. first_points holds
// each triangle's first extra point (3 floats, bind pose); baked holds baked_count points
// (3 floats). Triangles with area <= 0 (area[t]) rank last. Uses temporary memory (load time
// only); returns false if it cannot get it.
[[nodiscard]] bool first_point_phases(uint32_t triangle_count, const float* first_points,
                                      const float* area, uint32_t baked_count, const float* baked,
                                      float* phase);

}  // namespace stipple
