// Unit tests of runtime/particle_temporary.h: the particle tree continued past the bake with
// the run-time refinement's extra points (GI'01 §5's temporary particles on triangles).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "runtime/particle_stage.h"
#include "runtime/particle_temporary.h"
#include "tests/common/fixtures.h"

namespace {

using namespace stipple;
using namespace stipple::test;

class TemporaryParticlesTest : public ::testing::Test {
  protected:
    void SetUp() override {
        std::string error;
        ASSERT_TRUE(load_baked(baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 5000"),
                               &asset_, &error))
            << error;
    }
    Asset asset_;
};

TEST_F(TemporaryParticlesTest, ContinueTheBakeOnItsTrianglesCoarseToFine) {
    TemporaryParticles t;
    ASSERT_TRUE(temporary_particles_build(&t, asset_, 40000).ok());
    const uint32_t baked = asset_.points.point_count;
    EXPECT_EQ(t.baked, baked);
    EXPECT_EQ(t.count, 40000u);
    ASSERT_EQ(t.view.point_count, t.count);
    // The baked points are kept as they are.
    for (uint32_t i = 0; i < baked; ++i) {
        ASSERT_EQ(t.view.host_triangle[i], asset_.points.host_triangle[i]);
        ASSERT_EQ(t.view.radius[i], asset_.points.radius[i]);
    }
    // The temporary ones lie inside their triangles, at the refinement's ids, and their radii
    // shrink from where the bake's end (the A / i law continued): never larger than the next.
    float last = INFINITY;
    for (uint32_t i = baked; i < t.count; ++i) {
        const float u = t.view.bary_u[i], v = t.view.bary_v[i];
        ASSERT_TRUE(u >= -1e-6f && v >= -1e-6f && u + v <= 1.0f + 1e-6f) << i;
        ASSERT_LT(t.view.host_triangle[i], asset_.mesh.triangle_count);
        ASSERT_EQ(t.triangle[i - baked], t.view.host_triangle[i]);
        ASSERT_LE(t.view.radius[i], last * (1.0f + 1e-6f)) << i;
        last = t.view.radius[i];
    }
    // The law: radius ~ sqrt(A / i), so from index 20,000 to 40,000 a factor sqrt(2).
    const float first = t.view.radius[baked];
    EXPECT_NEAR(t.view.radius[20000] / t.view.radius[t.count - 1], std::sqrt(2.0f), 0.1f);
    // About the bake's last radius where they start (the fitted scale, within 30%).
    EXPECT_NEAR(first / asset_.points.radius[baked - 1], 1.0f, 0.3f);
    // Ids are deterministic: the same build twice gives the same points.
    TemporaryParticles again;
    ASSERT_TRUE(temporary_particles_build(&again, asset_, 40000).ok());
    for (uint32_t j = 0; j < t.count - baked; ++j) {
        ASSERT_EQ(again.triangle[j], t.triangle[j]);
        ASSERT_EQ(again.rank[j], t.rank[j]);
    }
}

TEST_F(TemporaryParticlesTest, NoneWhenTheBudgetIsTheBake) {
    TemporaryParticles t;
    ASSERT_TRUE(temporary_particles_build(&t, asset_, 0).ok());
    EXPECT_EQ(t.count, asset_.points.point_count);
    EXPECT_EQ(t.view.host_triangle, asset_.points.host_triangle);
}

// In the stage's tree, every temporary particle's parent precedes it and lies one level above
// (a baked point of the finest levels, or a temporary one), so unfolding past the bake keeps
// halving the spacing.
TEST_F(TemporaryParticlesTest, JoinTheTreeOneLevelBelowTheirParents) {
    ParticleStage s;
    ASSERT_TRUE(
        particle_stage_init(&s, asset_, *find_particle_style("painterly-long"), 320, 240, 40000)
            .ok());
    const uint32_t baked = asset_.points.point_count;
    ASSERT_EQ(s.tree.count, 40000u);
    ASSERT_TRUE(particle_parents_valid(s.tree.count, s.tree.parent));
    uint32_t one_level_up = 0, baked_parents = 0;
    for (uint32_t i = baked; i < s.tree.count; ++i) {
        const uint32_t p = s.tree.parent[i];
        ASSERT_LT(p, i);
        one_level_up += particle_level_start(p) * 4 == particle_level_start(i);
        baked_parents += p < baked;
    }
    const uint32_t temporary = s.tree.count - baked;
    EXPECT_GE(one_level_up, temporary - temporary / 100);
    EXPECT_GT(baked_parents, 0u);
    EXPECT_LT(baked_parents, temporary);
    particle_stage_destroy(&s);
}

// particle_stage_init's list_points bounds what a frame lists: stage 1's list, stage 3's
// samples and stage 4's strokes are sized by it, the tree's per-particle arrays by the tree.
TEST_F(TemporaryParticlesTest, AListBudgetSizesTheListedBuffersOnly) {
    const ParticleStyle* style = find_particle_style("painterly-long");
    ASSERT_NE(style, nullptr);
    auto bytes = [&](uint32_t tree, uint32_t list) {
        CountingArena arena;
        AllocatorScope scope(counting_allocator(&arena));
        ParticleStage s;
        EXPECT_TRUE(particle_stage_init(&s, asset_, *style, 640, 480, tree, list).ok());
        EXPECT_EQ(s.set.capacity, tree);
        EXPECT_EQ(s.set.list_capacity, list == 0 ? tree : list);
        particle_stage_destroy(&s);
        return arena.bytes;
    };
    const size_t whole = bytes(65536, 0), bounded = bytes(65536, 8192);
    const size_t big_tree = bytes(262144, 8192);
    const double per_unlisted = double(whole - bounded) / double(65536 - 8192);
    const double per_id = double(big_tree - bounded) / double(262144 - 65536);
    std::printf(
        "65,536 particles: %zu bytes listed whole, %zu with 8,192 listed (%.1f bytes per "
        "particle not listed); 262,144 with 8,192 listed: %zu (%.1f bytes per particle)\n",
        whole, bounded, per_unlisted, big_tree, per_id);
    // Samples 41, strokes and their ids 44, the list and stage 1's scratch 20, an answer 1.
    EXPECT_GT(per_unlisted, 100.0);
    // The tree, its state and its init-time scratch (116.5 when measured).
    EXPECT_LT(per_id, 130.0);
}

}  // namespace
