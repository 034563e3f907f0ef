// Stroke density under zoom with the particle tree a simplify bake stores from its own merge
// record (bake/particle_parents.h, docs/particles.md "Parents"): strokes per 1,000 object
// pixels at zoom 1, 2, 4, 8 stay within a fifth of their mean (the measure of
// test_particle_frames.cpp), as they do with the runtime's nearest-of-the-level-above tree
// built from the same bake.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "runtime/particle_frame.h"
#include "tests/common/fixtures.h"
#include "tests/common/particle_view.h"

namespace {

using namespace stipple;
using namespace stipple::test;

constexpr int kW = ParticleView::kWidth, kH = ParticleView::kHeight;

// Strokes per 1,000 object pixels of painterly-long at zoom 1, 2, 4, 8 (a static pose, six
// frames each for the fades to settle), with the asset's stored tree or, with
// `stored_tree` false, the one the runtime builds (the nearest point of the level above).
std::vector<double> densities(const std::string& path, int clip, bool stored_tree,
                              uint32_t tree_points) {
    HeadlessGl gl;
    Asset asset;
    std::string error;
    std::vector<double> d;
    EXPECT_TRUE(gl.open(&error) && load_baked(path, &asset, &error)) << error;
    EXPECT_NE(asset.particle_parent, nullptr) << path << " has no PTRE";
    if (!stored_tree) asset.particle_parent = nullptr;
    const ParticleStyle& style = *find_particle_style("painterly-long");
    auto pipeline = std::make_unique<Pipeline>();
    auto stage = std::make_unique<ParticleStage>();
    FrameConfig c;
    c.width = kW;
    c.height = kH;
    c.depth_readback = true;
    particle_style_frame_config(style, &c);
    Status st = pipeline_init(pipeline.get(), asset, gl.gl(), c);
    if (st.ok()) st = particle_stage_init(stage.get(), asset, style, kW, kH, tree_points);
    if (st.ok()) st = particle_stage_init_gl(stage.get(), gl.gl());
    EXPECT_TRUE(st.ok()) << st.message;
    std::vector<float> depth(size_t(kW) * kH), scratch(size_t(kW) * kH * 4);
    for (float zoom : {1.0f, 2.0f, 4.0f, 8.0f}) {
        if (!st.ok()) break;
        FrameConfig v = pipeline->config;
        v.zoom = zoom;
        EXPECT_TRUE(pipeline_set_view(pipeline.get(), v).ok());
        AnimationState state;
        state.clip = clip;
        state.time = 0.0f;
        for (int f = 0; f < 6; ++f)
            pipeline_particle_frame(pipeline.get(), stage.get(), state, nullptr);
        renderer_read_depth(&pipeline->renderer, scratch.data(), depth.data());
        std::vector<VisibleStroke> s(stage->stroke_count);
        s.resize(particle_visible_strokes(*pipeline, *stage, depth.data(), s.data(),
                                          uint32_t(s.size())));
        const size_t pixels =
            size_t(std::count_if(depth.begin(), depth.end(), [](float x) { return x < 1.0f; }));
        d.push_back(1000.0 * double(s.size()) / double(std::max<size_t>(pixels, 1)));
        if (const char* dir = std::getenv("STIPPLE_PARTICLE_PNG")) {  // to look at them
            std::vector<uint8_t> rgba(size_t(kW) * kH * 4);
            renderer_read_color(&pipeline->renderer, rgba.data());
            const std::string name = std::string(dir) + "/merge_" + std::to_string(stored_tree) +
                                     "_zoom" + std::to_string(int(zoom)) + ".png";
            image::write_png(name.c_str(), kW, kH, rgba.data(), true, &error);
        }
        std::printf(
            "%s, %s tree, zoom %g: %zu strokes over %zu px: %.2f per 1000 px (%u "
            "active)\n",
            path.c_str(), stored_tree ? "merge" : "nearest", zoom, s.size(), pixels, d.back(),
            stage->stats.active);
    }
    particle_stage_destroy(stage.get());
    pipeline_destroy(pipeline.get());
    return d;
}

void expect_within_a_fifth_of_the_mean(const std::vector<double>& d, const std::string& what) {
    ASSERT_EQ(d.size(), 4u) << what;
    const double mean = (d[0] + d[1] + d[2] + d[3]) / 4.0;
    for (double x : d) EXPECT_NEAR(x, mean, 0.2 * mean) << what;
}

// The bunny baked by simplify to 262,144 points, drawn from the bake alone (no temporary
// particles): every parent of the tree is the stored one, to zoom 8.
TEST(ParticleMergeTree, StrokeDensityHoldsUnderZoomWithTheStoredMergeTree) {
    const std::string bunny = baked_asset("assets/StanfordBunny/stanford-bunny.obj",
                                          "--points 262144 --method simplify --particles");
    const std::vector<double> merge = densities(bunny, -1, true, 0);
    expect_within_a_fifth_of_the_mean(merge, "bunny, merge tree");
    const std::vector<double> nearest = densities(bunny, -1, false, 0);
    expect_within_a_fifth_of_the_mean(nearest, "bunny, nearest tree");
    for (size_t z = 0; z < merge.size() && z < nearest.size(); ++z)
        EXPECT_NEAR(merge[z], nearest[z], 0.2 * nearest[z]) << "zoom " << (1 << z);
}

// CesiumMan baked by simplify (20,000 points, most of them subdivision points), with the
// default temporary particles past the bake (their parents: the runtime's rule).
TEST(ParticleMergeTree, StrokeDensityHoldsOnTheWalkerWithTemporaryParticles) {
    const std::string man =
        baked_asset("assets/CesiumMan/CesiumMan.glb", "--method simplify --particles");
    expect_within_a_fifth_of_the_mean(densities(man, 0, true, kDefaultParticleTreePoints),
                                      "CesiumMan, merge tree");
    expect_within_a_fifth_of_the_mean(densities(man, 0, false, kDefaultParticleTreePoints),
                                      "CesiumMan, nearest tree");
}

}  // namespace
