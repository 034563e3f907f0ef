// The refinement's early-out (runtime/refinement_cull.h) is exact: over random views, zooms,
// poses and tones on the CesiumMan walk, the culled refinement (only the clusters the test
// leaves active, their corners placed) gives byte for byte the points the full stage gives
// with every baked point placed, and where it skips every cluster the full stage adds none;
// with relevance updates, after the posed-area test (refinement_cull_posed) too.
// Far views skip clusters (whole frames), close-ups add points.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "runtime/double_sided.h"
#include "runtime/frame_pipeline.h"
#include "runtime/point_placement.h"
#include "runtime/point_refinement.h"
#include "runtime/refinement_cull.h"
#include "tests/common/fixtures.h"
#include "tests/common/refined_points_buffer.h"

namespace {

using Extra = stipple::test::RefinedPointsBuffer;

bool same(const float* a, const float* b, size_t n) {
    return n == 0 || std::memcmp(a, b, n * 4) == 0;  // (empty vectors' data() may be null)
}

bool same_points(const Extra& a, const Extra& b) {
    const uint32_t n = a.out.count;
    const bool same_hosts =
        n == 0 || (std::memcmp(a.triangle.data(), b.triangle.data(), size_t(n) * 4) == 0 &&
                   std::memcmp(a.index.data(), b.index.data(), size_t(n) * 4) == 0);
    return n == b.out.count && same(a.positions.data(), b.positions.data(), size_t(n) * 3) &&
           same(a.normals.data(), b.normals.data(), size_t(n) * 3) &&
           same(a.radius.data(), b.radius.data(), n) && same_hosts &&
           a.stats.wanted == b.stats.wanted && a.stats.budget_scale == b.stats.budget_scale;
}

class RefinementCull : public ::testing::Test {
  protected:
    void SetUp() override {
        std::string error;
        ASSERT_TRUE(load("assets/CesiumMan/CesiumMan.glb", "--points 20000", &asset_));
        ASSERT_TRUE(gl_.open(&error)) << error;
    }
    static bool load(const char* input, const char* options, stipple::Asset* out) {
        std::string error;
        const bool ok =
            stipple::test::load_baked(stipple::test::baked_asset(input, options), out, &error);
        EXPECT_TRUE(ok) << error;
        return ok;
    }
    // Random views of `asset`: the culled refinement against the full stage (see the header).
    void check_exact(const stipple::Asset& asset, int cases, int min_all_skipped,
                     int min_added_partly);
    stipple::Asset asset_;
    stipple::test::HeadlessGl gl_;
};

void RefinementCull::check_exact(const stipple::Asset& asset, int cases, int min_all_skipped,
                                 int min_added_partly) {
    stipple::FrameConfig config;
    config.width = 320;
    config.height = 240;
    config.refinement_budget = 1u << 16;
    auto owner = std::make_unique<stipple::Pipeline>();
    stipple::Pipeline& p = *owner;
    ASSERT_TRUE(stipple::pipeline_init(&p, asset, gl_.gl(), config).ok());
    ASSERT_TRUE(p.refine_on_points);
    stipple::RefinementMesh& r = p.refinement;
    ASSERT_GT(r.cull.cluster_count, 1u);
    const stipple::PointsView& pts = asset.points;
    const uint32_t baked = pts.point_count;
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const float zooms[] = {0.25f, 0.5f, 1.0f, 1.5f, 2.0f, 4.0f, 8.0f, 16.0f};
    int all_skipped = 0, some_skipped = 0, added = 0, added_partly_skipped = 0, staged = 0;
    int added_unprobed = 0, posed_skipped = 0, all_posed_skipped = 0;
    for (int k = 0; k < cases; ++k) {
        stipple::FrameConfig view = config;
        view.zoom = zooms[k % 8];
        view.yaw_degrees = 360.0f * unit(rng);
        view.pitch_degrees = 120.0f * unit(rng) - 60.0f;
        view.relevance_update = k % 5 != 4;
        view.constant_tone = k % 3 == 0 ? stipple::kLightingTone : 0.15f + 0.8f * unit(rng);
        ASSERT_TRUE(stipple::pipeline_set_view(&p, view).ok());
        stipple::AnimationState state;
        state.clip = asset.clip_count > 0 ? 0 : -1;
        state.time = 2.0f * unit(rng);
        r.cull.active_count = 0xFFFFFFFFu;  // the pipeline's stage sets it when it runs
        stipple::pipeline_update(&p, state, nullptr);
        const bool stage_ran = r.cull.active_count != 0xFFFFFFFFu;
        staged += stage_ran;
        Extra piped(p.refined_count);
        for (uint32_t i = 0; i < p.refined_count; ++i) {
            std::memcpy(&piped.positions[size_t(i) * 3], &p.point_positions[size_t(baked + i) * 3],
                        12);
            std::memcpy(&piped.normals[size_t(i) * 3], &p.point_normals[size_t(baked + i) * 3], 12);
            piped.radius[i] = p.radius[baked + i];
            piped.triangle[i] = p.refined_triangle[i];
            piped.index[i] = p.refined_index[i];
        }
        piped.out.count = p.refined_count;
        piped.stats = p.refinement_stats;
        // The full stage's input: every baked point placed in this pose.
        stipple::place_points(pts, asset.mesh.indices, p.vertex_positions.get(),
                              p.vertex_normals.get(), p.point_positions.get(),
                              p.point_normals.get());
        stipple::face_double_sided_points(baked, p.point_double_sided.get(),
                                          p.point_positions.get(), p.point_normals.get(),
                                          p.size_params.eye);
        stipple::MeshView domain = p.refinement_domain;
        domain.positions = p.point_positions.get();
        domain.normals = p.point_normals.get();
        const bool stretch = view.relevance_update;
        Extra full(config.refinement_budget), culled(config.refinement_budget);
        stipple::refine_points(&r, domain, domain.positions, domain.normals, nullptr, p.size_params,
                               stretch, &full.out, &full.stats);
        const uint32_t bounded = stipple::refinement_cull(
            &r.cull, asset.mesh, p.vertex_positions.get(),
            asset.sides.triangle_double_sided ? nullptr : p.vertex_normals.get(), p.size_params,
            stretch, stipple::refinement_near_w(p.size_params));
        // With relevance updates, again with the corners' posed areas (every corner is placed).
        const uint32_t active = stretch && bounded > 0 ? stipple::refinement_cull_posed(
                                                             &r.cull, domain, domain.positions)
                                                       : bounded;
        posed_skipped += active < bounded;
        all_posed_skipped += bounded > 0 && active == 0;
        if (active == 0) {
            EXPECT_EQ(full.out.count, 0u) << "case " << k << ": every cluster skipped";
            EXPECT_EQ(full.stats.wanted, 0u) << "case " << k;
            ++all_skipped;
        } else {
            stipple::refine_points_culled(&r, domain, domain.positions, domain.normals,
                                          p.size_params, stretch, &culled.out, &culled.stats,
                                          &p.pool);
            EXPECT_TRUE(same_points(full, culled))
                << "case " << k << ": zoom " << view.zoom << ", " << full.out.count << " vs "
                << culled.out.count << " points";
            uint32_t unprobed = 0;  // active clusters whose classified corners ruled them out
            for (uint32_t j = 0; j < active; ++j) unprobed += !r.cull.probed[r.cull.active_list[j]];
            added_unprobed += full.out.count > 0 && unprobed > 0;
        }
        some_skipped += active < r.cull.cluster_count;
        added += full.out.count > 0;
        added_partly_skipped += full.out.count > 0 && active < r.cull.cluster_count;
        if (stage_ran) {  // the pipeline's own stage placed only the active clusters' corners
            EXPECT_TRUE(same_points(full, piped))
                << "case " << k << ": pipeline " << piped.out.count << " vs full "
                << full.out.count;
        }
    }
    std::printf(
        "%d views: stage ran in %d; every cluster skipped in %d, some in %d; points "
        "added in %d (%d of them with clusters skipped, %d with active clusters not probed); "
        "the posed areas skipped clusters in %d (all in %d)\n",
        cases, staged, all_skipped, some_skipped, added, added_partly_skipped, added_unprobed,
        posed_skipped, all_posed_skipped);
    EXPECT_GE(all_skipped, min_all_skipped);
    EXPECT_GE(posed_skipped, min_added_partly);  // the posed-area test was exercised
    EXPECT_GE(added_partly_skipped, min_added_partly);
    EXPECT_GE(added_unprobed, min_added_partly);  // the probe's own early-out was exercised
    stipple::pipeline_destroy(&p);
}

TEST_F(RefinementCull, SkipsOnlyWhatTheFullStageWouldNotAdd) {
    check_exact(asset_, 48, 6, 3);
}

// Double-sided triangles seen from behind: normals turned to the eye before the refinement.
TEST_F(RefinementCull, SkipsOnlyWhatTheFullStageWouldNotAddDoubleSided) {
    stipple::Asset asset;
    ASSERT_TRUE(
        load("assets/SimpleSkin/SimpleSkin.gltf", "--points 20000 --double-sided on", &asset));
    check_exact(asset, 32, 1, 1);
}

// The frame's dots with the early-out and without it (cluster_count 0: the stage places every
// baked point and refines every triangle, as before), on the walk at zoom 1 to 16 with level of
// detail on and off: the same dots, byte for byte.
TEST_F(RefinementCull, FramesAreTheSameWithAndWithoutTheEarlyOut) {
    std::unique_ptr<stipple::Pipeline> p[2];
    int refined = 0;
    for (const bool lod : {true, false}) {
        stipple::FrameConfig config;
        config.width = 320;
        config.height = 240;
        config.lod = lod;
        for (auto& q : p) {
            q = std::make_unique<stipple::Pipeline>();
            ASSERT_TRUE(stipple::pipeline_init(q.get(), asset_, gl_.gl(), config).ok());
        }
        ASSERT_GT(p[0]->refinement.cull.cluster_count, 0u);
        p[1]->refinement.cull.cluster_count = 0;
        const float zooms[] = {1.0f, 2.0f, 4.0f, 8.0f, 16.0f};
        for (int f = 0; f < 10; ++f) {
            stipple::FrameConfig view = config;
            view.zoom = zooms[f % 5];
            view.yaw_degrees = 37.0f * float(f);
            stipple::AnimationState state;
            state.clip = asset_.clip_count > 0 ? 0 : -1;
            state.time = 0.13f * float(f);
            for (auto& q : p) {
                ASSERT_TRUE(stipple::pipeline_set_view(q.get(), view).ok());
                stipple::pipeline_update(q.get(), state, nullptr);
            }
            const stipple::Pipeline &a = *p[0], &b = *p[1];
            ASSERT_EQ(a.points_drawn, b.points_drawn) << "frame " << f << ", lod " << lod;
            ASSERT_EQ(a.refined_count, b.refined_count) << "frame " << f << ", lod " << lod;
            EXPECT_TRUE(
                same(a.draw_positions.get(), b.draw_positions.get(), size_t(a.points_drawn) * 3))
                << "frame " << f << ", lod " << lod;
            EXPECT_TRUE(same(a.draw_sizes.get(), b.draw_sizes.get(), a.points_drawn))
                << "frame " << f << ", lod " << lod;
            refined += a.refined_count > 0;
        }
        for (auto& q : p) stipple::pipeline_destroy(q.get());
    }
    EXPECT_GE(refined, 4);  // the close-ups did refine
}

}  // namespace
