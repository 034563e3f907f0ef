#include "runtime/stipple_size.h"

#include <cmath>

namespace stipple {

float smooth_slope_ink_fraction(float s) {
    if (s <= 1.0001f) return 1.0f;
    return 1.0f / s + (s - 2.0f * std::log(s) - 1.0f / s) / ((s - 1.0f) * (s - 1.0f));
}

float focal_pixels(const SizeParams& params) {
    // Row 1 of view_projection is P[1][1] times the view's unit up axis, so its length is
    // P[1][1]; focal = P[1][1] * H / 2.
    const glm::mat4& m = params.view_projection;
    return glm::length(glm::vec3(m[0][1], m[1][1], m[2][1])) * params.viewport_height * 0.5f;
}

float ink_for_tone(const SizeParams& params, float tone) {
    const float t = tone < 0.0f ? 0.0f : (tone > 1.0f ? 1.0f : tone);
    const float ink = t * (1.0f + params.overlap_gain * std::pow(t, params.overlap_power));
    return ink / smooth_slope_ink_fraction(params.smooth_slope);
}

InkTable::InkTable(const SizeParams& params) {
    for (int i = 0; i <= kSteps; ++i) {
        const float lit = float(i) / kSteps;
        const float tone = params.constant_tone >= 0.0f
                               ? params.constant_tone
                               : params.dark_tone + (params.light_tone - params.dark_tone) * lit;
        ink[i] = ink_for_tone(params, tone);
    }
}

void size_stipples(uint32_t count, const float* positions, const float* normals,
                   const float* radius, const SizeParams& params, float* out_size) {
    // Row 3 of view_projection gives the clip depth w.
    const glm::mat4& m = params.view_projection;
    const glm::vec4 row_w(m[0][3], m[1][3], m[2][3], m[3][3]);
    const float focal = focal_pixels(params);
    const InkTable table(params);
    for (uint32_t i = 0; i < count; ++i) {
        const glm::vec3 p(positions[i * 3], positions[i * 3 + 1], positions[i * 3 + 2]);
        const glm::vec3 n(normals[i * 3], normals[i * 3 + 1], normals[i * 3 + 2]);
        const glm::vec3 to_eye = params.eye - p;
        const float n_dot_v = glm::dot(n, to_eye) / glm::length(to_eye);
        const float w = glm::dot(row_w, glm::vec4(p, 1.0f));
        if (n_dot_v <= 0.0f || w <= 0.0f) {
            out_size[i] = 0.0f;
            continue;
        }
        const float r_px = radius[i] * focal / w;
        const float region_px = kRegionPerRadiusSquared * r_px * r_px * n_dot_v;  // §3.1.2
        const float ink = table.at(lighting(params, n));
        out_size[i] = smooth_point_size(ink, region_px, params.max_point_size, params.smooth_slope);
    }
}

}  // namespace stipple
