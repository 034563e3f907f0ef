// Frame checks of the curvature orientation field (OrientationField::curvature,
// runtime/particle_transform.h; the CURV section of stipple-bake --curvature): strokes follow
// the stored principal directions, so they differ from the random field's, lie closer to
// their neighbours' directions, are deterministic, and turn smoothly on a turntable; without
// CURV a curvature style draws exactly the random field's image.
//
// Most stages here hold the asset's own points (tree_points = the point count): the curvature
// is stored for baked points only, and temporary particles take the random field.
// DefaultPlayerPathUsesTheField runs the player as it is, temporary particles included.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "runtime/particle_frame.h"
#include "tests/common/fixtures.h"
#include "tests/common/particle_view.h"
#include "tools/image_write.h"

namespace {

using namespace stipple;
using namespace stipple::test;

constexpr int kW = 320, kH = 240;

// Two strokes' directions as lines, 0 to 90 degrees apart.
float line_degrees(float a, float b) {
    float d = std::fmod(std::abs(a - b), 3.14159265f);
    return std::min(d, 3.14159265f - d) * 57.2958f;
}

// Mean angle between each stroke long enough to show a direction and its nearest such
// neighbour on screen: 45 degrees for directions without order.
double neighbour_degrees(const std::vector<VisibleStroke>& s) {
    double sum = 0.0;
    size_t n = 0;
    auto shows = [](const VisibleStroke& v) { return v.size >= 1.5f * v.width; };
    for (const VisibleStroke& a : s) {
        if (!shows(a)) continue;
        const VisibleStroke* best = nullptr;
        float best_d2 = 1e30f;
        for (const VisibleStroke& b : s) {
            const float d2 = (a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y);
            if (&a != &b && shows(b) && d2 < best_d2) best_d2 = d2, best = &b;
        }
        if (best) sum += line_degrees(a.angle, best->angle), ++n;
    }
    return n ? sum / double(n) : 90.0;
}

ParticleStyle with_field(const char* name, OrientationField field) {
    ParticleStyle s = *find_particle_style(name);
    s.field = field;
    return s;
}

struct Drawn {
    std::vector<uint8_t> rgba;
    std::vector<VisibleStroke> strokes;
};

Drawn draw(const std::string& asset, const ParticleStyle& style, const char* png) {
    ParticleView v;
    std::string error;
    EXPECT_TRUE(v.open(asset, style, 1.0f, &error, 0)) << error;  // baked points only
    Drawn d;
    if (!error.empty()) return d;
    for (int f = 0; f < 6; ++f) v.frame(0, 0.5f);  // the fades settle
    d.strokes = v.frame(0, 0.5f);
    d.rgba = v.rgba();
    v.save(png);
    return d;
}

// ink and two-tone use the curvature field (runtime/particle_style.cpp); on the walk with
// CURV their strokes follow the limbs' curvature, without it they are the random field's.
TEST(CurvatureFrames, TheFieldTurnsStrokesAlongTheFormAndOnlyWithCurv) {
    const std::string curv =
        baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 20000 --curvature");
    const std::string plain = baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 20000");
    for (const char* name : {"ink", "two-tone"}) {
        ASSERT_EQ(find_particle_style(name)->field, OrientationField::curvature) << name;
        const ParticleStyle curvature = *find_particle_style(name);
        const ParticleStyle random = with_field(name, OrientationField::random);
        const Drawn a = draw(curv, curvature, (std::string(name) + "_curvature").c_str());
        const Drawn again = draw(curv, curvature, "again");
        const Drawn b = draw(curv, random, (std::string(name) + "_random").c_str());
        const Drawn without = draw(plain, curvature, "without");
        ASSERT_GT(a.strokes.size(), 100u) << name;
        EXPECT_EQ(a.rgba, again.rgba) << name << " is not deterministic";
        EXPECT_GT(changed_pixels(a.rgba, b.rgba), 300u) << name;
        EXPECT_EQ(without.rgba, b.rgba) << name << ": without CURV it must draw the random field";
    }
}

// Strokes on the curvature field lie along their neighbours' (cross-contour hatching around
// the limbs); the random field's are 45 degrees from them on average.
TEST(CurvatureFrames, NeighbouringStrokesAlign) {
    const std::string curv =
        baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 20000 --curvature");
    const Drawn a = draw(curv, with_field("painterly-long", OrientationField::curvature),
                         "painterly-long_curvature");
    const Drawn b =
        draw(curv, with_field("painterly-long", OrientationField::random), "painterly-long_random");
    ASSERT_GT(a.strokes.size(), 150u);
    const double curved = neighbour_degrees(a.strokes), unordered = neighbour_degrees(b.strokes);
    std::printf(
        "%zu strokes: nearest neighbours %.1f degrees apart on the curvature field, "
        "%.1f on the random field\n",
        a.strokes.size(), curved, unordered);
    EXPECT_LT(curved, 0.65 * unordered);
}

// The bunny turning at 2 degrees per frame: a stroke on the curvature field turns with the
// surface, smoothly (as StrokeOrientationTurnsSmoothlyOnATurntable checks the random field).
TEST(CurvatureFrames, StrokesTurnSmoothlyOnATurntable) {
    ParticleView v;
    std::string error;
    ASSERT_TRUE(v.open(baked_asset("assets/StanfordBunny/stanford-bunny.obj", "--curvature"),
                       with_field("painterly-long", OrientationField::curvature), 1.0f, &error, 0))
        << error;
    ASSERT_NE(v.asset().points.curvature_angle, nullptr);
    for (int f = 0; f < 6; ++f) v.frame(-1, 0.0f);
    std::map<uint32_t, VisibleStroke> last;
    for (const VisibleStroke& s : v.frame(-1, 0.0f)) last[s.id] = s;
    float worst = 0.0f;
    size_t compared = 0;
    for (int f = 1; f <= 45; ++f) {
        v.set_yaw(2.0f * float(f));
        std::map<uint32_t, VisibleStroke> now;
        for (const VisibleStroke& s : v.frame(-1, 0.0f)) {
            now[s.id] = s;
            auto it = last.find(s.id);
            if (it == last.end() || std::min(s.size, it->second.size) < 1.5f * s.width) continue;
            worst = std::max(worst, line_degrees(s.angle, it->second.angle));
            ++compared;
        }
        last = now;
    }
    v.save("bunny_turntable_curvature");
    std::printf("worst turn %.1f degrees over %zu stroke pairs\n", worst, compared);
    EXPECT_GT(compared, 1000u);
    EXPECT_LE(worst, 20.0f);
}

// One frame of the walk as stipple-play draws it with its defaults (640x480, the default
// particle budget: temporary particles continue the bake), as a PNG.
Image player_frame(const std::string& asset, const char* style, const ScratchDir& dir,
                   const std::string& name) {
    const std::string out = dir.file(name);
    std::filesystem::create_directories(out);
    std::string log;
    EXPECT_EQ(run(play_checked() + " '" + asset + "' --out '" + out + "' --style " + style +
                      " --time 0.5 --frames 3 --no-apng",
                  &log),
              0)
        << log;
    Image img;
    EXPECT_TRUE(load_png(out + "/frame_0002.png", &img)) << out;
    if (const char* png = std::getenv("STIPPLE_PARTICLE_PNG"))  // to look at them
        std::filesystem::copy_file(out + "/frame_0002.png",
                                   std::string(png) + "/player_" + name + ".png",
                                   std::filesystem::copy_options::overwrite_existing);
    return img;
}

// The default path (the player, temporary particles past the bake) draws `ink` along the
// stored curvature too: a CURV asset draws differently from the same bake without CURV, and
// the same twice.
TEST(CurvatureFrames, DefaultPlayerPathUsesTheField) {
    const std::string curv =
        baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 20000 --curvature");
    const std::string plain = baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 20000");
    ScratchDir dir;
    const Image a = player_frame(curv, "ink", dir, "ink_curvature");
    const Image again = player_frame(curv, "ink", dir, "ink_curvature_again");
    const Image without = player_frame(plain, "ink", dir, "ink_plain");
    ASSERT_EQ(a.rgba.size(), size_t(640) * 480 * 4);
    ASSERT_EQ(without.rgba.size(), a.rgba.size());
    EXPECT_EQ(a.rgba, again.rgba) << "not deterministic";
    const size_t changed = changed_pixels(a.rgba, without.rgba);
    size_t ink = 0;  // dark pixels: the strokes drawn
    for (size_t i = 0; i + 3 < a.rgba.size(); i += 4) ink += a.rgba[i] < 128;
    std::printf("ink: %zu dark pixels, %zu changed without CURV\n", ink, changed);
    EXPECT_GT(ink, 1000u);
    EXPECT_GT(changed, ink / 4) << "the curvature field should move most strokes";
}

}  // namespace
