// Tone on small objects (issue 7, zoom 0.25; docs/tone.md, "Small objects"). The corpus's
// assets, default bakes, 640x480, silhouettes off, each from several views (yaws 0, 30, ...,
// 330; the single-sided SimpleSkin sheet from -60 to 60, as it draws nothing from behind).
// At zoom 0.25 a target of 0.1 is 20-50 dots per view, so single views scatter by +-16%
// (few-dot noise); the checks average over the views.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "platform/headless_context.h"
#include "runtime/asset.h"
#include "runtime/frame_pipeline.h"
#include "tests/common/fixtures.h"
#include "tests/common/tone_stage.h"
#include "tools/frame_measure.h"

namespace {

using namespace stipple;

// What one view measured.
struct View {
    double tone = 0;        // mean darkness inside the mask less its outermost 2 px
    size_t pixels = 0;      // pixels of that inset mask
    double drawn_ink = 0;   // ink (pi (d/2)^2) of the dots drawn, per mask pixel
    double centre_ink = 0;  // the same for a one-texel test at the centre (the old rule)
};

// One view of the asset on `stage` measured: the inset tone, and the ink of the dots drawn and
// of those the old one-texel rule would have drawn, per mask pixel.
View shoot(test::Stage* stage, float zoom, float tone, float yaw) {
    const test::Shot shot = stage->shoot(zoom, tone, 0.0f, yaw);
    const Pipeline& p = stage->pipeline();
    const std::vector<float>& depth = stage->depth();
    const int w = test::Stage::kWidth, h = test::Stage::kHeight;
    size_t mask_pixels = 0;
    for (uint8_t in : shot.mask.inside) mask_pixels += in;
    View v;
    measure::Mask inner = shot.mask;
    const std::vector<float> distance = measure::distance_to_outside(shot.mask);
    for (size_t i = 0; i < distance.size(); ++i) inner.inside[i] = distance[i] > 2.0f;
    v.tone = measure::mean_tone(shot.image.rgba.data(), w, h, inner, &v.pixels);
    const double per_pixel = 1.0 / double(std::max<size_t>(mask_pixels, 1));
    for (const measure::Dot& d : shot.dots)
        v.drawn_ink += 0.785398 * double(d.size) * d.size * per_pixel;
    // The old rule: the one texel under the dot's centre on the object and not in front.
    for (uint32_t i = 0; i < pipeline_point_count(p); ++i) {
        if (p.size[i] <= 0.0f) continue;
        const glm::vec3 c = pipeline_project(p, i);
        const int x = int(std::floor(c.x)), y = int(std::floor(c.y));
        if (x < 0 || y < 0 || x >= w || y >= h) continue;
        const float mesh = depth[size_t(h - 1 - y) * size_t(w) + size_t(x)];
        if (mesh < 1.0f && c.z <= mesh + 1e-5f)
            v.centre_ink += 0.785398 * double(p.size[i]) * p.size[i] * per_pixel;
    }
    return v;
}

struct SmallAsset {
    const char* name;
    const char* path;  // under assets/
    float first_yaw, last_yaw;
};

void PrintTo(const SmallAsset& a, std::ostream* os) {
    *os << a.path;
}  // ctest's test names

const SmallAsset kSmall[] = {
    {"RiggedSimple", "RiggedSimple/RiggedSimple.glb", 0, 330},
    {"SimpleSkin", "SimpleSkin/SimpleSkin.gltf", -60, 60},
    {"TeapotStl", "UtahTeapot/utah_teapot_solid.stl", 0, 330},
    {"TeapotObj", "UtahTeapot/teapot.obj", 0, 330},
    {"Horse", "Horse/horse.ply", 0, 330},
    {"Spot", "Spot/spot_triangulated.obj", 0, 330},
    {"RiggedFigure", "RiggedFigure/RiggedFigure.glb", 0, 330},
};

// Views of one asset at one zoom and target, averaged.
struct Views {
    double tone = 0, lo = 1, hi = 0, drawn_ink = 0, centre_ink = 0;
    size_t pixels = 0;
};

Views shoot_views(test::Stage* stage, const SmallAsset& a, float zoom, float target) {
    Views s;
    int n = 0;
    for (float yaw = a.first_yaw; yaw <= a.last_yaw; yaw += 30.0f, ++n) {
        const View v = shoot(stage, zoom, target, yaw);
        s.tone += v.tone;
        s.lo = std::min(s.lo, v.tone);
        s.hi = std::max(s.hi, v.tone);
        s.drawn_ink += v.drawn_ink;
        s.centre_ink += v.centre_ink;
        s.pixels += v.pixels;
    }
    s.tone /= n, s.drawn_ink /= n, s.centre_ink /= n, s.pixels /= size_t(n);
    return s;
}

class SmallTone : public ::testing::TestWithParam<SmallAsset> {};

// The dots drawn at zoom 0.25 lay down, per pixel of the object, the ink they lay at zoom 1
// within 7% (averaged over the views): the dot pass's visibility test no longer drops dots
// within a pixel of the outline or on slopes (runtime/renderer_shaders.h). With the one-texel
// test of before (printed: "centre") zoom 0.25 lost 3-11% (RiggedFigure, tone 0.1: 0.0868
// against 0.0977 at zoom 1). Also the tone inside the object (mask less 2 px), averaged over
// the views: within +-10% of 0.3 and 0.6; 0.1 within +-20% (see below).
TEST_P(SmallTone, ToneHoldsAtZoomQuarter) {
    const SmallAsset& a = GetParam();
    test::Stage stage;
    std::string error;
    ASSERT_TRUE(stage.open(a.path, "", nullptr, &error)) << error;
    for (float target : {0.1f, 0.3f, 0.6f}) {
        const Views near = shoot_views(&stage, a, 1.0f, target);
        const Views small = shoot_views(&stage, a, 0.25f, target);
        std::printf(
            "%-12s tone %.1f zoom 0.25: tone %.4f (%+.1f%%, views %.4f-%.4f, %zu px); ink drawn "
            "%.4f (centre rule %.4f), zoom 1 %.4f: %+.1f%%\n",
            a.name, double(target), small.tone, 100.0 * (small.tone / target - 1.0), small.lo,
            small.hi, small.pixels, small.drawn_ink, small.centre_ink, near.drawn_ink,
            100.0 * (small.drawn_ink / near.drawn_ink - 1.0));
        ASSERT_GT(small.pixels, 300u) << a.name;
        EXPECT_NEAR(small.drawn_ink / near.drawn_ink, 1.0, 0.07) << a.name << " tone " << target;
        // Tone 0.1 at zoom 0.25 reads 7-17% low inside the object on the horse, the teapots
        // and RiggedFigure for every bake seed tried (6): not few-dot noise, and not the dot
        // pass (the ink is drawn, see above), but where it is drawn: the ink of the dots
        // centred inside the inset mask is as low, so at that tone the drawn dots crowd the
        // 2-px outline band (docs/tone.md, "Small objects").
        const double tolerance = target < 0.2f ? 0.2 : 0.1;
        EXPECT_NEAR(small.tone, target, tolerance * target) << a.name;
    }
}

std::string asset_name(const ::testing::TestParamInfo<SmallAsset>& info) {
    return info.param.name;
}

INSTANTIATE_TEST_SUITE_P(Issue7, SmallTone, ::testing::ValuesIn(kSmall), asset_name);

}  // namespace
