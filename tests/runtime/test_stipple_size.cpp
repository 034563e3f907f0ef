// Unit tests of runtime/stipple_size.h: the smooth size rule (Alg. 3.2) with the slope
// factor, back faces, screen scale and overlapping ink.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "runtime/stipple_size.h"

namespace {

TEST(SmoothPointSize, FollowsAlgorithm32) {
    const float max_size = 3.0f, slope = 2.0f;
    const float dot_area = 3.14159265f * 1.5f * 1.5f;
    // GivenTone = dot_area / region; ratio = target / given.
    // ratio 0.5 (< 1): not drawn.
    EXPECT_FLOAT_EQ(stipple::smooth_point_size(0.25f, 0.5f * dot_area / 0.25f, max_size, slope),
                    0.0f);
    // region = 2 * dot_area / target  -> ratio 2 = smoothSlope: full size.
    EXPECT_NEAR(stipple::smooth_point_size(0.3f, 2.0f * dot_area / 0.3f, max_size, slope), 3.0f,
                1e-5);
    // ratio 1.5: halfway, (1.5 - 1) / (2 - 1) * 3 = 1.5 px.
    EXPECT_NEAR(stipple::smooth_point_size(0.3f, 1.5f * dot_area / 0.3f, max_size, slope), 1.5f,
                1e-5);
    // ratio 0.9: zero.
    EXPECT_FLOAT_EQ(stipple::smooth_point_size(0.3f, 0.9f * dot_area / 0.3f, max_size, slope),
                    0.0f);
    // Huge region: clamps to the maximum.
    EXPECT_FLOAT_EQ(stipple::smooth_point_size(0.3f, 1e6f, max_size, slope), 3.0f);
    // White tone never draws.
    EXPECT_FLOAT_EQ(stipple::smooth_point_size(0.0f, 1e6f, max_size, slope), 0.0f);
}

TEST(SmoothPointSize, InkFractionMatchesNumericIntegral) {
    // Integrate the ink of Alg. 3.2 over an evenly spread hierarchy numerically.
    const float s = 2.0f;
    double ink = 0;
    const int n = 200000;
    for (int i = 1; i <= n; ++i) {
        double x = (i - 0.5) / n;  // index / N
        double size = std::min(std::max((1.0 / x - 1.0) / (s - 1.0), 0.0), 1.0);
        ink += size * size / n;
    }
    EXPECT_NEAR(stipple::smooth_slope_ink_fraction(s), ink, 1e-4);
    EXPECT_NEAR(stipple::smooth_slope_ink_fraction(2.0f), 0.6137, 1e-3);
    EXPECT_NEAR(stipple::smooth_slope_ink_fraction(1.0f), 1.0f, 1e-6);
}

TEST(SizeStipples, SlopeFactorAndBackFacesAndScreenScale) {
    // Identity camera looking down -z from the origin is awkward; use a simple view-projection:
    // orthographic-like scale with w = 1 so pixels per unit = |row1| * H / 2.
    stipple::SizeParams params;
    params.view_projection = glm::mat4(1.0f);
    params.view_projection[1][1] = 0.1f;  // 0.1 NDC per unit -> 0.1 * 480 / 2 = 24 px per unit
    params.eye = glm::vec3(0, 0, 10);
    params.viewport_height = 480;
    // size_stipples compensates Alg. 3.2's partial dots: tone 0.3 * f(2) targets ratio 0.3
    // (without the overlap correction, tested on its own below).
    params.overlap_gain = 0.0f;
    params.constant_tone = 0.3f * stipple::smooth_slope_ink_fraction(2.0f);
    const float positions[] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
    const float c60 = 0.5f;  // cos 60 degrees
    const float normals[] = {0, 0, 1, std::sqrt(1 - c60 * c60), 0, c60, 0, 0, -1};
    // radius chosen so the facing point's ratio is exactly 1.5 (size 1.5 px).
    const float dot_area = 3.14159265f * 1.5f * 1.5f;
    const float region = 1.5f * dot_area / 0.3f;
    const float r_px = std::sqrt(region / stipple::kRegionPerRadiusSquared);
    const float r = r_px / 24.0f;
    const float radius[] = {r, r, r};
    float size[3];
    stipple::size_stipples(3, positions, normals, radius, params, size);
    EXPECT_NEAR(size[0], 1.5f, 1e-3);
    // N.V = 0.5 halves the region: ratio 0.75 -> not drawn (thesis §3.1.2).
    EXPECT_FLOAT_EQ(size[1], 0.0f);
    EXPECT_FLOAT_EQ(size[2], 0.0f);  // back-facing
    // Twice the screen scale quadruples the region: ratio 6 -> full size.
    params.view_projection[1][1] = 0.2f;
    stipple::size_stipples(3, positions, normals, radius, params, size);
    EXPECT_FLOAT_EQ(size[0], 3.0f);
    EXPECT_NEAR(size[1], 3.0f, 1e-5);  // ratio 3 > smoothSlope
}

TEST(SizeStipples, InkCoversOverlapsSoDarkTonesReachDark) {
    // Ink for tone T is T (1 + g T^p) before the smooth-slope fraction: none at g = 0, almost
    // none for light tones, more and more toward black.
    stipple::SizeParams params;
    const float f = stipple::smooth_slope_ink_fraction(params.smooth_slope);
    params.overlap_gain = 0.0f;
    EXPECT_NEAR(stipple::ink_for_tone(params, 0.6f) * f, 0.6f, 1e-6f);
    params.overlap_gain = 0.46f;
    params.overlap_power = 2.6f;
    EXPECT_NEAR(stipple::ink_for_tone(params, 0.1f) * f, 0.1f, 0.001f);
    EXPECT_NEAR(stipple::ink_for_tone(params, 0.3f) * f, 0.3f * 1.02f, 0.002f);
    EXPECT_NEAR(stipple::ink_for_tone(params, 0.9f) * f, 0.9f * 1.35f, 0.01f);
    EXPECT_NEAR(stipple::ink_for_tone(params, 1.0f) * f, 1.46f, 1e-5f);
    EXPECT_GT(stipple::ink_for_tone(params, 1.0f), stipple::ink_for_tone(params, 0.9f));
    EXPECT_EQ(stipple::ink_for_tone(params, -1.0f), 0.0f);  // clamped
    EXPECT_EQ(stipple::ink_for_tone(params, 2.0f), stipple::ink_for_tone(params, 1.0f));
    // The per-frame table agrees with the formula between its steps.
    params.constant_tone = -1.0f;
    const stipple::InkTable table(params);
    for (float lit : {0.0f, 0.13f, 0.5f, 0.77f, 1.0f}) {
        const float tone = params.dark_tone + (params.light_tone - params.dark_tone) * lit;
        EXPECT_NEAR(table.at(lit), stipple::ink_for_tone(params, tone), 2e-3f) << lit;
    }
}

}  // namespace
