// MorphJob (anim/anim.h): weighted morph-target deltas, in place, and its span checks.
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

TEST(AnimMorphJob, JobValidityAndWeightedDeltasInPlace) {
    const std::vector<float> d0 = {1, 0, 0, 2, 0, 0};  // vertices 1..2
    const std::vector<float> n0 = {0, 1, 0, 0, 1, 0};
    const std::vector<float> d1 = {0, 0, 4};  // vertex 2
    const MorphTarget targets[2] = {{0, 1, 2, d0.data(), n0.data()}, {1, 2, 1, d1.data(), nullptr}};
    const float defaults[2] = {0, 0};
    const Morph morph{2, defaults, 2, targets};
    std::vector<float> p = {0, 0, 0, 1, 1, 1, 2, 2, 2};
    std::vector<float> n = {0, 0, 1, 0, 0, 1, 0, 0, 1};
    const float w[2] = {0.5f, 0.25f};
    MorphJob job;
    job.morph = &morph;
    job.vertex_count = 3;
    job.weights = w;
    job.in_positions = {p.data(), p.size()};
    job.out_positions = {p.data(), p.size()};  // in place
    job.in_normals = {n.data(), n.size()};
    EXPECT_FALSE(job.validate());  // normals in without out
    job.out_normals = {n.data(), n.size()};
    EXPECT_TRUE(job.validate());
    job.vertex_count = 2;  // target 1 (vertex 2) outside
    EXPECT_FALSE(job.run());
    EXPECT_EQ(p[6], 2.0f);
    job.vertex_count = 3;
    job.out_positions = {p.data() + 3, 9};  // overlaps the input without being it
    EXPECT_FALSE(job.validate());
    job.out_positions = {p.data(), p.size()};
    ASSERT_TRUE(job.run());
    EXPECT_EQ(p, (std::vector<float>{0, 0, 0, 1.5f, 1, 1, 3, 2, 3}));
    EXPECT_EQ(n, (std::vector<float>{0, 0, 1, 0, 0.5f, 1, 0, 0.5f, 1}));
}

}  // namespace
