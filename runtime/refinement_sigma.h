// The refinement cull's stretch factor (runtime/refinement_cull.h): the posed map is affine on
// each render triangle, so a segment inside one stretches at most by the largest singular value
// sigma of its map from bind to posed pose (thesis §4.5's refinement under deformation; the
// cull's bound on a domain edge's posed length, L g).
#pragma once
#include <cstdint>

namespace stipple {

// sigma^2 of render triangle t: the largest generalised eigenvalue of its posed Gram matrix
// (from `posed`, 3 floats per vertex, and `indices`, 3 per triangle) against its bind one
// (`bind_gram`: e1.e1, e1.e2, e2.e2 per triangle), in double, a little above (1 + 1e-5); +inf
// where the bind triangle has no area or the result is not a number.
float refinement_sigma2(const uint32_t* indices, const float* posed, const float* bind_gram,
                        uint32_t t);

// refinement_sigma2 of each listed triangle into sigma[triangles[j]]: 4 a step with AVX2 where
// runtime/point_simd.h chose it (the same bits), the rest one by one.
void refinement_sigma2_listed(const uint32_t* triangles, uint32_t count, const uint32_t* indices,
                              const float* posed, const float* bind_gram, float* sigma);

}  // namespace stipple
