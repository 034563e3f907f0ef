// Frame checks of view-dependent particles (GI'01, runtime/particle_frame.h, issue 11): each
// style distinct and deterministic, stroke density under zoom, persistence and fades on the
// walk, smooth stroke orientation on a turntable.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include "runtime/particle_frame.h"
#include "tests/common/fixtures.h"
#include "tests/common/particle_view.h"
#include "tools/image_write.h"

namespace {

using namespace stipple;
using namespace stipple::test;

constexpr int kW = 320, kH = 240;

const char* kStyles[] = {"painterly-long", "painterly-dab", "sketch",   "cartoon",
                         "graftals",       "charcoal",      "two-tone", "ink"};

void styles_are_distinct_and_deterministic(const std::string& asset, int clip, float time) {
    std::vector<std::vector<uint8_t>> frames;
    for (const char* name : kStyles) {
        ParticleView v;
        std::string error;
        ASSERT_TRUE(v.open(asset, name, 1.0f, &error)) << error;
        for (int f = 0; f < 6; ++f) v.frame(clip, time);  // the fades settle
        const std::vector<VisibleStroke> strokes = v.frame(clip, time);
        EXPECT_GT(strokes.size(), 3u) << name;
        EXPECT_EQ(pipeline_gl_errors(v.pipeline()).count, 0u) << name;
        frames.push_back(v.rgba());
        if (const char* dir = std::getenv("STIPPLE_PARTICLE_PNG")) {  // to look at them
            std::string e;
            image::write_png((std::string(dir) + "/" + name + ".png").c_str(), kW, kH,
                             v.rgba().data(), true, &e);
        }
        ParticleView again;
        ASSERT_TRUE(again.open(asset, name, 1.0f, &error)) << error;
        for (int f = 0; f < 7; ++f) again.frame(clip, time);
        EXPECT_EQ(again.rgba(), v.rgba()) << name << " is not deterministic";
    }
    for (size_t a = 0; a < frames.size(); ++a)
        for (size_t b = a + 1; b < frames.size(); ++b)
            EXPECT_GT(changed_pixels(frames[a], frames[b]), 300u)
                << kStyles[a] << " and " << kStyles[b] << " look alike";
}

TEST(ParticleFrames, EveryStyleIsDistinctAndDeterministicOnTheWalk) {
    styles_are_distinct_and_deterministic(
        baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 20000"), 0, 0.5f);
}

TEST(ParticleFrames, EveryStyleIsDistinctAndDeterministicOnTheBunny) {
    styles_are_distinct_and_deterministic(
        baked_asset("assets/StanfordBunny/stanford-bunny.obj", ""), -1, 0.0f);
}

// Visible strokes per 1,000 object pixels.
double density(const std::vector<VisibleStroke>& strokes, size_t object_pixels) {
    return 1000.0 * double(strokes.size()) / double(std::max<size_t>(object_pixels, 1));
}

// Strokes per 1,000 object pixels at zoom 1, 2, 4, 8 of one asset (a static pose), each
// after six frames for the fades to settle. tree_points: the particle tree's size (temporary
// particles past the bake, runtime/particle_temporary.h; 0: the bake alone).
// list_points: the most listed at once (0: the whole tree); width x height: the image.
std::vector<double> densities_under_zoom(const std::string& asset, int clip, uint32_t tree_points,
                                         uint32_t list_points = 0, int width = kW,
                                         int height = kH) {
    ParticleView v;
    std::string error;
    EXPECT_TRUE(
        v.open(asset, "painterly-long", 1.0f, &error, tree_points, list_points, width, height))
        << error;
    std::vector<double> d;
    for (float zoom : {1.0f, 2.0f, 4.0f, 8.0f}) {
        v.set_view(0.0f, zoom);
        std::vector<VisibleStroke> s;
        for (int f = 0; f < 6; ++f) s = v.frame(clip, 0.0f);
        d.push_back(density(s, v.object_pixels()));
        EXPECT_LE(v.stage().stats.listed, v.stage().set.list_capacity);
        std::printf(
            "zoom %g: %zu strokes over %zu px: %.2f per 1000 px (%u active, %u listed of "
            "%u, tree %u)\n",
            zoom, s.size(), v.object_pixels(), d.back(), v.stage().stats.active,
            v.stage().stats.listed, v.stage().set.list_capacity, v.stage().set.capacity);
        const TemporaryStats& t = v.stage().temporary.stats;
        std::printf(
            "  temporary: %u shown, %u slots held, %u triangles, %llu wanted, budget x%.2f\n",
            t.shown, t.live, t.triangles, (unsigned long long)t.wanted, double(t.budget_scale));
        if (const char* dir = std::getenv("STIPPLE_PARTICLE_PNG")) {  // to look at them
            const std::string name = std::string(dir) + "/zoom" + std::to_string(int(zoom)) + "_" +
                                     std::to_string(tree_points) + "_" +
                                     std::to_string(v.object_pixels()) + ".png";
            std::string e;
            image::write_png(name.c_str(), width, height, v.rgba().data(), true, &e);
        }
    }
    return d;
}

void expect_within_a_fifth_of_the_mean(const std::vector<double>& d, const char* what) {
    const double mean = (d[0] + d[1] + d[2] + d[3]) / 4.0;
    for (double x : d) EXPECT_NEAR(x, mean, 0.2 * mean) << what;
}

TEST(ParticleFrames, StrokeDensityHoldsUnderZoom) {
    expect_within_a_fifth_of_the_mean(
        densities_under_zoom(
            baked_asset("assets/StanfordBunny/stanford-bunny.obj", "--points 262144"), -1, 0),
        "bunny, 262,144 baked points");
}

// Default bakes (20,000 points) hold the density to zoom 8 with temporary particles (GI'01
// §5); the bake alone does not (the finest level runs out).
TEST(ParticleFrames, StrokeDensityHoldsUnderZoomOnDefaultBakesWithTemporaryParticles) {
    const std::string bunny = baked_asset("assets/StanfordBunny/stanford-bunny.obj", "");
    const std::string man = baked_asset("assets/CesiumMan/CesiumMan.glb", "");
    expect_within_a_fifth_of_the_mean(densities_under_zoom(bunny, -1, kDefaultParticleTreePoints),
                                      "bunny");
    expect_within_a_fifth_of_the_mean(densities_under_zoom(man, 0, kDefaultParticleTreePoints),
                                      "CesiumMan");
    const std::vector<double> bare = densities_under_zoom(bunny, -1, 0);
    EXPECT_LT(bare[3], 0.6 * bare[0]) << "the bake alone should run out at zoom 8";
}

// At the player's 640x480 the bunny needs a tree of 4^10 particles for zoom 8 (the default
// 4^9 holds it to zoom 4), but the view lists a fraction of them: with the per-frame list
// bounded at 65,536 (particle_stage_init's list_points) both default bakes hold the density
// from zoom 1 to 8, and the listed buffers (about 150 bytes a particle) are sized by the
// list, not the tree (docs/particles.md).
TEST(ParticleFrames, StrokeDensityHoldsAt640x480WithABoundedList) {
    const std::string bunny = baked_asset("assets/StanfordBunny/stanford-bunny.obj", "");
    const std::string man = baked_asset("assets/CesiumMan/CesiumMan.glb", "");
    constexpr uint32_t kTree = 1u << 20, kList = 65536;
    expect_within_a_fifth_of_the_mean(densities_under_zoom(bunny, -1, kTree, kList, 640, 480),
                                      "bunny, 640x480");
    expect_within_a_fifth_of_the_mean(densities_under_zoom(man, 0, kTree, kList, 640, 480),
                                      "CesiumMan, 640x480");
    // A list too short for the view: nodes stay folded rather than overflow it, so the list
    // holds its bound and zoom 8 runs out as a small tree does.
    const std::vector<double> short_list = densities_under_zoom(bunny, -1, kTree, 8192, 640, 480);
    EXPECT_LT(short_list[3], 0.6 * short_list[0]) << "8,192 listed should run out at zoom 8";
}

// Issue 11's check at the player's default size and budget: temporary particles are generated
// per view (runtime/particle_temporary.h), only on the triangles in view, so the default
// budget (262,144 ids) holds both default bakes from zoom 1 to 8 at 640x480, where a budget
// spread over the whole surface held the bunny only to zoom 4 (25.3 strokes per 1,000 px at
// zoom 8, docs/particles.md). The slots the view holds stay a small part of the pool.
TEST(ParticleFrames, StrokeDensityHoldsAt640x480WithTheDefaultBudget) {
    const std::string bunny = baked_asset("assets/StanfordBunny/stanford-bunny.obj", "");
    const std::string man = baked_asset("assets/CesiumMan/CesiumMan.glb", "");
    for (const auto& [asset, clip, name] :
         {std::tuple<std::string, int, const char*>{bunny, -1, "bunny, 640x480"},
          std::tuple<std::string, int, const char*>{man, 0, "CesiumMan, 640x480"}}) {
        ParticleView v;
        std::string error;
        ASSERT_TRUE(
            v.open(asset, "painterly-long", 1.0f, &error, kDefaultParticleTreePoints, 0, 640, 480))
            << error;
        std::vector<double> d;
        for (float zoom : {1.0f, 2.0f, 4.0f, 8.0f}) {
            v.set_view(0.0f, zoom);
            std::vector<VisibleStroke> s;
            for (int f = 0; f < 6; ++f) s = v.frame(clip, 0.0f);
            d.push_back(density(s, v.object_pixels()));
            const TemporaryStats& t = v.stage().temporary.stats;
            std::printf(
                "%s, zoom %g: %.2f strokes per 1000 px; %u temporary shown, %u slots "
                "held of %u, budget x%.2f\n",
                name, zoom, d.back(), t.shown, t.live, v.stage().temporary.slots,
                double(t.budget_scale));
            EXPECT_EQ(t.budget_scale, 1.0f) << name << ": the default budget should not bind";
            EXPECT_LT(t.live, v.stage().temporary.slots / 4) << name;
            if (zoom == 8.0f) {
                EXPECT_GT(t.shown, 1000u) << name;
            }
            v.save(
                ("default_budget_" + std::to_string(clip + 1) + "_zoom" + std::to_string(int(zoom)))
                    .c_str());
        }
        expect_within_a_fifth_of_the_mean(d, name);
    }
}

// When the view needs more ranks than the slots, the spacing of every triangle is raised by
// the same factor (the coarsest ranks on screen keep their slots): the density falls evenly,
// and no slot or listed particle past the budget is taken.
TEST(ParticleFrames, ABindingTemporaryBudgetRaisesTheSpacingEvenly) {
    const std::string bunny = baked_asset("assets/StanfordBunny/stanford-bunny.obj", "");
    ParticleView v;
    std::string error;
    ASSERT_TRUE(v.open(bunny, "painterly-long", 8.0f, &error, 20000 + 1500, 0, 640, 480)) << error;
    std::vector<VisibleStroke> s;
    for (int f = 0; f < 6; ++f) s = v.frame(-1, 0.0f);
    const TemporaryStats& t = v.stage().temporary.stats;
    std::printf(
        "1,500 slots at zoom 8: %u shown, %u held, %llu wanted, spacing x%.2f, %.2f strokes "
        "per 1000 px\n",
        t.shown, t.live, (unsigned long long)t.wanted, double(t.budget_scale),
        density(s, v.object_pixels()));
    EXPECT_GT(t.budget_scale, 1.1f);
    EXPECT_LE(t.live, 1500u);
    EXPECT_GT(t.shown, 1000u);  // the budget is used, not dropped
    EXPECT_GT(t.wanted, uint64_t(t.shown));
    // Evenly: the strokes of the image's four quadrants that hold the object differ in density
    // far less than a first-come-first-served pool (all slots in the first triangles) would.
    std::vector<size_t> per(4, 0);
    for (const VisibleStroke& k : s) per[(k.x >= 320.0f) + 2 * (k.y >= 240.0f)]++;
    const size_t most = *std::max_element(per.begin(), per.end());
    const size_t least = *std::min_element(per.begin(), per.end());
    std::printf("strokes per quadrant: %zu %zu %zu %zu\n", per[0], per[1], per[2], per[3]);
    EXPECT_GT(least, most / 4);
}

// Strokes of frame b that frame a had too, by particle id.
double persistence(const std::vector<VisibleStroke>& a, const std::vector<VisibleStroke>& b) {
    std::map<uint32_t, int> in_b;
    for (const VisibleStroke& s : b) in_b[s.id] = 1;
    size_t kept = 0;
    for (const VisibleStroke& s : a) kept += in_b.count(s.id);
    return a.empty() ? 1.0 : double(kept) / double(a.size());
}

// The strokes stage 4 drew (before the GPU's depth test), as the strokes CSV lists them.
std::vector<VisibleStroke> drawn_strokes(const ParticleStage& s) {
    std::vector<VisibleStroke> out;
    for (uint32_t k = 0; k < s.stroke_count; ++k) {
        const StrokeInstance& st = s.strokes[k];
        out.push_back({s.stroke_id[k], st.x, st.y, st.angle, st.length, st.width, st.alpha});
    }
    return out;
}

struct Coherence {
    double worst = 1.0;
    size_t popped_in = 0, popped_out = 0, strokes = 0;
    void add(const std::vector<VisibleStroke>& last, const std::vector<VisibleStroke>& now,
             float opacity) {
        worst = std::min(worst, persistence(last, now));
        std::map<uint32_t, float> before, after;
        for (const VisibleStroke& s : last) before[s.id] = s.alpha;
        for (const VisibleStroke& s : now) after[s.id] = s.alpha;
        const float third = opacity / 3.0f + 1e-4f;  // a third of the style's full opacity
        for (const VisibleStroke& s : now) popped_in += !before.count(s.id) && s.alpha > third;
        for (const VisibleStroke& s : last) popped_out += !after.count(s.id) && s.alpha > third;
        strokes += now.size();
    }
};

// Two seconds of the walk at 30 fps: coherence of the strokes drawn (stage 4) and of those
// seen (after the polygon pass's depth test), optionally with visibility fades.
void walk_coherence(bool visibility_fades, Coherence* drawn, Coherence* seen) {
    ParticleView v;
    std::string error;
    ASSERT_TRUE(v.open(baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 20000"),
                       "painterly-long", 1.0f, &error))
        << error;
    if (visibility_fades) {
        ASSERT_TRUE(v.enable_visibility_fades().ok());
    }
    for (int f = 0; f < 6; ++f) v.frame(0, 0.0f);
    std::vector<VisibleStroke> last_seen = v.frame(0, 0.0f);
    std::vector<VisibleStroke> last_drawn = drawn_strokes(v.stage());
    const float opacity = v.stage().style.opacity;
    for (int f = 1; f <= 60; ++f) {
        const std::vector<VisibleStroke> now_seen = v.frame(0, float(f) / 30.0f);
        const std::vector<VisibleStroke> now_drawn = drawn_strokes(v.stage());
        drawn->add(last_drawn, now_drawn, opacity);
        seen->add(last_seen, now_seen, opacity);
        last_drawn = now_drawn;
        last_seen = now_seen;
        if (const char* dir = std::getenv("STIPPLE_PARTICLE_PNG")) {  // to look at them
            const std::string name = std::string(dir) + "/walk" + std::to_string(f) +
                                     (visibility_fades ? "_fades" : "_tested") + ".png";
            std::string e;
            image::write_png(name.c_str(), kW, kH, v.rgba().data(), true, &e);
        }
    }
    std::printf("%s: drawn: worst persistence %.3f, popped in %zu, out %zu of %zu strokes\n",
                visibility_fades ? "visibility fades" : "shader depth test", drawn->worst,
                drawn->popped_in, drawn->popped_out, drawn->strokes);
    std::printf("  seen (after the depth test): worst %.3f, popped in %zu, out %zu of %zu\n",
                seen->worst, seen->popped_in, seen->popped_out, seen->strokes);
}

TEST(ParticleFrames, StrokesPersistAndFadeOnTheWalk) {
    Coherence drawn, seen;
    walk_coherence(false, &drawn, &seen);
    EXPECT_GE(drawn.worst, 0.95);
    EXPECT_EQ(drawn.popped_in, 0u);
    EXPECT_EQ(drawn.popped_out, 0u);
}

// The walk at zoom 8 (640x480, the default budget), where most strokes are temporary
// particles generated per view: a slot keeps its id while its (triangle, rank) stays shown, so
// strokes persist by id, and the ranks that join and leave the particle set as the limbs move
// fade: no stroke of a particle new to the set shows above a third of full opacity, and none
// leaves the set while drawn above a third. (Strokes also come and go whole where their
// centres cross the image's border, which moves fast at zoom 8: stage 4 skips centres off
// the image, for baked particles as well; those are printed, not asserted.)
TEST(ParticleFrames, TemporaryStrokesPersistAndFadeOnTheWalkAtZoom8) {
    ParticleView v;
    std::string error;
    ASSERT_TRUE(v.open(baked_asset("assets/CesiumMan/CesiumMan.glb", ""), "painterly-long", 8.0f,
                       &error, kDefaultParticleTreePoints, 0, 640, 480))
        << error;
    for (int f = 0; f < 6; ++f) v.frame(0, 0.0f);
    const ParticleStage& st = v.stage();
    std::vector<VisibleStroke> last = drawn_strokes(st);
    const float third = st.style.opacity / 3.0f + 1e-4f;
    const uint32_t baked = v.asset().points.point_count;
    auto listed = [&st] {
        std::map<uint32_t, int> m;
        for (uint32_t k = 0; k < st.set.count; ++k) m[st.set.list[k]] = 1;
        return m;
    };
    std::map<uint32_t, int> was_listed = listed();
    double worst = 1.0;
    size_t temporary = 0, total = 0, joined = 0, left = 0, at_border = 0;
    for (int f = 1; f <= 30; ++f) {
        v.frame(0, float(f) / 30.0f);
        const std::vector<VisibleStroke> now = drawn_strokes(st);
        const std::map<uint32_t, int> is_listed = listed();
        worst = std::min(worst, persistence(last, now));
        std::map<uint32_t, int> before, after;
        for (const VisibleStroke& s : last) before[s.id] = 1;
        for (const VisibleStroke& s : now) after[s.id] = 1;
        for (const VisibleStroke& s : now) {
            joined += !was_listed.count(s.id) && s.alpha > third;
            at_border += was_listed.count(s.id) && !before.count(s.id) && s.alpha > third;
            temporary += s.id >= baked;
        }
        for (const VisibleStroke& s : last) {
            left += !is_listed.count(s.id) && s.alpha > third;
            at_border += is_listed.count(s.id) && !after.count(s.id) && s.alpha > third;
        }
        total += now.size();
        last = now;
        was_listed = is_listed;
    }
    std::printf(
        "walk at zoom 8: worst persistence %.3f; joining or leaving the set above a third "
        "of full opacity %zu + %zu; whole at the image border %zu; of %zu strokes (%zu "
        "temporary)\n",
        worst, joined, left, at_border, total, temporary);
    EXPECT_GT(temporary, total / 2) << "most strokes should be temporary particles";
    EXPECT_GE(worst, 0.9);
    EXPECT_EQ(joined, 0u);
    EXPECT_EQ(left, 0u);
}

// With visibility fades, what the depth test hides fades too: strokes seen persist like those
// drawn, and none appears or vanishes above a third of its opacity.
TEST(ParticleFrames, HiddenStrokesFadeWithVisibilityFades) {
    Coherence drawn, seen, tested_drawn, tested_seen;
    walk_coherence(false, &tested_drawn, &tested_seen);
    walk_coherence(true, &drawn, &seen);
    // Strokes that go behind the body still leave (after fading), so persistence by id only
    // improves (0.867 to 0.907 when measured); the pops go.
    EXPECT_GT(seen.worst, tested_seen.worst);
    EXPECT_GE(seen.worst, 0.85);
    EXPECT_GT(tested_seen.popped_in + tested_seen.popped_out, 100u);
    EXPECT_EQ(seen.popped_in, 0u);
    EXPECT_EQ(seen.popped_out, 0u);
    EXPECT_GT(seen.strokes, 10000u);
}

TEST(ParticleFrames, StrokeOrientationTurnsSmoothlyOnATurntable) {
    ParticleView v;
    std::string error;
    ASSERT_TRUE(v.open(baked_asset("assets/StanfordBunny/stanford-bunny.obj", ""), "painterly-long",
                       1.0f, &error))
        << error;
    for (int f = 0; f < 6; ++f) v.frame(-1, 0.0f);
    std::map<uint32_t, VisibleStroke> last;
    for (const VisibleStroke& s : v.frame(-1, 0.0f)) last[s.id] = s;
    float worst = 0.0f;
    size_t compared = 0;
    for (int f = 1; f <= 45; ++f) {
        v.set_view(2.0f * float(f), 1.0f);
        std::map<uint32_t, VisibleStroke> now;
        for (const VisibleStroke& s : v.frame(-1, 0.0f)) {
            now[s.id] = s;
            auto it = last.find(s.id);
            // Strokes foreshortened to a dab (length under 1.5 widths) show no direction.
            if (it == last.end() || std::min(s.size, it->second.size) < 1.5f * s.width) continue;
            // A stroke is a line: its direction counts modulo 180 degrees.
            float d = std::fmod(std::abs(s.angle - it->second.angle), 3.14159265f);
            d = std::min(d, 3.14159265f - d);
            worst = std::max(worst, d);
            ++compared;
        }
        last = now;
    }
    std::printf("worst turn %.1f degrees over %zu stroke pairs\n", worst * 57.2958f, compared);
    EXPECT_GT(compared, 1000u);
    EXPECT_LE(worst * 57.2958f, 20.0f);
}

// stipple-play --style NAME --strokes-out: the strokes CSV (id,x,y,angle,size,width,alpha,
// visible) lists what stage 4 drew; particle names are one-line errors where they do not fit.
TEST(ParticleFrames, PlayerWritesTheStrokesCsv) {
    const std::string asset = baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 20000");
    ScratchDir dir;
    std::string log;
    ASSERT_EQ(run(play_checked() + " " + asset + " --out " + dir.file("p") +
                      " --frames 3 --size 320x240 --no-apng --style two-tone --strokes-out",
                  &log),
              0)
        << log;
    std::ifstream csv(dir.file("p") + "/strokes_0002.csv");
    std::string line;
    ASSERT_TRUE(std::getline(csv, line));
    EXPECT_EQ(line, "id,x,y,angle,size,width,alpha,visible");
    size_t rows = 0, visible = 0;
    while (std::getline(csv, line)) {
        unsigned id = 0;
        float x, y, angle, size, width, alpha;
        int seen = 0;
        ASSERT_EQ(std::sscanf(line.c_str(), "%u,%f,%f,%f,%f,%f,%f,%d", &id, &x, &y, &angle, &size,
                              &width, &alpha, &seen),
                  8)
            << line;
        EXPECT_LT(id, 20000u);
        EXPECT_TRUE(x >= 0 && x < 320 && y >= 0 && y < 240) << line;
        EXPECT_TRUE(alpha > 0 && alpha <= 1.0f) << line;
        ++rows;
        visible += seen;
    }
    EXPECT_GT(rows, 50u);
    EXPECT_GT(visible, rows / 3);
    for (const char* bad : {"--strokes-out", "--style painterly",
                            "--style ink --strokes-out --path gpu --dots-out"}) {
        EXPECT_EQ(
            run(bin("stipple-play") + " " + asset + " --out " + dir.file("x") + " " + bad, &log), 1)
            << bad << ": " << log;
        EXPECT_EQ(std::count(log.begin(), log.end(), '\n'), 1) << bad << ": " << log;
    }
}

// stipple-bake --particles stores the tree (PTRE); the runtime draws the same frames from it
// as from the tree it builds itself.
TEST(ParticleFrames, TheStoredTreeIsTheOneTheRuntimeBuilds) {
    Asset stored;
    std::string error;
    ASSERT_TRUE(
        load_baked(baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 20000 --particles"),
                   &stored, &error))
        << error;
    ASSERT_NE(stored.particle_parent, nullptr);
    ParticleStage built;  // the runtime's own tree, from an asset without PTRE
    Asset plain;
    ASSERT_TRUE(
        load_baked(baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 20000"), &plain, &error))
        << error;
    ASSERT_EQ(plain.particle_parent, nullptr);
    ASSERT_TRUE(
        particle_stage_init(&built, plain, *find_particle_style("painterly-long"), kW, kH).ok());
    uint32_t same = 0;
    for (uint32_t i = 0; i < plain.points.point_count; ++i)
        same += built.tree.parent[i] == stored.particle_parent[i];
    EXPECT_GE(same, plain.points.point_count - plain.points.point_count / 1000);
    particle_stage_destroy(&built);
}

}  // namespace
