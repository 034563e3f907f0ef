// What a part of the surface's vertex normals bound for every point placed on it (issue 9:
// the level of detail's cut, runtime/point_clusters.h, and the refinement's early-out,
// runtime/refinement_cull.h): the size rule's slope factor N.V (thesis §3.1.2) and its ink
// (§8.4's tone from lighting, runtime/stipple_size.h).
//
// A point placed on the part (Alg. 6.3) has a Gouraud normal that blends the vertex normals
// with weights >= 0. So:
//   - it lies in their cone: axis a (the unit normals' normalised sum), half-angle t (the
//     widest of them), when t < 90 degrees. The point lies in the box [lo, hi], so its
//     direction to the eye lies within f of the direction from the box's centre (sin f = box
//     radius / distance); the angle between N and V is at least the axis' angle to that
//     direction less t + f, and N.V at most its cosine;
//   - its N.L per light is at least the least N.L of the unit vertex normals (when that is
//     >= 0), so its lighting is at least theirs and its ink at most the ink table's largest
//     entry from there up (whatever shape the tone curve gives the table).
// Both hold only for single-sided surfaces with barycentric weights in [0, 1] (a double-sided
// point's normal turns toward the eye): the callers check.
#pragma once
#include <cstdint>
#include <glm/glm.hpp>

#include "runtime/stipple_size.h"

namespace stipple {

// N.V over points on the triangles whose vertices are vertices[0 .. count) (normals: 3 floats
// per vertex, any length) inside the box [lo, hi], plus 1e-3 of slack for the float
// arithmetic, at most 1. 1 where there is no cone (a zero normal, t >= 90 degrees) or the eye
// is inside the box's sphere.
float normal_cone_slope_bound(const float* normals, const uint32_t* vertices, uint32_t count,
                              const glm::vec3& lo, const glm::vec3& hi, const glm::vec3& eye);

// The least lighting (stipple_size.h's lighting()) of such points, with 1e-4 of slack per light.
float least_lighting(const float* normals, const uint32_t* vertices, uint32_t count,
                     const SizeParams& params);

// The same bounds in two passes over a part's vertices read as vertex pairs (x y z |n| nx ny nz
// 1/|n|, runtime/point_simd.h's pair_vertices: one cache line per vertex for position, normal
// and the normal's length, taken once per vertex, not once per part that holds it),
// for the level of detail's clusters (runtime/point_clusters_select.cpp), with the box of the
// positions taken in the first pass and the back-face test in the second.
struct PartBounds {
    glm::vec3 lo{1e30f}, hi{-1e30f};  // box of the positions
    glm::vec3 axis{0.0f};             // sum of the unit normals (the cone's axis, not normalised)
    bool cone = true;                 // every normal has a length
    float least[kMaxLights] = {};     // per light: the least N.L of the unit normals (<= 1)
};
// Pass 1: box, axis and least N.L per light.
void part_bounds(const float* pairs, const uint32_t* vertices, uint32_t count,
                 const SizeParams& params, PartBounds* out);
// least_lighting from pass 1.
float part_least_lighting(const PartBounds& b, const SizeParams& params);
// Pass 2: whether every normal faces away from every point of the box (the size rule's N.V < 0
// for every point placed on the part; with faces_away's tolerance, runtime/point_clusters.h)
// and, when `cone_wanted`, normal_cone_slope_bound from the axis of pass 1.
struct PartFacing {
    bool away = true;
    float slope = 1.0f;
};
PartFacing part_facing(const float* pairs, const uint32_t* vertices, uint32_t count,
                       const PartBounds& b, const glm::vec3& eye, bool cone_wanted);

// The largest ink the size rule can ask for where lighting is at least `lit`.
struct InkBound {
    float from[InkTable::kSteps + 2];
    explicit InkBound(const SizeParams& params);
    float at(float lit) const {
        const int i = lit > 0.0f ? glm::min(int(lit * InkTable::kSteps), InkTable::kSteps) : 0;
        return from[i];
    }
};

// The size rule's N.V times ink at most, on such points: the refinement's need.
float need_bound(const float* normals, const uint32_t* vertices, uint32_t count,
                 const glm::vec3& lo, const glm::vec3& hi, const SizeParams& params,
                 const InkBound& ink);

}  // namespace stipple
