// Double-sided surfaces (issue 7, item 5): points on double-sided triangles (glTF
// material.doubleSided, or stipple-bake --double-sided on) draw from both sides. After
// placement (thesis Alg. 6.3) a point's Gouraud normal (§4.5.1) may face away from the eye;
// on a double-sided host it is turned toward the viewer, so the size stage (Alg. 3.2) sees a
// front-facing point with the right slope factor |N.V| (§3.1.2) and lights the side that is
// seen. Single-sided points are left alone: their back faces stay undrawn.
#pragma once
#include <cstdint>
#include <glm/glm.hpp>

#include "runtime/asset.h"

namespace stipple {

// At load: out_flags[i] = 1 if point i's host triangle is double-sided (triangle_double_sided
// from SidesView, one byte per triangle). Returns the number of flagged points.
uint32_t double_sided_point_flags(uint32_t count, const uint32_t* host_triangle,
                                  const uint8_t* triangle_double_sided, uint8_t* out_flags);

// Per frame, after placement: every flagged point whose normal points away from the eye
// (N . (eye - p) < 0) gets its normal negated. flags == nullptr (no double-sided triangle)
// does nothing. Returns the number of normals turned.
uint32_t face_double_sided_points(uint32_t count, const uint8_t* flags, const float* positions,
                                  float* normals, const glm::vec3& eye);

// The same for the points list[0 .. list_count) only (level of detail).
uint32_t face_listed_double_sided_points(const uint32_t* list, uint32_t list_count,
                                         const uint8_t* flags, const float* positions,
                                         float* normals, const glm::vec3& eye);

}  // namespace stipple
