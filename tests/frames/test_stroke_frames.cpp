// Paintstroke frame checks (issue 10, GI'98): strokes baked onto skinned surfaces ride with
// them, hide behind the body, and compose with the stipples into one image. Rendered headless
// with the CLIs; the goldens of the sketch's examples are in tests/golden/cases.txt.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>

#include "tests/common/fixtures.h"

namespace {

using namespace stipple::test;

struct Root {
    unsigned stroke;
    float x, y, sx, sy;  // drawn root, host surface point (pixels)
};

std::vector<Root> load_roots(const std::string& path) {
    std::vector<Root> roots;
    std::ifstream f(path);
    std::string line;
    std::getline(f, line);  // header
    while (std::getline(f, line)) {
        Root r;
        if (std::sscanf(line.c_str(), "%u,%f,%f,%f,%f", &r.stroke, &r.x, &r.y, &r.sx, &r.sy) == 5)
            roots.push_back(r);
    }
    return roots;
}

// Pixels whose colour differs by more than 8/255 in any channel.
size_t changed_pixels(const Image& a, const Image& b, const std::vector<uint8_t>* mask = nullptr) {
    size_t n = 0;
    for (size_t i = 0; i < a.rgba.size() / 4; ++i) {
        if (mask && !(*mask)[i]) continue;
        for (int c = 0; c < 3; ++c)
            if (std::abs(int(a.rgba[i * 4 + c]) - int(b.rgba[i * 4 + c])) > 8) {
                ++n;
                break;
            }
    }
    return n;
}

std::string play(const std::string& asset, const ScratchDir& dir, const std::string& name,
                 const std::string& args) {
    std::string log;
    const std::string out = dir.file(name);
    EXPECT_EQ(run(play_checked() + " " + asset + " --out " + out + " --no-apng " + args, &log), 0)
        << log;
    return out;
}

Image frame_png(const std::string& out, int f = 0) {
    char name[32];
    std::snprintf(name, sizeof(name), "/frame_%04d.png", f);
    Image img;
    EXPECT_TRUE(load_png(out + name, &img)) << out << name;
    return img;
}

const char* kFurBake = "--points 20000 --fur 3000";

TEST(StrokeFrames, FurRootsStayOnTheWalkingSurface) {
    const std::string asset = baked_asset("assets/CesiumMan/CesiumMan.glb", kFurBake);
    ASSERT_FALSE(asset.empty());
    ScratchDir dir;
    const std::string out =
        play(asset, dir, "walk", "--size 320x240 --frames 12 --fps 30 --yaw -60 --roots-out");
    // Per stroke, the offset between the drawn root and its host surface point (placed by the
    // stipple stage, independently) stays put from frame to frame: no sliding.
    std::map<unsigned, Root> last;
    double worst_slide = 0, worst_offset = 0;
    size_t compared = 0;
    for (int f = 0; f < 12; ++f) {
        char name[32];
        std::snprintf(name, sizeof(name), "/roots_%04d.csv", f);
        const std::vector<Root> roots = load_roots(out + name);
        ASSERT_GT(roots.size(), 2500u) << name;
        for (const Root& r : roots) {
            worst_offset = std::max(worst_offset, double(std::hypot(r.x - r.sx, r.y - r.sy)));
            auto it = last.find(r.stroke);
            if (it != last.end()) {
                const Root& p = it->second;
                const double slide =
                    std::hypot((r.x - r.sx) - (p.x - p.sx), (r.y - r.sy) - (p.y - p.sy));
                worst_slide = std::max(worst_slide, slide);
                ++compared;
            }
            last[r.stroke] = r;
        }
    }
    EXPECT_GT(compared, 25000u);
    EXPECT_LE(worst_slide, 0.5) << "a root slid against its host surface point";
    EXPECT_LE(worst_offset, 1.0) << "a root is drawn away from its host surface point";
}

TEST(StrokeFrames, FurDrawsAndIsDeterministic) {
    const std::string asset = baked_asset("assets/CesiumMan/CesiumMan.glb", kFurBake);
    ASSERT_FALSE(asset.empty());
    ScratchDir dir;
    const std::string args = "--size 320x240 --frames 1 --time 0.5";
    const Image fur = frame_png(play(asset, dir, "fur", args));
    const Image again = frame_png(play(asset, dir, "again", args));
    const Image bare = frame_png(play(asset, dir, "bare", args + " --no-strokes"));
    EXPECT_EQ(changed_pixels(fur, again), 0u);
    EXPECT_GT(changed_pixels(fur, bare), 2000u) << "the fur changed too few pixels";
}

// An object-anchored stroke placed behind the torus (tests/data/strokes_behind_torus.json) is
// hidden by it seen from the front and shows when the camera goes round to its side.
TEST(StrokeFrames, StrokesHideBehindTheBody) {
    const std::string asset = baked_asset(
        "assets/torus.obj", "--points 5000 --strokes tests/data/strokes_behind_torus.json");
    ASSERT_FALSE(asset.empty());
    ScratchDir dir;
    for (const char* yaw : {"0", "180"}) {
        const std::string args = std::string("--size 240x240 --frames 1 --tone 0 --yaw ") + yaw;
        const Image with = frame_png(play(asset, dir, std::string("with") + yaw, args));
        const Image without =
            frame_png(play(asset, dir, std::string("without") + yaw, args + " --no-strokes"));
        const size_t changed = changed_pixels(with, without);
        if (std::string(yaw) == "0")
            EXPECT_LT(changed, 20u) << "a stroke behind the torus showed through it";
        else
            EXPECT_GT(changed, 200u) << "the stroke in front of the torus did not show";
    }
}

// Stroke LOD from the hierarchy's coarse-to-fine order: with --stroke-lod, a hair draws only
// where its root point's relevance radius covers enough pixels, so zooming out thins the fur.
TEST(StrokeFrames, LodThinsTheFurWithDistance) {
    const std::string asset = baked_asset("assets/CesiumMan/CesiumMan.glb", kFurBake);
    ASSERT_FALSE(asset.empty());
    ScratchDir dir;
    long last = 1 << 30;
    long drawn[3] = {};
    int k = 0;
    for (const char* zoom : {"1", "0.5", "0.25"}) {
        std::string log;
        ASSERT_EQ(run(play_checked() + " " + asset + " --out " + dir.file(zoom) +
                          " --frames 1 --size 320x240 --no-png --no-apng --stats --stroke-lod 1.5" +
                          " --zoom " + zoom,
                      &log),
                  0)
            << log;
        const size_t at = log.find("\"strokes_drawn\": ");
        ASSERT_NE(at, std::string::npos) << log;
        drawn[k] = std::atol(log.c_str() + at + 17);
        EXPECT_LE(drawn[k], last) << "zoom " << zoom;
        last = drawn[k++];
    }
    // zoom 1: all but a few hairs (one at 320x240): roots on parts thinner than their
    // prefix's spacing have smaller regions (runtime/region_density.h) and are cut sooner.
    EXPECT_GE(drawn[0], 3000 - 10);
    EXPECT_LT(drawn[2], 3000 / 2);  // zoom 0.25: the coarser part only
}

// GI'98 eqs. 3-5 in a frame: the water stream (assets/strokes/water.json: op_min 0.35,
// op_centre 0.15, op_edge 0.85) seen from the side, drawn over black and over white. Where
// only the stream covers the background, black = a c and white = a c + (1 - a), so each
// pixel's opacity is a = 1 - (white - black). Across the stream it must run from
// op_min * op_edge at the silhouette down to op_min * op_centre at the centre (the Fresnel
// look of §5.2).
TEST(StrokeFrames, WaterStreamShowsBreadthwiseOpacity) {
    const std::string asset =
        baked_asset("assets/torus.obj", "--points 5000 --strokes assets/strokes/water.json");
    ASSERT_FALSE(asset.empty());
    ScratchDir dir;
    const std::string args = "--size 200x400 --zoom 3 --no-silhouettes --tone 0 --frames 1";
    const Image black = frame_png(play(asset, dir, "black", args + " --background 000000"));
    const Image white = frame_png(play(asset, dir, "white", args + " --background ffffff"));
    const int y = 330;  // below the torus: the stream alone over the background
    std::vector<double> alpha;
    for (int x = 60; x < black.width; ++x) {
        const size_t i = (size_t(y) * size_t(black.width) + size_t(x)) * 4;
        const double a = 1.0 - (double(white.rgba[i]) - double(black.rgba[i])) / 255.0;
        if (a > 0.02)
            alpha.push_back(a);
        else if (!alpha.empty())
            break;  // the end of the stream's run
    }
    ASSERT_GE(alpha.size(), 7u) << "the stream is too narrow to measure";
    const double edge = std::max(alpha.front(), alpha.back());
    const double centre = *std::min_element(alpha.begin() + 2, alpha.end() - 2);
    EXPECT_NEAR(edge, 0.35 * 0.85, 0.05);
    EXPECT_NEAR(centre, 0.35 * 0.15, 0.04);
    const size_t mid = std::min_element(alpha.begin(), alpha.end()) - alpha.begin();
    for (size_t k = 1; k <= mid; ++k) EXPECT_LE(alpha[k], alpha[k - 1] + 0.01) << k;  // falls
    for (size_t k = mid + 1; k < alpha.size(); ++k)
        EXPECT_GE(alpha[k], alpha[k - 1] - 0.01) << k;  // and rises again
}

}  // namespace
