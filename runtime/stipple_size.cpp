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

float tone_curve(const SizeParams& params, float tone) {
    if (params.tone_gamma == 1.0f && params.tone_contrast == 1.0f) return tone;
    const float t = tone < 0.0f ? 0.0f : (tone > 1.0f ? 1.0f : tone);
    const float curved = 0.5f + (std::pow(t, params.tone_gamma) - 0.5f) * params.tone_contrast;
    return curved < 0.0f ? 0.0f : (curved > 1.0f ? 1.0f : curved);
}

float ink_for_tone(const SizeParams& params, float tone_in) {
    const float tone = tone_curve(params, tone_in);  // the identity by default (classic)
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

namespace {

// What every point's size reads once per frame.
struct SizeFrame {
    glm::vec4 row_w;  // row 3 of view_projection: the clip depth w
    float focal;
    InkTable table;
    explicit SizeFrame(const SizeParams& params)
        : row_w(params.view_projection[0][3], params.view_projection[1][3],
                params.view_projection[2][3], params.view_projection[3][3]),
          focal(focal_pixels(params)),
          table(params) {}
};

inline float stipple_size(const SizeFrame& f, const SizeParams& params, const float* positions,
                          const float* normals, const float* radius, uint32_t i) {
    const glm::vec3 p(positions[i * 3], positions[i * 3 + 1], positions[i * 3 + 2]);
    const glm::vec3 n(normals[i * 3], normals[i * 3 + 1], normals[i * 3 + 2]);
    const glm::vec3 to_eye = params.eye - p;
    const float n_dot_v = glm::dot(n, to_eye) / glm::length(to_eye);
    const float w = glm::dot(f.row_w, glm::vec4(p, 1.0f));
    if (n_dot_v <= 0.0f || w <= 0.0f) return 0.0f;
    const float r_px = radius[i] * f.focal / w;
    const float region_px = kRegionPerRadiusSquared * r_px * r_px * n_dot_v;  // §3.1.2
    const float ink = f.table.at(lighting(params, n));
    return smooth_point_size(ink, region_px, params.max_point_size, params.smooth_slope);
}

}  // namespace

void size_stipples(uint32_t count, const float* positions, const float* normals,
                   const float* radius, const SizeParams& params, float* out_size) {
    const SizeFrame frame(params);
    for (uint32_t i = 0; i < count; ++i)
        out_size[i] = stipple_size(frame, params, positions, normals, radius, i);
}

void size_listed_stipples(const uint32_t* list, uint32_t list_count, const float* positions,
                          const float* normals, const float* radius, const SizeParams& params,
                          float* out_size) {
    const SizeFrame frame(params);
    for (uint32_t j = 0; j < list_count; ++j)
        out_size[list[j]] = stipple_size(frame, params, positions, normals, radius, list[j]);
}

}  // namespace stipple
