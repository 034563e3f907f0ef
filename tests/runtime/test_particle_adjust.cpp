// Unit tests of runtime/particle_adjust.h: stage 1 of view-dependent particles (GI'01 §2),
// fold and unfold over a persistent active set, with fades (GI'01 §5).
#include <gtest/gtest.h>

#include <vector>

#include "runtime/particle_adjust.h"

namespace {

using namespace stipple;

// A complete binary tree in breadth-first order (coarse to fine): parent(i) = (i - 1) / 2.
struct BinaryTree {
    std::vector<uint32_t> parent, depth;
    ParticleTree tree;
    explicit BinaryTree(uint32_t levels) {
        const uint32_t n = (1u << levels) - 1;
        parent.resize(n);
        depth.resize(n);
        for (uint32_t i = 0; i < n; ++i) {
            parent[i] = i == 0 ? kNoParent : (i - 1) / 2;
            depth[i] = i == 0 ? 0 : depth[(i - 1) / 2] + 1;
        }
        EXPECT_TRUE(particle_tree_build(&tree, n, parent.data()).ok());
    }
};

// Unfold every particle shallower than `depth` (a zoom level), and count what is asked.
struct DepthCriterion {
    const std::vector<uint32_t>* depth;
    uint32_t target = 0;
    std::vector<uint32_t> asked;
    static void decide(const uint32_t* ids, uint32_t count, uint8_t* unfold, void* user) {
        auto* c = static_cast<DepthCriterion*>(user);
        for (uint32_t k = 0; k < count; ++k) {
            if (k > 0) {
                EXPECT_LT(ids[k - 1], ids[k]);  // ascending
            }
            unfold[k] = (*c->depth)[ids[k]] < c->target;
            c->asked.push_back(ids[k]);
        }
    }
};

uint32_t active_at_depth(uint32_t d) {
    return (2u << d) - 1;
}  // nodes of depth <= d

TEST(ParticleAdjust, OneFrameUnfoldsAsDeepAsTheCriterionAsks) {
    BinaryTree b(10);
    ParticleSet s;
    ASSERT_TRUE(particle_set_init(&s, b.tree, 4).ok());
    EXPECT_EQ(s.count, 1u);
    DepthCriterion c{&b.depth, 6, {}};
    particles_adjust(&s, b.tree, &DepthCriterion::decide, &c);
    EXPECT_EQ(s.active_count, active_at_depth(6));
    EXPECT_EQ(s.count, active_at_depth(6));
    EXPECT_EQ(s.joined, active_at_depth(6) - 1);
    for (uint32_t i = 1; i < s.count; ++i) EXPECT_LT(s.list[i - 1], s.list[i]);
    // The first frame shows what it unfolds at once; later joins start at one fade step.
    EXPECT_FLOAT_EQ(s.alpha[0], 1.0f);
    EXPECT_FLOAT_EQ(s.alpha[s.list[s.count - 1]], 1.0f);
    c.target = 7;
    particles_adjust(&s, b.tree, &DepthCriterion::decide, &c);
    EXPECT_FLOAT_EQ(s.alpha[s.list[s.count - 1]], 0.25f);
}

TEST(ParticleAdjust, AStillViewAsksOnlyTheActiveSetAndChangesNothing) {
    BinaryTree b(10);
    ParticleSet s;
    ASSERT_TRUE(particle_set_init(&s, b.tree, 4).ok());
    DepthCriterion c{&b.depth, 5, {}};
    for (int f = 0; f < 5; ++f) particles_adjust(&s, b.tree, &DepthCriterion::decide, &c);
    const std::vector<uint32_t> before(s.list.get(), s.list.get() + s.count);
    c.asked.clear();
    particles_adjust(&s, b.tree, &DepthCriterion::decide, &c);
    EXPECT_EQ(std::vector<uint32_t>(s.list.get(), s.list.get() + s.count), before);
    EXPECT_EQ(c.asked.size(), size_t(active_at_depth(5)));  // not the 1023 particles of the tree
    EXPECT_EQ(s.joined + s.left, 0u);
    for (uint32_t i = 0; i < s.count; ++i) EXPECT_FLOAT_EQ(s.alpha[s.list[i]], 1.0f);
}

TEST(ParticleAdjust, FoldsCascadeAndFadeOutWithoutJumps) {
    BinaryTree b(8);
    ParticleSet s;
    ASSERT_TRUE(particle_set_init(&s, b.tree, 3).ok());
    DepthCriterion c{&b.depth, 6, {}};
    for (int f = 0; f < 4; ++f) particles_adjust(&s, b.tree, &DepthCriterion::decide, &c);
    std::vector<float> alpha(s.alpha.get(), s.alpha.get() + b.tree.count);
    c.target = 1;  // zoom out: everything below depth 1 folds in this one frame
    for (int f = 0; f < 5; ++f) {
        particles_adjust(&s, b.tree, &DepthCriterion::decide, &c);
        EXPECT_EQ(s.active_count, active_at_depth(1));
        for (uint32_t i = 0; i < b.tree.count; ++i) {  // at most a third per frame
            EXPECT_LE(std::abs(s.alpha[i] - alpha[i]), 1.0f / 3.0f + 1e-6f) << i;
            alpha[i] = s.alpha[i];
        }
    }
    EXPECT_EQ(s.count, active_at_depth(1));  // the folded ones have faded out and left
    c.target = 3;                            // and back in: the children join again from zero
    particles_adjust(&s, b.tree, &DepthCriterion::decide, &c);
    EXPECT_EQ(s.active_count, active_at_depth(3));
    EXPECT_NEAR(s.alpha[active_at_depth(3) - 1], 1.0f / 3.0f, 1e-6f);
}

TEST(ParticleAdjust, AParticleFoldedAndUnfoldedAgainFadesBackFromWhereItWas) {
    BinaryTree b(4);
    ParticleSet s;
    ASSERT_TRUE(particle_set_init(&s, b.tree, 4).ok());
    DepthCriterion c{&b.depth, 1, {}};
    for (int f = 0; f < 4; ++f) particles_adjust(&s, b.tree, &DepthCriterion::decide, &c);
    ASSERT_FLOAT_EQ(s.alpha[1], 1.0f);
    c.target = 0;
    particles_adjust(&s, b.tree, &DepthCriterion::decide, &c);
    EXPECT_FLOAT_EQ(s.alpha[1], 0.75f);
    EXPECT_EQ(s.count, 3u);  // still drawn while it fades
    c.target = 1;
    particles_adjust(&s, b.tree, &DepthCriterion::decide, &c);
    EXPECT_FLOAT_EQ(s.alpha[1], 1.0f);
    EXPECT_EQ(s.count, 3u);
    EXPECT_EQ(s.active_count, 3u);
}

TEST(ParticleAdjust, FadeFramesOutsideTheirRangeAreRefused) {
    BinaryTree b(3);
    ParticleSet s;
    EXPECT_EQ(particle_set_init(&s, b.tree, 0).code, StatusCode::invalid_argument);
    EXPECT_EQ(particle_set_init(&s, b.tree, 256).code, StatusCode::invalid_argument);
}

}  // namespace
