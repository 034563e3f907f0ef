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

SizeFrame::SizeFrame(const SizeParams& p)
    : params(&p),
      row_w{p.view_projection[0][3], p.view_projection[1][3], p.view_projection[2][3],
            p.view_projection[3][3]},
      focal(focal_pixels(p)),
      dot_area_per_region(0.785398163f * p.max_point_size * p.max_point_size /
                          kRegionPerRadiusSquared),
      inv_slope(1.0f / (p.smooth_slope - 1.0f)),
      table(p) {}

namespace {

// One point's size (Thesis §3.1.1, §3.1.2, Alg. 3.2) with its three divides folded into one:
// the region of influence on the screen is kRegion (r focal / w)^2 N.V, N.V = N.(eye - p) /
// |eye - p|, and Alg. 3.2's ratio TargetTone / GivenTone = ink region / dot area, so
//   ratio = ink (r focal)^2 N.(eye - p) / (w^2 |eye - p| dot area / kRegion).
// Back-facing points (N.(eye - p) <= 0) and points behind the eye (w <= 0) get size 0. The AVX2
// kernel (runtime/point_simd_avx2.cpp) does these operations in this order.
inline float stipple_size(const SizeFrame& f, const glm::vec3& p, const glm::vec3& n,
                          float radius) {
    const SizeParams& params = *f.params;
    const glm::vec3 to_eye = params.eye - p;
    const float n_dot_t = glm::dot(n, to_eye);
    // glm::dot(vec4(p, 1)): (x + y) + (z + w), w's product row_w[3] * 1.
    const float w = (f.row_w[0] * p.x + f.row_w[1] * p.y) + (f.row_w[2] * p.z + f.row_w[3]);
    if (n_dot_t <= 0.0f || w <= 0.0f) return 0.0f;
    const float rf = radius * f.focal;
    const float ink = f.table.at(lighting(params, n));
    const float ratio = ink * (rf * rf) * n_dot_t /
                        ((w * w) * (std::sqrt(glm::dot(to_eye, to_eye)) * f.dot_area_per_region));
    return smooth_size_from_ratio(ratio, params.max_point_size, f.inv_slope);
}

inline float size_of(const SizeFrame& f, const float* positions, const float* normals,
                     const float* radius, uint32_t i) {
    const glm::vec3 p(positions[i * 3], positions[i * 3 + 1], positions[i * 3 + 2]);
    const glm::vec3 n(normals[i * 3], normals[i * 3 + 1], normals[i * 3 + 2]);
    return stipple_size(f, p, n, radius[i]);
}

}  // namespace

void size_stipples(uint32_t count, const float* positions, const float* normals,
                   const float* radius, const SizeParams& params, float* out_size) {
    const SizeFrame frame(params);
    for (uint32_t i = 0; i < count; ++i)
        out_size[i] = size_of(frame, positions, normals, radius, i);
}

void size_listed_stipples(const uint32_t* list, uint32_t list_count, const float* positions,
                          const float* normals, const float* radius, const SizeParams& params,
                          float* out_size) {
    const SizeFrame frame(params);
    for (uint32_t j = 0; j < list_count; ++j)
        out_size[list[j]] = size_of(frame, positions, normals, radius, list[j]);
}

}  // namespace stipple
