// Unit tests of runtime/particle_tree.h: the particle tree of view-dependent particles (GI'01
// §3) on the point hierarchy.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "runtime/particle_tree.h"

namespace {

using namespace stipple;

TEST(ParticleTree, ChildrenListsFollowTheParents) {
    //        0       5
    //      / | \     |
    //     1  2  4    6
    //        |
    //        3
    const std::vector<uint32_t> parent = {kNoParent, 0, 0, 2, 0, kNoParent, 5};
    ParticleTree t;
    ASSERT_TRUE(particle_tree_build(&t, 7, parent.data()).ok());
    ASSERT_EQ(t.root_count, 2u);
    EXPECT_EQ(t.roots[0], 0u);
    EXPECT_EQ(t.roots[1], 5u);
    const std::vector<std::vector<uint32_t>> expected = {{1, 2, 4}, {}, {3}, {}, {}, {6}, {}};
    for (uint32_t p = 0; p < 7; ++p) {
        std::vector<uint32_t> got(t.children.get() + t.child_begin[p],
                                  t.children.get() + t.child_begin[p + 1]);
        EXPECT_EQ(got, expected[p]) << "parent " << p;
    }
}

TEST(ParticleTree, ParentsMustPrecedeTheirChildren) {
    const std::vector<uint32_t> self = {kNoParent, 1};
    const std::vector<uint32_t> later = {kNoParent, 2, 0};
    ParticleTree t;
    EXPECT_EQ(particle_tree_build(&t, 2, self.data()).code, StatusCode::invalid_argument);
    EXPECT_EQ(particle_tree_build(&t, 3, later.data()).code, StatusCode::invalid_argument);
    const std::vector<uint32_t> zero_not_root = {0};
    EXPECT_FALSE(particle_parents_valid(1, zero_not_root.data()));
}

// Points on a unit sphere in random (coarse-to-fine-like) order.
std::vector<float> sphere_points(uint32_t n, uint32_t seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<float> g;
    std::vector<float> p(size_t(n) * 3);
    for (uint32_t i = 0; i < n; ++i) {
        float x = g(rng), y = g(rng), z = g(rng);
        const float len = std::sqrt(x * x + y * y + z * z);
        p[i * 3] = x / len;
        p[i * 3 + 1] = y / len;
        p[i * 3 + 2] = z / len;
    }
    return p;
}

uint32_t brute_nearest_coarser(const std::vector<float>& p, uint32_t i) {
    uint32_t best = kNoParent;
    float best_d2 = INFINITY;
    const uint32_t above = particle_level_start(i);
    for (uint32_t j = particle_level_start(above - 1 + (above == 0)); j < above; ++j) {
        float d2 = 0.0f;
        for (int k = 0; k < 3; ++k)
            d2 += (p[j * 3 + k] - p[i * 3 + k]) * (p[j * 3 + k] - p[i * 3 + k]);
        if (d2 < best_d2) {
            best_d2 = d2;
            best = j;
        }
    }
    return best;
}

TEST(ParticleTree, LevelsGrowByFour) {
    const uint32_t expected[] = {0, 1, 1, 1, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 16, 16};
    for (uint32_t i = 0; i < 18; ++i) EXPECT_EQ(particle_level_start(i), expected[i]) << i;
    EXPECT_EQ(particle_level_start(1u << 30), 1u << 30);
    EXPECT_EQ(particle_level_start((1u << 30) - 1), 1u << 28);
    EXPECT_EQ(particle_level_start(0xFFFFFFFFu), 1u << 30);
}

TEST(ParticleTree, ParentsAreTheNearestPointsOfTheLevelAbove) {
    const uint32_t n = 6000;
    const std::vector<float> p = sphere_points(n, 7);
    std::vector<uint32_t> parent(n);
    ASSERT_TRUE(particle_parents(n, p.data(), INFINITY, parent.data()).ok());
    EXPECT_EQ(parent[0], kNoParent);
    uint32_t same = 0;
    for (uint32_t i = 1; i < n; ++i) same += parent[i] == brute_nearest_coarser(p, i);
    EXPECT_EQ(same, n - 1);
    EXPECT_TRUE(particle_parents_valid(n, parent.data()));
}

TEST(ParticleTree, FarPiecesAndCoincidentPointsStillMakeAForest) {
    // Two clusters far apart, the second starting late; then every point at one place.
    const uint32_t n = 2000;
    std::vector<float> p = sphere_points(n, 3);
    for (uint32_t i = 1500; i < n; ++i) p[i * 3] += 1000.0f;
    std::vector<uint32_t> parent(n);
    ASSERT_TRUE(particle_parents(n, p.data(), INFINITY, parent.data()).ok());
    EXPECT_TRUE(particle_parents_valid(n, parent.data()));
    EXPECT_LT(parent[1500], 1024u);      // found across the gap
    for (uint32_t i = 1501; i < n; ++i)  // level 6 starts at 1024: the first piece's points
        EXPECT_LT(parent[i], 1024u) << i;
    // A distance cap makes the far piece's points roots.
    ASSERT_TRUE(particle_parents(n, p.data(), 10.0f, parent.data()).ok());
    for (uint32_t i = 1500; i < n; ++i) EXPECT_EQ(parent[i], kNoParent) << i;
    std::vector<float> same(30, 0.5f);
    ASSERT_TRUE(particle_parents(10, same.data(), INFINITY, parent.data()).ok());
    EXPECT_TRUE(particle_parents_valid(10, parent.data()));
}

}  // namespace
