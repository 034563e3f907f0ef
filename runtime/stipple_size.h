// Stipple sizing: target tone -> dot diameter in pixels (thesis ch. 3).
#pragma once
#include <cstdint>
#include <glm/glm.hpp>

#include "runtime/frame_config.h"

namespace stipple {

// The pipeline fills the frame settings here from its resolved FrameConfig; the initialisers
// are the defaults of runtime/frame_config.h's table, for callers that size points directly.
struct SizeParams {
    glm::mat4 view_projection = glm::mat4(1.0f);
    glm::vec3 eye = glm::vec3(0.0f);                                // camera position (world)
    float viewport_height = float(kFrameSettings.height.fallback);  // pixels
    float max_point_size = kFrameSettings.max_point_size.fallback;  // MaximumPtSize, pixels
    float smooth_slope = kFrameSettings.smooth_slope.fallback;      // Alg. 3.2's smoothSlope, > 1
    float constant_tone = kFrameSettings.constant_tone.fallback;    // in [0,1]; < 0: Lambert
    // Directional lights in the points' space (towards the light, unit) and their intensities,
    // plus ambient: lighting(n) = ambient + sum intensity max(N.L, 0), clamped to [0, 1].
    int light_count = 1;
    glm::vec3 light_direction[kMaxLights] = {glm::vec3(0.0f, 0.0f, 1.0f)};
    float light_intensity[kMaxLights] = {1.0f};
    float ambient = 0.0f;
    // Target tone where N.L <= 0: the darkest tone lighting asks for (thesis §8.4's limit).
    float dark_tone = kFrameSettings.dark_tone.fallback;
    float light_tone = 0.0f;  // target tone where N.L = 1
    // Tone curve (FrameConfig::tone_gamma, tone_contrast): T -> 0.5 + (T^gamma - 0.5) contrast,
    // clamped to [0, 1], on the target tone before the size rule; 1, 1 leaves T untouched.
    float tone_gamma = kFrameSettings.tone_gamma.fallback;
    float tone_contrast = kFrameSettings.tone_contrast.fallback;
    // Dots overlap as tone rises, so ink laid down is not darkness seen. Ink asked for tone T
    // is T (1 + overlap_gain T^overlap_power): 2% more at 0.3, 12% at 0.6, 35% at 0.9, 46% at
    // 1 (overlap_gain 0 turns it off). Fitted to tone measured over the corpus at zoom 0.25 to
    // 16 (docs/tone.md); a Poisson law -ln(1 - T) would ask for far too much at mid tones,
    // since evenly spread dots overlap much less than random ones.
    float overlap_gain = 0.46f;
    float overlap_power = 2.6f;
};

// A normal's lighting under the params' lights, in [0, 1] (1 = fully lit: white).
inline float lighting(const SizeParams& params, const glm::vec3& n) {
    float lit = params.ambient;
    for (int k = 0; k < params.light_count; ++k)
        lit += params.light_intensity[k] * glm::max(glm::dot(n, params.light_direction[k]), 0.0f);
    return lit < 1.0f ? lit : 1.0f;
}

// Pixels per world unit at clip depth w is focal / w.
float focal_pixels(const SizeParams& params);

// The tone curve of `params` applied to a target tone in [0, 1] (gamma > 1 lightens, contrast
// > 1 spreads tones away from 0.5); exactly `tone` for the identity curve.
float tone_curve(const SizeParams& params, float tone);

// Ink (summed dot area per screen area) the size rule must lay down for tone T in [0, 1]:
// the tone curve, overlap correction, then the smooth-slope ink fraction (see
// smooth_slope_ink_fraction).
float ink_for_tone(const SizeParams& params, float tone);

// Ink as a function of N.L in [0, 1] (constant when the tone is), tabulated once per frame so
// per-point loops do no logarithm.
struct InkTable {
    static constexpr int kSteps = 32;
    float ink[kSteps + 1];
    explicit InkTable(const SizeParams& params);
    float at(float n_dot_l) const {
        // Clamped to [0, 1]; NaN (a pose gone non-finite) reads as 0, not as an index.
        const float x = (n_dot_l > 0.0f ? (n_dot_l < 1.0f ? n_dot_l : 1.0f) : 0.0f) * kSteps;
        const int i = glm::min(int(x), kSteps - 1);
        return ink[i] + (ink[i + 1] - ink[i]) * (x - float(i));
    }
};

// Area of a point's region of influence per squared relevance radius. Measured on baked
// hierarchies (surface area / number of points at a level, over r^2 of the level's last
// point): 0.98-1.08 for simplification levels of CesiumMan; the bake scales bisection radii
// to match (bake/point_hierarchy.cpp).
constexpr float kRegionPerRadiusSquared = 1.0f;

// Alg. 3.2 draws points whose tone ratio lies in [1, smoothSlope] at partial size, so on an
// evenly spread hierarchy (region of the i-th point = A / i) the ink laid down is
// f(s) * targetTone with f(s) = 1/s + (s - 2 ln s - 1/s) / (s - 1)^2 (0.614 for s = 2).
// size_stipples divides the target tone by f(s) so the drawn tone matches the target.
float smooth_slope_ink_fraction(float smooth_slope);

// Thesis Alg. 3.2 (smooth point rendering) from a point's tone ratio TargetTone / GivenTone:
// ratios in [1, smoothSlope] give partial size, inv_slope = 1 / (smoothSlope - 1).
inline float smooth_size_from_ratio(float ratio, float max_point_size, float inv_slope) {
    float s = (ratio - 1.0f) * inv_slope;
    s = s < 0.0f ? 0.0f : (s > 1.0f ? 1.0f : s);
    return s * max_point_size;
}

// Alg. 3.2 for one point: the diameter in pixels, from its target tone and the screen area of
// its region of influence (GivenTone = dot area / region).
inline float smooth_point_size(float target_tone, float region_px, float max_point_size,
                               float smooth_slope) {
    const float dot_area = 0.785398163f * max_point_size * max_point_size;  // pi (d/2)^2
    return smooth_size_from_ratio(target_tone * region_px / dot_area, max_point_size,
                                  1.0f / (smooth_slope - 1.0f));
}

// What every point's size reads once per frame (the scalar code and the AVX2 kernels of
// runtime/point_simd.h alike).
struct SizeFrame {
    const SizeParams* params;
    float row_w[4];             // row 3 of view_projection: the clip depth w
    float focal;                // focal_pixels(params)
    float dot_area_per_region;  // pi (MaximumPtSize / 2)^2 / kRegionPerRadiusSquared
    float inv_slope;            // 1 / (smoothSlope - 1)
    InkTable table;
    explicit SizeFrame(const SizeParams& params);
};

// Sizes every point: target tone (constant, or Lambert from one directional light) turned into
// ink by ink_for_tone, the region of influence projected to the screen (§3.1.1: radius times pixels
// per unit at the point's depth, squared) and reduced by the slope factor N.V (§3.1.2), then
// Alg. 3.2. Back-facing points get size 0.
void size_stipples(uint32_t count, const float* positions, const float* normals,
                   const float* radius, const SizeParams& params, float* out_size);

// size_stipples for the points list[0 .. list_count) only (level of detail,
// runtime/point_clusters.h); the others' sizes are left as they were.
void size_listed_stipples(const uint32_t* list, uint32_t list_count, const float* positions,
                          const float* normals, const float* radius, const SizeParams& params,
                          float* out_size);

}  // namespace stipple
