#include "runtime/normal_bounds.h"

#include <algorithm>
#include <cmath>

namespace stipple {

namespace {

glm::vec3 normal(const float* normals, uint32_t v) {
    const float* n = normals + size_t(v) * 3;
    return glm::vec3(n[0], n[1], n[2]);
}

}  // namespace

float normal_cone_slope_bound(const float* normals, const uint32_t* vertices, uint32_t count,
                              const glm::vec3& lo, const glm::vec3& hi, const glm::vec3& eye) {
    glm::vec3 axis(0.0f);
    for (uint32_t j = 0; j < count; ++j) {
        const glm::vec3 n = normal(normals, vertices[j]);
        const float len = glm::length(n);
        if (!(len > 0.0f)) return 1.0f;
        axis += n / len;
    }
    const float axis_len = glm::length(axis);
    if (!(axis_len > 0.0f)) return 1.0f;
    axis /= axis_len;
    float cos_t = 1.0f;  // the widest normal's angle to the axis
    for (uint32_t j = 0; j < count; ++j) {
        const glm::vec3 n = normal(normals, vertices[j]);
        cos_t = std::min(cos_t, glm::dot(axis, n) / glm::length(n));
    }
    const glm::vec3 centre = 0.5f * (lo + hi), to_eye = eye - centre;
    const float radius = 0.5f * glm::length(hi - lo), distance = glm::length(to_eye);
    if (!(cos_t > 0.0f) || !(distance > radius * 1.01f)) return 1.0f;
    const float angle =
        std::acos(std::max(-1.0f, std::min(1.0f, glm::dot(axis, to_eye) / distance)));
    const float spread = std::acos(std::min(cos_t, 1.0f)) + std::asin(radius / distance);
    const float bound = angle > spread ? std::cos(angle - spread) : 1.0f;
    return std::min(bound + 1e-3f, 1.0f);
}

float least_lighting(const float* normals, const uint32_t* vertices, uint32_t count,
                     const SizeParams& params) {
    float lit = params.ambient;
    for (int l = 0; l < params.light_count; ++l) {
        float least = 1.0f;
        for (uint32_t j = 0; j < count && least > 0.0f; ++j) {
            const glm::vec3 n = normal(normals, vertices[j]);
            const float len = glm::length(n);
            least =
                len > 0.0f ? std::min(least, glm::dot(n, params.light_direction[l]) / len) : 0.0f;
        }
        lit += params.light_intensity[l] * std::max(least - 1e-4f, 0.0f);
    }
    return std::min(lit, 1.0f);
}

InkBound::InkBound(const SizeParams& params) {
    const InkTable table(params);
    from[InkTable::kSteps + 1] = 0.0f;
    for (int i = InkTable::kSteps; i >= 0; --i) from[i] = std::max(from[i + 1], table.ink[i]);
}

float need_bound(const float* normals, const uint32_t* vertices, uint32_t count,
                 const glm::vec3& lo, const glm::vec3& hi, const SizeParams& params,
                 const InkBound& ink) {
    return normal_cone_slope_bound(normals, vertices, count, lo, hi, params.eye) *
           ink.at(least_lighting(normals, vertices, count, params));
}

}  // namespace stipple
