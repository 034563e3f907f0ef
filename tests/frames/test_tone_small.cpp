// Tone on small objects (issue 7, zoom 0.25; docs/tone.md, "Small objects"). The corpus's
// assets, default bakes, 640x480, silhouettes off, each from several views (yaws 0, 30, ...,
// 330; the single-sided SimpleSkin sheet from -60 to 60, as it draws nothing from behind).
// At zoom 0.25 a target of 0.1 is 20-50 dots per view, so single views scatter by +-16%
// (few-dot noise); the checks average over the views.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
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
#include "tools/image_write.h"

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
// against 0.0977 at zoom 1). And the tone inside the object (mask less 2 px), averaged over
// the views, within +-10% of 0.1, 0.3 and 0.6, with the coarse points' regions following
// their prefix's surface density (runtime/region_density.h). With the bake's rank law alone
// tone 0.1 read 7-17% low on the horse, the teapots and RiggedFigure for every bake seed:
// sample elimination's coarsest points crowd parts thinner than their spacing (legs, ears,
// limbs: at zoom 0.25 the outline ring), and the inside got less (docs/tone.md, "Small
// objects"; DISABLED_InkByOutlineDistance prints both, ring by ring).
TEST_P(SmallTone, ToneHoldsAtZoomQuarter) {
    const SmallAsset& a = GetParam();
    test::Stage stage;  // pipeline_init applies the density regions (runtime/region_density.h)
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
        EXPECT_NEAR(small.tone, target, 0.1 * target) << a.name;
    }
}

// Diagnostic (run with --gtest_also_run_disabled_tests): where the ink of zoom 0.25 lands,
// by the distance of the dot's centre to the outline, over the views, with the radii as loaded
// (the pipeline's density regions, runtime/region_density.h; DIAG_PNG=dir writes a magnified
// view: docs/tone.md).
constexpr int kBins = 5;
int bin_of(float d) {  // 0: centre off the mask; 1: d <= 1.5; 2: <= 2.5; 3: <= 4.5; 4: beyond
    return d <= 0.0f ? 0 : d <= 1.5f ? 1 : d <= 2.5f ? 2 : d <= 4.5f ? 3 : 4;
}

struct Bins {
    double pixels[kBins] = {}, dark[kBins] = {}, seen[kBins] = {}, hidden[kBins] = {};
    double prefix[4][kBins] = {};  // front-facing baked points of prefixes 64/256/1024/all
    double dots[kBins] = {}, full[kBins] = {};
    double clump_share = 0, nn_cv = 0;  // summed over the views
};

void diag_view(test::Stage* stage, float zoom, float target, float yaw, Bins* b) {
    const test::Shot shot = stage->shoot(zoom, target, 0.0f, yaw);
    const Pipeline& p = stage->pipeline();
    const int w = test::Stage::kWidth, h = test::Stage::kHeight;
    const std::vector<float> distance = measure::distance_to_outside(shot.mask);
    const measure::Evenness even = measure::evenness(shot.dots, shot.mask);
    b->clump_share += even.clump_share, b->nn_cv += even.nn_cv;
    for (size_t i = 0; i < distance.size(); ++i) {
        if (!shot.mask.inside[i]) continue;
        const int k = bin_of(distance[i]);
        b->pixels[k] += 1;
        b->dark[k] += 1.0 - measure::luminance(shot.image.rgba.data() + i * 4);
    }
    auto bin_at = [&](float x, float y) {
        const int px = int(std::floor(x)), py = int(std::floor(y));
        if (px < 0 || py < 0 || px >= w || py >= h) return 0;
        return bin_of(distance[size_t(py) * size_t(w) + size_t(px)]);
    };
    for (const measure::Dot& d : shot.dots) {
        const int k = bin_at(d.x, d.y);
        b->seen[k] += 0.785398 * double(d.size) * d.size;
        b->dots[k] += 1;
        b->full[k] += d.size >= p.size_params.max_point_size * 0.999f;
    }
    for (const measure::Dot& d : shot.hidden)
        b->hidden[bin_at(d.x, d.y)] += 0.785398 * double(d.size) * d.size;
    const uint32_t n = p.asset->points.point_count;
    const uint32_t limits[4] = {64, 256, 1024, n};
    for (uint32_t i = 0; i < n; ++i) {
        const glm::vec3 pos(p.point_positions[i * 3], p.point_positions[i * 3 + 1],
                            p.point_positions[i * 3 + 2]);
        const glm::vec3 nrm(p.point_normals[i * 3], p.point_normals[i * 3 + 1],
                            p.point_normals[i * 3 + 2]);
        if (glm::dot(nrm, p.size_params.eye - pos) <= 0.0f) continue;
        const glm::vec3 c = pipeline_project(p, i);
        // Only points the mesh pass does not hide (centre pixel test, with a margin).
        const int px = int(std::floor(c.x)), py = int(std::floor(c.y));
        if (px < 0 || py < 0 || px >= w || py >= h) continue;
        const float mesh = stage->depth()[size_t(h - 1 - py) * size_t(w) + size_t(px)];
        if (mesh < 1.0f && c.z > mesh + 1e-3f) continue;
        const int k = bin_at(c.x, c.y);
        for (int l = 0; l < 4; ++l)
            if (i < limits[l]) b->prefix[l][k] += 1;
    }
}

// The object at zoom 0.25, tone 0.1, yaw 90, cropped and magnified 4x, into dir/<name>_<law>.png.
void write_close_up(test::Stage* stage, const char* dir, const char* name, bool density) {
    const test::Shot shot = stage->shoot(0.25f, 0.1f, 0.0f, 90.0f);
    const measure::MaskExtent e = measure::mask_extent(shot.mask);
    const int x0 = std::max(e.left - 4, 0), y0 = std::max(e.top - 4, 0);
    const int w = std::min(e.right + 5, test::Stage::kWidth) - x0;
    const int h = std::min(e.bottom + 5, test::Stage::kHeight) - y0;
    std::vector<uint8_t> out(size_t(w) * h * 64);
    for (int y = 0; y < h * 4; ++y)
        for (int x = 0; x < w * 4; ++x)
            for (int c = 0; c < 4; ++c)
                out[(size_t(y) * w * 4 + x) * 4 + c] =
                    shot.image
                        .rgba[(size_t(y0 + y / 4) * test::Stage::kWidth + x0 + x / 4) * 4 + c];
    std::string error;
    const std::string path =
        std::string(dir) + "/" + name + (density ? "_density.png" : "_rank.png");
    EXPECT_TRUE(image::write_png(path.c_str(), w * 4, h * 4, out.data(), false, &error)) << error;
}

TEST_P(SmallTone, DISABLED_InkByOutlineDistance) {
    const SmallAsset& a = GetParam();
    {
        const bool fix = true;  // the density regions (the diagnostic once compared both laws)
        test::Stage stage;
        std::string error;
        ASSERT_TRUE(stage.open(a.path, "", nullptr, &error)) << error;
        if (const char* dir = std::getenv("DIAG_PNG")) write_close_up(&stage, dir, a.name, fix);
        for (float zoom : {0.25f})
            for (float target : {0.1f, 0.3f, 0.6f}) {
                Bins b;
                int views = 0;
                for (float yaw = a.first_yaw; yaw <= a.last_yaw; yaw += 30.0f, ++views)
                    diag_view(&stage, zoom, target, yaw, &b);
                double all_pixels = 0, all_prefix[4] = {};
                for (int k = 1; k < kBins; ++k) all_pixels += b.pixels[k];
                for (int l = 0; l < 4; ++l)
                    for (int k = 0; k < kBins; ++k) all_prefix[l] += b.prefix[l][k];
                std::printf(
                    "%-12s %s zoom %.2f tone %.1f: inset %.4f (%+.1f%%), clump share %.3f, NN cv "
                    "%.3f\n",
                    a.name, fix ? "density" : "rank   ", double(zoom), double(target),
                    (b.dark[3] + b.dark[4]) / (b.pixels[3] + b.pixels[4]),
                    100.0 * ((b.dark[3] + b.dark[4]) / (b.pixels[3] + b.pixels[4]) / target - 1.0),
                    b.clump_share / views, b.nn_cv / views);
                for (int k = 1; k < kBins; ++k) {
                    const double px = std::max(b.pixels[k], 1.0);
                    std::printf(
                        "  bin %d: px %.3f  dark %.4f  seen ink %.4f  hidden %.4f  dots %.0f "
                        "full %.0f  prefix/px share 64 %.2f 256 %.2f 1k %.2f all %.2f\n",
                        k, b.pixels[k] / all_pixels, b.dark[k] / px, b.seen[k] / px,
                        b.hidden[k] / px, b.dots[k], b.full[k],
                        b.prefix[0][k] / all_prefix[0] / (b.pixels[k] / all_pixels),
                        b.prefix[1][k] / all_prefix[1] / (b.pixels[k] / all_pixels),
                        b.prefix[2][k] / all_prefix[2] / (b.pixels[k] / all_pixels),
                        b.prefix[3][k] / all_prefix[3] / (b.pixels[k] / all_pixels));
                }
            }
    }
}

std::string asset_name(const ::testing::TestParamInfo<SmallAsset>& info) {
    return info.param.name;
}

INSTANTIATE_TEST_SUITE_P(Issue7, SmallTone, ::testing::ValuesIn(kSmall), asset_name);

}  // namespace
