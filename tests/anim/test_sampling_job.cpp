// SamplingJob (anim/anim.h): clip sampling, glTF 2.0 §3.11 "Animation" and Appendix C
// interpolation (STEP, LINEAR, CUBICSPLINE), against hand-computed values; the context's
// cursors, wrap modes and morph-weight channels.
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

// Translation keys at t = 0, 1, 2.
const float kTimes3[] = {0.0f, 1.0f, 2.0f};
const float kTranslations3[] = {0, 0, 0, /**/ 2, 4, -6, /**/ 4, 0, 10};

TEST(AnimSampling, LinearTranslationAtAndBetweenKeys) {
    const std::vector<int32_t> parents = {-1};
    const std::vector<Trs> rest = {identity_trs()};
    const Skeleton skeleton = make_skeleton(parents, rest);
    const std::vector<Channel> channels = {
        {0, Path::translation, Interp::linear, 3, kTimes3, kTranslations3}};
    const Clip clip = make_clip(channels, 2.0f);
    Trs pose;

    sample_pose(skeleton, clip, 0.0f, &pose);
    expect_vec3(pose.translation, 0, 0, 0);
    sample_pose(skeleton, clip, 0.5f, &pose);  // halfway between key 0 and 1
    expect_vec3(pose.translation, 1, 2, -3);
    sample_pose(skeleton, clip, 1.0f, &pose);
    expect_vec3(pose.translation, 2, 4, -6);
    // 1.5: halfway between (2, 4, -6) and (4, 0, 10) = (3, 2, 2).
    sample_pose(skeleton, clip, 1.5f, &pose);
    expect_vec3(pose.translation, 3, 2, 2);
    // 1.75: (2, 4, -6) + 0.75 * (2, -4, 16) = (3.5, 1, 6).
    sample_pose(skeleton, clip, 1.75f, &pose);
    expect_vec3(pose.translation, 3.5f, 1, 6);
    sample_pose(skeleton, clip, 2.0f, &pose);
    expect_vec3(pose.translation, 4, 0, 10);
    // Rotation and scale are not animated: rest values.
    EXPECT_EQ(pose.rotation[3], 1.0f);
    expect_vec3(pose.scale, 1, 1, 1);
}

TEST(AnimSampling, TimesClampToFirstAndLastKey) {
    const std::vector<int32_t> parents = {-1};
    const std::vector<Trs> rest = {identity_trs()};
    const Skeleton skeleton = make_skeleton(parents, rest);
    const std::vector<Channel> channels = {
        {0, Path::translation, Interp::linear, 3, kTimes3, kTranslations3}};
    const Clip clip = make_clip(channels, 2.0f);
    Trs pose;

    sample_pose(skeleton, clip, -1.0f, &pose);
    expect_vec3(pose.translation, 0, 0, 0);
    sample_pose(skeleton, clip, 2.5f, &pose);
    expect_vec3(pose.translation, 4, 0, 10);
    sample_pose(skeleton, clip, 1e9f, &pose);
    expect_vec3(pose.translation, 4, 0, 10);
    sample_pose(skeleton, clip, std::nanf(""), &pose);  // NaN samples the start
    expect_vec3(pose.translation, 0, 0, 0);
}

TEST(AnimSampling, ChannelStartingLateHoldsItsFirstKey) {
    // glTF 2.0 §3.11: before a sampler's first key its first value holds, even when the clip
    // (here 0..3 s) starts earlier.
    const std::vector<int32_t> parents = {-1};
    const std::vector<Trs> rest = {identity_trs()};
    const Skeleton skeleton = make_skeleton(parents, rest);
    const float times[] = {1.0f, 2.0f};
    const float values[] = {5, 5, 5, /**/ 7, 7, 7};
    const std::vector<Channel> channels = {{0, Path::scale, Interp::linear, 2, times, values}};
    const Clip clip = make_clip(channels, 3.0f);
    Trs pose;
    sample_pose(skeleton, clip, 0.25f, &pose);
    expect_vec3(pose.scale, 5, 5, 5);
    sample_pose(skeleton, clip, 1.25f, &pose);  // 5 + 0.25 * 2
    expect_vec3(pose.scale, 5.5f, 5.5f, 5.5f);
    sample_pose(skeleton, clip, 3.0f, &pose);
    expect_vec3(pose.scale, 7, 7, 7);
}

TEST(AnimSampling, StepHoldsTheKeyAtOrBeforeTime) {
    const std::vector<int32_t> parents = {-1};
    const std::vector<Trs> rest = {identity_trs()};
    const Skeleton skeleton = make_skeleton(parents, rest);
    const std::vector<Channel> channels = {
        {0, Path::translation, Interp::step, 3, kTimes3, kTranslations3}};
    const Clip clip = make_clip(channels, 2.0f);
    Trs pose;

    sample_pose(skeleton, clip, 0.0f, &pose);
    expect_vec3(pose.translation, 0, 0, 0);
    sample_pose(skeleton, clip, 0.99f, &pose);
    expect_vec3(pose.translation, 0, 0, 0);
    sample_pose(skeleton, clip, 1.0f, &pose);
    expect_vec3(pose.translation, 2, 4, -6);
    sample_pose(skeleton, clip, 1.5f, &pose);
    expect_vec3(pose.translation, 2, 4, -6);
    sample_pose(skeleton, clip, 2.0f, &pose);
    expect_vec3(pose.translation, 4, 0, 10);
    sample_pose(skeleton, clip, -3.0f, &pose);
    expect_vec3(pose.translation, 0, 0, 0);
}

// Rotation keys: identity and 90° about Z, i.e. (0, 0, sin 45°, cos 45°).
TEST(AnimSampling, RotationSlerpsAtConstantAngularSpeed) {
    const std::vector<int32_t> parents = {-1};
    const std::vector<Trs> rest = {identity_trs()};
    const Skeleton skeleton = make_skeleton(parents, rest);
    const float times[] = {0.0f, 1.0f};
    const float values[] = {0, 0, 0, 1, /**/ 0, 0, kHalfSqrt2, kHalfSqrt2};
    const std::vector<Channel> channels = {{0, Path::rotation, Interp::linear, 2, times, values}};
    const Clip clip = make_clip(channels, 1.0f);
    Trs pose;

    // Midpoint: 45° about Z = (0, 0, sin 22.5°, cos 22.5°).
    sample_pose(skeleton, clip, 0.5f, &pose);
    const float half = 22.5f * 3.14159265358979f / 180.0f;
    EXPECT_NEAR(pose.rotation[0], 0.0f, kEps);
    EXPECT_NEAR(pose.rotation[1], 0.0f, kEps);
    EXPECT_NEAR(pose.rotation[2], std::sin(half), kEps);
    EXPECT_NEAR(pose.rotation[3], std::cos(half), kEps);
    // x axis rotated 45°: (cos 45°, sin 45°, 0).
    const glm::vec3 x45 = rotate(pose.rotation, glm::vec3(1, 0, 0));
    EXPECT_NEAR(x45.x, kHalfSqrt2, kEps);
    EXPECT_NEAR(x45.y, kHalfSqrt2, kEps);

    // A quarter of the way: 22.5° about Z. Normalised lerp would give 2 * atan(0.1768 / 0.9268)
    // = 21.6°, so this checks a true slerp.
    sample_pose(skeleton, clip, 0.25f, &pose);
    const float quarter = 11.25f * 3.14159265358979f / 180.0f;
    EXPECT_NEAR(pose.rotation[2], std::sin(quarter), kEps);
    EXPECT_NEAR(pose.rotation[3], std::cos(quarter), kEps);
}

TEST(AnimSampling, RotationTakesTheShortestPath) {
    // The second key is -(90° about Z): the same rotation on the other hemisphere. A naive
    // slerp would sweep 270° the long way round, whose midpoint is 135° about Z.
    const std::vector<int32_t> parents = {-1};
    const std::vector<Trs> rest = {identity_trs()};
    const Skeleton skeleton = make_skeleton(parents, rest);
    const float times[] = {0.0f, 1.0f};
    const float values[] = {0, 0, 0, 1, /**/ 0, 0, -kHalfSqrt2, -kHalfSqrt2};
    const std::vector<Channel> channels = {{0, Path::rotation, Interp::linear, 2, times, values}};
    const Clip clip = make_clip(channels, 1.0f);
    Trs pose;
    sample_pose(skeleton, clip, 0.5f, &pose);
    const float* q = pose.rotation;
    EXPECT_NEAR(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3], 1.0f, kEps);
    // 45° about Z either sign: x axis -> (cos 45°, sin 45°, 0).
    const glm::vec3 x45 = rotate(q, glm::vec3(1, 0, 0));
    EXPECT_NEAR(x45.x, kHalfSqrt2, kEps);
    EXPECT_NEAR(x45.y, kHalfSqrt2, kEps);
    EXPECT_NEAR(x45.z, 0.0f, kEps);
    // Interpolating from the first key, the result stays on its hemisphere: w = cos 22.5°.
    EXPECT_NEAR(q[3], std::cos(22.5f * 3.14159265358979f / 180.0f), kEps);
}

TEST(AnimSampling, RotationResultIsNormalised) {
    // Keys that are not quite unit length (quantised asset) still give a unit quaternion.
    const std::vector<int32_t> parents = {-1};
    const std::vector<Trs> rest = {identity_trs()};
    const Skeleton skeleton = make_skeleton(parents, rest);
    const float times[] = {0.0f, 1.0f};
    const float values[] = {0, 0, 0, 1.01f, /**/ 0, 0.99f * kHalfSqrt2, 0, 0.99f * kHalfSqrt2};
    const std::vector<Channel> channels = {{0, Path::rotation, Interp::linear, 2, times, values}};
    const Clip clip = make_clip(channels, 1.0f);
    Trs pose;
    sample_pose(skeleton, clip, 0.3f, &pose);
    const float* q = pose.rotation;
    EXPECT_NEAR(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3], 1.0f, kEps);
}

TEST(AnimSampling, OneKeyChannelHoldsItsValue) {
    const std::vector<int32_t> parents = {-1};
    const std::vector<Trs> rest = {identity_trs()};
    const Skeleton skeleton = make_skeleton(parents, rest);
    const float times[] = {0.5f};
    const float values[] = {1, 2, 3};
    const float rot_values[] = {0, 0, kHalfSqrt2, kHalfSqrt2};
    for (Interp interp : {Interp::linear, Interp::step}) {
        const std::vector<Channel> channels = {{0, Path::translation, interp, 1, times, values},
                                               {0, Path::rotation, interp, 1, times, rot_values}};
        const Clip clip = make_clip(channels, 1.0f);
        for (float t : {-1.0f, 0.0f, 0.5f, 0.75f, 1.0f, 5.0f}) {
            Trs pose;
            sample_pose(skeleton, clip, t, &pose);
            expect_vec3(pose.translation, 1, 2, 3);
            EXPECT_NEAR(pose.rotation[2], kHalfSqrt2, kEps);
            EXPECT_NEAR(pose.rotation[3], kHalfSqrt2, kEps);
        }
    }
}

TEST(AnimSampling, NodesNotAnimatedKeepTheirRestPose) {
    const std::vector<int32_t> parents = {-1, 0, 1};
    std::vector<Trs> rest(3, identity_trs());
    rest[0] = Trs{{1, 2, 3}, {0, 0, kHalfSqrt2, kHalfSqrt2}, {2, 2, 2}};
    rest[2] = Trs{{-1, 0, 0}, {kHalfSqrt2, 0, 0, kHalfSqrt2}, {1, 3, 1}};
    const Skeleton skeleton = make_skeleton(parents, rest);
    // Animate node 1's translation only; plus a channel aimed past the skeleton (ignored).
    const std::vector<Channel> channels = {
        {1, Path::translation, Interp::linear, 3, kTimes3, kTranslations3},
        {7, Path::translation, Interp::linear, 3, kTimes3, kTranslations3}};
    const Clip clip = make_clip(channels, 2.0f);
    Trs pose[3];
    std::memset(pose, 0xff, sizeof(pose));  // garbage: everything must be written
    sample_pose(skeleton, clip, 0.5f, pose);
    EXPECT_EQ(std::memcmp(&pose[0], &rest[0], sizeof(Trs)), 0);
    EXPECT_EQ(std::memcmp(&pose[2], &rest[2], sizeof(Trs)), 0);
    expect_vec3(pose[1].translation, 1, 2, -3);
    EXPECT_EQ(std::memcmp(pose[1].rotation, rest[1].rotation, sizeof(float) * 4), 0);
    EXPECT_EQ(std::memcmp(pose[1].scale, rest[1].scale, sizeof(float) * 3), 0);
}

TEST(AnimSamplingJob, JobValidity) {
    const std::vector<int32_t> parents = {-1, 0};
    const std::vector<Trs> rest = {identity_trs(), identity_trs()};
    const Skeleton skeleton = make_skeleton(parents, rest);
    const std::vector<float> times = {0, 1};
    const std::vector<float> values = {0, 0, 0, 1, 1, 1};
    const std::vector<Channel> channels = {
        channel(1, Path::translation, Interp::linear, times, values)};
    const Clip clip = make_clip(channels, 1);
    Trs locals[2];
    Trs sentinel;
    std::memset(&sentinel, 0x5a, sizeof(sentinel));
    locals[0] = locals[1] = sentinel;
    uint32_t cursor = 0;
    SamplingContext context;
    float weights[2];

    SamplingJob job;
    EXPECT_FALSE(job.validate());  // nothing set
    job.skeleton = &skeleton;
    job.clip = &clip;
    job.locals = {locals, 1};  // too small
    EXPECT_FALSE(job.validate());
    EXPECT_FALSE(job.run());
    EXPECT_TRUE(same_trs(locals[0], sentinel));  // untouched
    job.locals = locals;
    EXPECT_TRUE(job.validate());
    job.context = &context;  // context without cursors
    EXPECT_FALSE(job.validate());
    context.cursors = {&cursor, 1};
    EXPECT_TRUE(job.validate());
    job.morph_weights = weights;
    const float one_default[1] = {0.5f};
    job.default_morph_weights = one_default;  // smaller than the output
    EXPECT_FALSE(job.validate());
    job.default_morph_weights = {};
    EXPECT_TRUE(job.run());
    EXPECT_EQ(weights[0], 0.0f);  // no defaults: zeros
    job.clip = nullptr;
    EXPECT_FALSE(job.validate());
}

TEST(AnimSamplingJob, EmptyClipGivesRestPoseAndDefaultWeights) {
    const std::vector<int32_t> parents = {-1};
    const std::vector<Trs> rest = {Trs{{1, 2, 3}, {0, 0, 0, 1}, {2, 2, 2}}};
    const Skeleton skeleton = make_skeleton(parents, rest);
    const Clip clip{"empty", 0.0f, 0, nullptr};
    Trs pose;
    float weights[2] = {9, 9};
    const float defaults[2] = {0.25f, 0.5f};
    SamplingJob job;
    job.skeleton = &skeleton;
    job.clip = &clip;
    job.time = 3.0f;
    job.wrap = Wrap::loop;  // duration 0 loops to 0
    job.locals = {&pose, 1};
    job.morph_weights = weights;
    job.default_morph_weights = defaults;
    ASSERT_TRUE(job.run());
    EXPECT_TRUE(same_trs(pose, rest[0]));
    EXPECT_EQ(weights[0], 0.25f);
    EXPECT_EQ(weights[1], 0.5f);
}

// Appendix C by hand: keys at t = 0 and 2 (td = 2), sampled at t = 0.5 (s = 0.25):
//   h00 = 2s^3 - 3s^2 + 1 = 0.84375      h10 = td (s^3 - 2s^2 + s) = 0.28125
//   h01 = -2s^3 + 3s^2    = 0.15625      h11 = td (s^3 - s^2)      = -0.09375
// x: v0 = 1, b0 = 0.5, v1 = 3, a1 = -1 -> 0.84375 + 0.140625 + 0.46875 + 0.09375 = 1.546875
// y: v0 = 0, b0 = 1,   v1 = 0, a1 = 1  -> 0.28125 - 0.09375 = 0.1875
// z: v0 = 2, b0 = 0,   v1 = 2, a1 = 0  -> 2 (h00 + h01 = 1)
TEST(AnimSamplingJob, CubicSplineMatchesHandComputedHermite) {
    const std::vector<int32_t> parents = {-1};
    const std::vector<Trs> rest = {identity_trs()};
    const Skeleton skeleton = make_skeleton(parents, rest);
    const std::vector<float> times = {0, 2};
    const std::vector<float> values = {9,  9, 9, /**/ 1, 0, 2, /**/ 0.5f, 1, 0,   // key 0: a, v, b
                                       -1, 1, 0, /**/ 3, 0, 2, /**/ 9,    9, 9};  // key 1
    const std::vector<Channel> channels = {
        channel(0, Path::translation, Interp::cubic_spline, times, values)};
    const Clip clip = make_clip(channels, 2);
    Trs pose;
    SamplingJob job;
    job.skeleton = &skeleton;
    job.clip = &clip;
    job.locals = {&pose, 1};
    job.time = 0.5f;
    ASSERT_TRUE(job.run());
    EXPECT_NEAR(pose.translation[0], 1.546875f, 1e-6f);
    EXPECT_NEAR(pose.translation[1], 0.1875f, 1e-6f);
    EXPECT_NEAR(pose.translation[2], 2.0f, 1e-6f);
    // At and outside the keys: the values (the tangents, 9, are never returned).
    for (float t : {-1.0f, 0.0f}) {
        job.time = t;
        ASSERT_TRUE(job.run());
        EXPECT_EQ(pose.translation[0], 1.0f);  // key 0's value, not its in-tangent
    }
}

TEST(AnimSamplingJob, CubicSplineHoldsKeyValuesOutsideAndOneKey) {
    const std::vector<int32_t> parents = {-1};
    const std::vector<Trs> rest = {identity_trs()};
    const Skeleton skeleton = make_skeleton(parents, rest);
    const std::vector<float> times = {0.5f, 2};
    const std::vector<float> values = {9, 9, 9, 1, 0, 2, 9, 9, 9, 9, 9, 9, 3, 0, 2, 9, 9, 9};
    const std::vector<float> one_time = {0.5f};
    const std::vector<float> one_value = {7, 7, 7, 4, 5, 6, 7, 7, 7};
    const std::vector<Channel> channels = {
        channel(0, Path::translation, Interp::cubic_spline, times, values),
        channel(0, Path::scale, Interp::cubic_spline, one_time, one_value)};
    const Clip clip = make_clip(channels, 3);
    Trs pose;
    SamplingJob job;
    job.skeleton = &skeleton;
    job.clip = &clip;
    job.locals = {&pose, 1};
    for (float t : {0.0f, 0.25f, 0.5f}) {
        job.time = t;
        ASSERT_TRUE(job.run());
        EXPECT_EQ(pose.translation[0], 1.0f) << t;
        EXPECT_EQ(pose.scale[1], 5.0f);
    }
    for (float t : {2.0f, 2.5f, 99.0f}) {
        job.time = t;
        ASSERT_TRUE(job.run());
        EXPECT_EQ(pose.translation[0], 3.0f) << t;
        EXPECT_EQ(pose.scale[2], 6.0f);
    }
}

TEST(AnimSamplingJob, CubicSplineRotationIsNormalised) {
    const std::vector<int32_t> parents = {-1};
    const std::vector<Trs> rest = {identity_trs()};
    const Skeleton skeleton = make_skeleton(parents, rest);
    const std::vector<float> times = {0, 1};
    const float h = std::sqrt(0.5f);
    const std::vector<float> values = {0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 2, 1,  //
                                       0, 1, 0, 3, 0, 0, h, h, 0, 0, 0, 0};
    const std::vector<Channel> channels = {
        channel(0, Path::rotation, Interp::cubic_spline, times, values)};
    const Clip clip = make_clip(channels, 1);
    Trs pose;
    SamplingJob job;
    job.skeleton = &skeleton;
    job.clip = &clip;
    job.locals = {&pose, 1};
    for (float t = 0.05f; t < 1.0f; t += 0.1f) {
        job.time = t;
        ASSERT_TRUE(job.run());
        const float* q = pose.rotation;
        EXPECT_NEAR(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3], 1.0f, 1e-6f);
    }
}

TEST(AnimSamplingJob, WeightsChannelsWriteTheirSlotsOnly) {
    const std::vector<int32_t> parents = {-1};
    const std::vector<Trs> rest = {identity_trs()};
    const Skeleton skeleton = make_skeleton(parents, rest);
    const std::vector<float> times = {0, 1};
    const std::vector<float> lin = {0, 1, /**/ 1, 0};    // 2 slots per key
    const std::vector<float> step = {0.5f, /**/ 0.75f};  // 1 slot per key
    const std::vector<Channel> channels = {
        channel(0, Path::weights, Interp::linear, times, lin, 1, 2),
        channel(0, Path::weights, Interp::step, times, step, 3, 1),
        channel(0, Path::weights, Interp::linear, times, lin, 4, 2)};  // past the slots: ignored
    const Clip clip = make_clip(channels, 1);
    Trs pose;
    float weights[5];
    const float defaults[5] = {0.1f, 0.2f, 0.3f, 0.4f, 0.5f};
    SamplingJob job;
    job.skeleton = &skeleton;
    job.clip = &clip;
    job.locals = {&pose, 1};
    job.morph_weights = weights;
    job.default_morph_weights = defaults;
    job.time = 0.25f;
    ASSERT_TRUE(job.run());
    EXPECT_EQ(weights[0], 0.1f);
    EXPECT_NEAR(weights[1], 0.25f, 1e-6f);
    EXPECT_NEAR(weights[2], 0.75f, 1e-6f);
    EXPECT_EQ(weights[3], 0.5f);
    EXPECT_EQ(weights[4], 0.5f);
    uint32_t bad = 99;
    EXPECT_EQ(check_clip(clip, 1, 5, &bad), DataError::weights_out_of_range);
    EXPECT_EQ(bad, 2u);
}

TEST(AnimSamplingJob, LoopWrapsForwardAndBackward) {
    const std::vector<int32_t> parents = {-1};
    const std::vector<Trs> rest = {identity_trs()};
    const Skeleton skeleton = make_skeleton(parents, rest);
    const std::vector<float> times = {0, 1, 2};
    const std::vector<float> values = {0, 0, 0, 1, 2, 3, 4, 0, 10};
    const std::vector<Channel> channels = {
        channel(0, Path::translation, Interp::linear, times, values)};
    const Clip clip = make_clip(channels, 2);
    auto sample = [&](float t, Wrap wrap) {
        Trs pose;
        SamplingJob job;
        job.skeleton = &skeleton;
        job.clip = &clip;
        job.locals = {&pose, 1};
        job.time = t;
        job.wrap = wrap;
        EXPECT_TRUE(job.run());
        return pose.translation[0];
    };
    EXPECT_FLOAT_EQ(sample(2.5f, Wrap::loop), sample(0.5f, Wrap::clamp));
    EXPECT_FLOAT_EQ(sample(-0.5f, Wrap::loop), sample(1.5f, Wrap::clamp));
    EXPECT_FLOAT_EQ(sample(6.25f, Wrap::loop), sample(0.25f, Wrap::clamp));
    EXPECT_FLOAT_EQ(sample(2.5f, Wrap::clamp), 4.0f);
    EXPECT_FLOAT_EQ(sample(std::nanf(""), Wrap::loop), 0.0f);
}

// The context is a cache: any sequence of times, forward, backward or jumping, and clip
// switches give bit-identical poses to sampling without it.
TEST(AnimSamplingJob, ContextCursorsMatchUncachedForwardBackwardAndJumps) {
    const std::vector<int32_t> parents = {-1, 0};
    const std::vector<Trs> rest = {identity_trs(), identity_trs()};
    const Skeleton skeleton = make_skeleton(parents, rest);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1, 1);
    std::vector<float> times, t3, q4;
    for (int k = 0; k < 50; ++k) {
        times.push_back(0.1f * float(k) + 0.02f * u(rng));
        t3.insert(t3.end(), {u(rng), u(rng), u(rng)});
        float q[4] = {u(rng), u(rng), u(rng), u(rng) + 2};
        const float l = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
        for (float& c : q) q4.push_back(c / l);
    }
    std::vector<float> cubic;
    for (int k = 0; k < 50; ++k)
        cubic.insert(cubic.end(), {u(rng), u(rng), u(rng), t3[3 * k], t3[3 * k + 1], t3[3 * k + 2],
                                   u(rng), u(rng), u(rng)});
    const std::vector<Channel> a = {channel(0, Path::translation, Interp::linear, times, t3),
                                    channel(1, Path::rotation, Interp::linear, times, q4),
                                    channel(1, Path::scale, Interp::cubic_spline, times, cubic)};
    const std::vector<Channel> b = {channel(1, Path::translation, Interp::step, times, t3)};
    const Clip clip_a = make_clip(a, 5), clip_b = make_clip(b, 5);
    uint32_t cursors[3] = {};
    SamplingContext context;
    context.cursors = cursors;
    std::vector<float> sequence;
    for (float t = -0.5f; t < 5.5f; t += 1.0f / 60) sequence.push_back(t);   // forward
    for (float t = 5.5f; t > -0.5f; t -= 1.0f / 30) sequence.push_back(t);   // backward
    for (int i = 0; i < 200; ++i) sequence.push_back(6.0f * u(rng) + 2.5f);  // jumps
    for (size_t i = 0; i < sequence.size(); ++i) {
        const Clip& clip = (i / 37) % 4 == 3 ? clip_b : clip_a;  // switch clips now and then
        Trs cached[2], plain[2];
        SamplingJob job;
        job.skeleton = &skeleton;
        job.clip = &clip;
        job.time = sequence[i];
        job.locals = cached;
        job.context = &context;
        ASSERT_TRUE(job.run());
        job.context = nullptr;
        job.locals = plain;
        ASSERT_TRUE(job.run());
        ASSERT_TRUE(same_trs(cached[0], plain[0]) && same_trs(cached[1], plain[1]))
            << "t = " << sequence[i];
    }
    // A corrupt cursor (past the keys) is harmless.
    cursors[0] = 1000000;
    Trs pose[2];
    SamplingJob job;
    job.skeleton = &skeleton;
    job.clip = &clip_a;
    job.time = 1.0f;
    job.locals = pose;
    job.context = &context;
    EXPECT_TRUE(job.run());
}

// Eberly's polynomial slerp against double-precision slerp, over the whole shortest arc.
TEST(AnimSamplingJob, SlerpMatchesExactSlerp) {
    const std::vector<int32_t> parents = {-1};
    const std::vector<Trs> rest = {identity_trs()};
    const Skeleton skeleton = make_skeleton(parents, rest);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-1, 1);
    double worst_all = 0, worst_120 = 0;
    for (int trial = 0; trial < 2000; ++trial) {
        glm::dquat a(u(rng), u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng), u(rng));
        a = glm::normalize(a);
        b = glm::normalize(b);
        const std::vector<float> times = {0, 1};
        const std::vector<float> values = {float(a.x), float(a.y), float(a.z), float(a.w),
                                           float(b.x), float(b.y), float(b.z), float(b.w)};
        const std::vector<Channel> channels = {
            channel(0, Path::rotation, Interp::linear, times, values)};
        const Clip clip = make_clip(channels, 1);
        const double s = (trial % 19 + 0.5) / 19.0;
        Trs pose;
        SamplingJob job;
        job.skeleton = &skeleton;
        job.clip = &clip;
        job.time = float(s);
        job.locals = {&pose, 1};
        ASSERT_TRUE(job.run());
        // Exact, from the float keys.
        glm::dquat fa(values[3], values[0], values[1], values[2]),
            fb(values[7], values[4], values[5], values[6]);
        fa = glm::normalize(fa);
        fb = glm::normalize(fb);
        double d = glm::dot(fa, fb);
        if (d < 0) {
            fb = -fb;
            d = -d;
        }
        const double theta = std::acos(std::min(d, 1.0));
        const glm::dquat want = glm::normalize(fa * (std::sin((1 - s) * theta) / std::sin(theta)) +
                                               fb * (std::sin(s * theta) / std::sin(theta)));
        glm::dquat got(pose.rotation[3], pose.rotation[0], pose.rotation[1], pose.rotation[2]);
        got = glm::normalize(got);
        if (glm::dot(want, got) < 0) got = -got;
        // Rotation angle between them, well conditioned near 0 (acos of a dot is not):
        // |q1 - q2| = 2 sin(angle / 4).
        const glm::dquat diff = got - want;
        const double chord = std::sqrt(glm::dot(diff, diff));
        const double angle = 4 * std::asin(std::min(1.0, chord / 2));
        worst_all = std::max(worst_all, angle);
        if (theta <= glm::radians(60.0))
            worst_120 = std::max(worst_120, angle);  // 120° rotation apart
    }
    std::printf("[slerp] worst angular error %.3g rad (keys up to 120 degrees apart: %.3g rad)\n",
                worst_all, worst_120);
    EXPECT_LT(worst_all, 2e-5);
    EXPECT_LT(worst_120, 2e-6);
}

}  // namespace
