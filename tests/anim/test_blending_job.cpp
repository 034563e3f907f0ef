// BlendingJob and crossfade (anim/anim.h): weighted means, hemisphere alignment, node masks,
// the rest-pose fill and morph weights.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <random>
#include <vector>

#include "anim/anim.h"
#include "tests/common/anim_builders.h"

namespace {

using namespace stipple::anim;
using namespace stipple::test;

TEST(AnimBlendingJob, JobValidity) {
    const std::vector<int32_t> parents = {-1, 0};
    const std::vector<Trs> rest = {identity_trs(), identity_trs()};
    const Skeleton skeleton = make_skeleton(parents, rest);
    Trs a[2] = {identity_trs(), identity_trs()};
    Trs out[2];
    BlendLayer layers[1];
    layers[0].locals = {a, 1};  // too small
    layers[0].weight = 1;
    BlendingJob job;
    EXPECT_FALSE(job.validate());
    job.skeleton = &skeleton;
    job.layers = layers;
    job.out = out;
    EXPECT_FALSE(job.validate());
    layers[0].locals = a;
    EXPECT_TRUE(job.validate());
    const float mask[1] = {1};
    layers[0].node_weights = mask;  // mask shorter than the skeleton
    EXPECT_FALSE(job.validate());
    layers[0].node_weights = {};
    job.threshold = 0;
    EXPECT_FALSE(job.validate());
    job.threshold = 0.1f;
    job.out = {out, 1};
    EXPECT_FALSE(job.run());
}

TEST(AnimBlendingJob, WeightedMeanHemisphereMasksAndRestFill) {
    const std::vector<int32_t> parents = {-1, 0};
    const std::vector<Trs> rest = {Trs{{0, 0, 0}, {0, 0, 0, 1}, {1, 1, 1}},
                                   Trs{{0, 10, 0}, {0, 0, 0, 1}, {1, 1, 1}}};
    const Skeleton skeleton = make_skeleton(parents, rest);
    const float h = std::sqrt(0.5f);
    // Layer a: T (4,0,0), 90° about Z. Layer b: T (0,4,0), the same rotation as -q.
    const Trs a[2] = {Trs{{4, 0, 0}, {0, 0, h, h}, {2, 2, 2}},
                      Trs{{4, 0, 0}, {0, 0, 0, 1}, {1, 1, 1}}};
    const Trs b[2] = {Trs{{0, 4, 0}, {0, 0, -h, -h}, {1, 1, 1}},
                      Trs{{0, 4, 0}, {0, 0, 0, 1}, {1, 1, 1}}};
    const float mask_b[2] = {1, 0};  // layer b does not drive node 1
    BlendLayer layers[2];
    layers[0].locals = a;
    layers[0].weight = 0.25f;
    layers[1].locals = b;
    layers[1].weight = 0.75f;
    layers[1].node_weights = mask_b;
    Trs out[2];
    BlendingJob job;
    job.skeleton = &skeleton;
    job.layers = layers;
    job.out = out;
    ASSERT_TRUE(job.run());
    // Node 0: 0.25 * (4,0,0) + 0.75 * (0,4,0) = (1,3,0); scale 0.25 * 2 + 0.75 = 1.25;
    // rotation: -q joins q's hemisphere, so the blend is q itself.
    EXPECT_NEAR(out[0].translation[0], 1, 1e-6f);
    EXPECT_NEAR(out[0].translation[1], 3, 1e-6f);
    EXPECT_NEAR(out[0].scale[0], 1.25f, 1e-6f);
    EXPECT_NEAR(std::abs(out[0].rotation[2]), h, 1e-6f);
    EXPECT_NEAR(std::abs(out[0].rotation[3]), h, 1e-6f);
    // Node 1: only layer a (weight 0.25 >= threshold 0.1): exactly a.
    EXPECT_NEAR(out[1].translation[0], 4, 1e-6f);
    EXPECT_NEAR(out[1].translation[1], 0, 1e-6f);
    // Weight deficit: a alone at 0.05 < threshold 0.1 -> half a, half rest.
    layers[0].weight = 0.05f;
    job.layers = {layers, 1};
    ASSERT_TRUE(job.run());
    EXPECT_NEAR(out[1].translation[0], 2, 1e-5f);
    EXPECT_NEAR(out[1].translation[1], 5, 1e-5f);
    // No layer at all: the rest pose.
    job.layers = {};
    ASSERT_TRUE(job.run());
    EXPECT_TRUE(same_trs(out[1], rest[1]));
}

TEST(AnimBlendingJob, CrossfadeEndsAreTheClipsAndMorphWeightsBlend) {
    const std::vector<int32_t> parents = {-1};
    const std::vector<Trs> rest = {identity_trs()};
    const Skeleton skeleton = make_skeleton(parents, rest);
    const Trs from[1] = {Trs{{1, 0, 0}, {0, 0, 0, 1}, {1, 1, 1}}};
    const Trs to[1] = {Trs{{3, 0, 0}, {0, 1, 0, 0}, {1, 1, 1}}};
    Trs out[1];
    ASSERT_TRUE(crossfade(skeleton, from, to, 0.0f, out));
    EXPECT_TRUE(same_trs(out[0], from[0]));
    ASSERT_TRUE(crossfade(skeleton, from, to, 1.0f, out));
    EXPECT_TRUE(same_trs(out[0], to[0]));
    ASSERT_TRUE(crossfade(skeleton, from, to, 0.5f, out));
    EXPECT_NEAR(out[0].translation[0], 2, 1e-6f);

    const float wa[2] = {1, 0}, wb[2] = {0, 1};
    BlendLayer layers[2];
    layers[0].locals = from;
    layers[0].weight = 0.25f;
    layers[0].morph_weights = wa;
    layers[1].locals = to;
    layers[1].weight = 0.75f;
    layers[1].morph_weights = wb;
    float mw[2];
    BlendingJob job;
    job.skeleton = &skeleton;
    job.layers = layers;
    job.out = out;
    job.out_morph_weights = mw;
    ASSERT_TRUE(job.run());
    EXPECT_NEAR(mw[0], 0.25f, 1e-6f);
    EXPECT_NEAR(mw[1], 0.75f, 1e-6f);
}

}  // namespace
