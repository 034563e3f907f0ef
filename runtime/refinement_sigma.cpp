#include "runtime/refinement_sigma.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <glm/gtc/type_ptr.hpp>

#include "runtime/point_simd.h"

namespace stipple {

// With G and P the bind and posed Gram matrices, sigma^2 solves det(P - s G) = 0: s^2 det G -
// s b + det P = 0, b = p11 g22 + p22 g11 - 2 p12 g12; the larger root. The AVX2 kernel
// (triangle_sigma2_avx2) repeats these operations in this order.
float refinement_sigma2(const uint32_t* indices, const float* posed, const float* bind_gram,
                        uint32_t t) {
    const uint32_t* tri = indices + size_t(t) * 3;
    const glm::dvec3 a = glm::make_vec3(posed + size_t(tri[0]) * 3);
    const glm::dvec3 e1 = glm::dvec3(glm::make_vec3(posed + size_t(tri[1]) * 3)) - a;
    const glm::dvec3 e2 = glm::dvec3(glm::make_vec3(posed + size_t(tri[2]) * 3)) - a;
    const double p11 = glm::dot(e1, e1), p12 = glm::dot(e1, e2), p22 = glm::dot(e2, e2);
    const float* g = bind_gram + size_t(t) * 3;
    const double g11 = g[0], g12 = g[1], g22 = g[2];
    const double det = g11 * g22 - g12 * g12;
    if (!(det > 1e-10 * (g11 + g22) * (g11 + g22))) return INFINITY;
    const double b = p11 * g22 + p22 * g11 - 2.0 * p12 * g12;
    const double disc = std::max(b * b - 4.0 * det * (p11 * p22 - p12 * p12), 0.0);
    const double s = (b + std::sqrt(disc)) / (2.0 * det);
    return s == s ? float(s * (1.0 + 1e-5)) : INFINITY;
}

void refinement_sigma2_listed(const uint32_t* triangles, uint32_t count, const uint32_t* indices,
                              const float* posed, const float* bind_gram, float* sigma) {
    uint32_t j = 0;
    if (has_avx2(point_simd()))
        j = triangle_sigma2_avx2(triangles, count, indices, posed, bind_gram, sigma);
    for (; j < count; ++j)
        sigma[triangles[j]] = refinement_sigma2(indices, posed, bind_gram, triangles[j]);
}

}  // namespace stipple
