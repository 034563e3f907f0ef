// Tests for the anim/ jobs added for issue 4: SamplingJob (context, CUBICSPLINE, weights,
// wrap), BlendingJob, MorphJob, SkinningJob (LBS/DQS, SIMD vs scalar), dqs_joints and the
// load-time checks. One section per job, each with its JobValidity test (ozz style).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <random>
#include <vector>

#include "anim/anim.h"

namespace {

using namespace stipple::anim;

Trs identity_trs() { return Trs{{0, 0, 0}, {0, 0, 0, 1}, {1, 1, 1}}; }

Skeleton make_skeleton(const std::vector<int32_t>& parents, const std::vector<Trs>& rest) {
    Skeleton s{};
    s.node_count = uint32_t(rest.size());
    s.parents = parents.data();
    s.rest = rest.data();
    return s;
}

Channel channel(uint32_t node, Path path, Interp interp, const std::vector<float>& times,
                const std::vector<float>& values, uint32_t weight_begin = 0,
                uint32_t weight_count = 0) {
    return Channel{node, path, interp, uint32_t(times.size()), times.data(), values.data(),
                   weight_begin, weight_count};
}

Clip make_clip(const std::vector<Channel>& channels, float duration) {
    return Clip{"test", duration, uint32_t(channels.size()), channels.data()};
}

bool same_trs(const Trs& a, const Trs& b) { return std::memcmp(&a, &b, sizeof(Trs)) == 0; }

// ---------------------------------------------------------------------------------------
// SamplingJob

TEST(AnimSamplingJob, JobValidity) {
    const std::vector<int32_t> parents = {-1, 0};
    const std::vector<Trs> rest = {identity_trs(), identity_trs()};
    const Skeleton skeleton = make_skeleton(parents, rest);
    const std::vector<float> times = {0, 1};
    const std::vector<float> values = {0, 0, 0, 1, 1, 1};
    const std::vector<Channel> channels = {channel(1, Path::translation, Interp::linear, times, values)};
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
    const std::vector<float> values = {9, 9, 9, /**/ 1, 0, 2, /**/ 0.5f, 1, 0,   // key 0: a, v, b
                                       -1, 1, 0, /**/ 3, 0, 2, /**/ 9, 9, 9};    // key 1
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
    const std::vector<Channel> channels = {channel(0, Path::rotation, Interp::cubic_spline, times, values)};
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
    const std::vector<float> lin = {0, 1, /**/ 1, 0};           // 2 slots per key
    const std::vector<float> step = {0.5f, /**/ 0.75f};          // 1 slot per key
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
    const std::vector<Channel> channels = {channel(0, Path::translation, Interp::linear, times, values)};
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
    for (int k = 0; k < 50; ++k) cubic.insert(cubic.end(), {u(rng), u(rng), u(rng), t3[3 * k], t3[3 * k + 1], t3[3 * k + 2], u(rng), u(rng), u(rng)});
    const std::vector<Channel> a = {channel(0, Path::translation, Interp::linear, times, t3),
                                    channel(1, Path::rotation, Interp::linear, times, q4),
                                    channel(1, Path::scale, Interp::cubic_spline, times, cubic)};
    const std::vector<Channel> b = {channel(1, Path::translation, Interp::step, times, t3)};
    const Clip clip_a = make_clip(a, 5), clip_b = make_clip(b, 5);
    uint32_t cursors[3] = {};
    SamplingContext context;
    context.cursors = cursors;
    std::vector<float> sequence;
    for (float t = -0.5f; t < 5.5f; t += 1.0f / 60) sequence.push_back(t);     // forward
    for (float t = 5.5f; t > -0.5f; t -= 1.0f / 30) sequence.push_back(t);     // backward
    for (int i = 0; i < 200; ++i) sequence.push_back(6.0f * u(rng) + 2.5f);   // jumps
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
        const std::vector<Channel> channels = {channel(0, Path::rotation, Interp::linear, times, values)};
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
        glm::dquat fa(values[3], values[0], values[1], values[2]), fb(values[7], values[4], values[5], values[6]);
        fa = glm::normalize(fa);
        fb = glm::normalize(fb);
        double d = glm::dot(fa, fb);
        if (d < 0) {
            fb = -fb;
            d = -d;
        }
        const double theta = std::acos(std::min(d, 1.0));
        const glm::dquat want = glm::normalize(
            fa * (std::sin((1 - s) * theta) / std::sin(theta)) + fb * (std::sin(s * theta) / std::sin(theta)));
        glm::dquat got(pose.rotation[3], pose.rotation[0], pose.rotation[1], pose.rotation[2]);
        got = glm::normalize(got);
        if (glm::dot(want, got) < 0) got = -got;
        // Rotation angle between them, well conditioned near 0 (acos of a dot is not):
        // |q1 - q2| = 2 sin(angle / 4).
        const glm::dquat diff = got - want;
        const double chord = std::sqrt(glm::dot(diff, diff));
        const double angle = 4 * std::asin(std::min(1.0, chord / 2));
        worst_all = std::max(worst_all, angle);
        if (theta <= glm::radians(60.0)) worst_120 = std::max(worst_120, angle);  // 120° rotation apart
    }
    std::printf("[slerp] worst angular error %.3g rad (keys up to 120 degrees apart: %.3g rad)\n",
                worst_all, worst_120);
    EXPECT_LT(worst_all, 2e-5);
    EXPECT_LT(worst_120, 2e-6);
}

TEST(AnimDataChecks, RejectNamedProblems) {
    const std::vector<float> times = {0, 1};
    const std::vector<float> bad_times = {1, 1};
    const std::vector<float> values = {0, 0, 0, 1, 1, 1};
    const std::vector<float> nan_values = {0, 0, 0, 1, std::nanf(""), 1};
    uint32_t bad = 0;
    std::vector<Channel> c = {channel(0, Path::translation, Interp::linear, times, values)};
    EXPECT_EQ(check_clip(make_clip(c, 1), 1, 0, &bad), DataError::ok);
    EXPECT_EQ(check_clip(make_clip(c, 1), 0, 0, &bad), DataError::node_out_of_range);
    c = {channel(0, Path::translation, Interp::linear, bad_times, values)};
    EXPECT_EQ(check_clip(make_clip(c, 1), 1, 0, &bad), DataError::times_not_increasing);
    c = {channel(0, Path::translation, Interp::linear, times, nan_values)};
    EXPECT_EQ(check_clip(make_clip(c, 1), 1, 0, &bad), DataError::non_finite_value);
    c = {channel(0, Path(7), Interp::linear, times, values)};
    EXPECT_EQ(check_clip(make_clip(c, 1), 1, 0, &bad), DataError::bad_path);
    c = {channel(0, Path::translation, Interp::linear, {}, values)};
    EXPECT_EQ(check_clip(make_clip(c, 1), 1, 0, &bad), DataError::no_keys);
    EXPECT_STREQ(data_error_name(DataError::times_not_increasing), "times_not_increasing");

    const std::vector<int32_t> parents = {-1, 1};
    const std::vector<Trs> rest = {identity_trs(), identity_trs()};
    EXPECT_EQ(check_skeleton(make_skeleton(parents, rest)), DataError::parent_out_of_range);
    const std::vector<float> deltas = {1, 1, 1};
    const MorphTarget target{0, 2, 1, deltas.data(), nullptr};
    const float w = 0;
    const Morph morph{1, &w, 1, &target};
    EXPECT_EQ(check_morph(morph, 3), DataError::ok);
    EXPECT_EQ(check_morph(morph, 2), DataError::target_out_of_range);
}

// ---------------------------------------------------------------------------------------
// BlendingJob

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
    const Trs a[2] = {Trs{{4, 0, 0}, {0, 0, h, h}, {2, 2, 2}}, Trs{{4, 0, 0}, {0, 0, 0, 1}, {1, 1, 1}}};
    const Trs b[2] = {Trs{{0, 4, 0}, {0, 0, -h, -h}, {1, 1, 1}}, Trs{{0, 4, 0}, {0, 0, 0, 1}, {1, 1, 1}}};
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

// ---------------------------------------------------------------------------------------
// MorphJob

TEST(AnimMorphJob, JobValidityAndWeightedDeltasInPlace) {
    const std::vector<float> d0 = {1, 0, 0, 2, 0, 0};  // vertices 1..2
    const std::vector<float> n0 = {0, 1, 0, 0, 1, 0};
    const std::vector<float> d1 = {0, 0, 4};           // vertex 2
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

// ---------------------------------------------------------------------------------------
// SkinningJob

struct RandomMesh {
    std::vector<uint16_t> joints;
    std::vector<float> weights, positions, normals;
    RandomMesh(uint32_t n, uint32_t joint_count, uint32_t seed) {
        std::mt19937 rng(seed);
        std::uniform_real_distribution<float> u(-1, 1);
        for (uint32_t v = 0; v < n; ++v) {
            const int influences = 1 + int(v / 5 % 4);  // runs of 1..4 influences
            float w[4] = {0, 0, 0, 0}, sum = 0;
            for (int k = 0; k < influences; ++k) sum += (w[k] = u(rng) + 1.1f);
            for (int k = 0; k < 4; ++k) {
                joints.push_back(uint16_t(rng() % (joint_count + 1)));  // some out of range
                weights.push_back(w[k] / sum);
            }
            float nrm[3] = {u(rng), u(rng), u(rng) + 2};
            const float l = std::sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
            for (int c = 0; c < 3; ++c) {
                positions.push_back(2 * u(rng));
                normals.push_back(nrm[c] / l);
            }
        }
    }
};

std::vector<glm::mat4> random_palette(uint32_t n, bool scaled, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1, 1);
    std::vector<glm::mat4> palette;
    for (uint32_t j = 0; j < n; ++j) {
        glm::mat4 m = glm::translate(glm::mat4(1), glm::vec3(u(rng), u(rng), u(rng)));
        m = glm::rotate(m, 3.0f * u(rng), glm::normalize(glm::vec3(u(rng), u(rng), u(rng) + 0.01f)));
        if (scaled) m = glm::scale(m, glm::vec3(1 + 0.3f * u(rng), 1 + 0.3f * u(rng), 1));
        palette.push_back(m);
    }
    return palette;
}

SkinningJob make_skinning(Skinning method, const RandomMesh& mesh, const std::vector<glm::mat4>& palette,
                          const std::vector<DqsJoint>& dq, std::vector<float>* out_p,
                          std::vector<float>* out_n) {
    SkinningJob job;
    job.method = method;
    job.vertex_count = uint32_t(mesh.positions.size() / 3);
    job.joint_matrices = {palette.data(), palette.size()};
    job.dq_joints = {dq.data(), dq.size()};
    job.joints = {mesh.joints.data(), mesh.joints.size()};
    job.weights = {mesh.weights.data(), mesh.weights.size()};
    job.in_positions = {mesh.positions.data(), mesh.positions.size()};
    job.in_normals = {mesh.normals.data(), mesh.normals.size()};
    out_p->assign(mesh.positions.size(), 0.0f);
    out_n->assign(mesh.normals.size(), 0.0f);
    job.out_positions = {out_p->data(), out_p->size()};
    job.out_normals = {out_n->data(), out_n->size()};
    return job;
}

TEST(AnimSkinningJob, JobValidity) {
    const RandomMesh mesh(10, 3, 1);
    const std::vector<glm::mat4> palette = random_palette(3, false, 2);
    const std::vector<DqsJoint> dq;
    std::vector<float> op, on;
    SkinningJob job = make_skinning(Skinning::lbs, mesh, palette, dq, &op, &on);
    EXPECT_TRUE(job.validate());
    job.method = Skinning::dqs;  // no DQS palette
    EXPECT_FALSE(job.run());
    EXPECT_EQ(op[0], 0.0f);  // untouched
    job.method = Skinning(9);
    EXPECT_FALSE(job.validate());
    job.method = Skinning::lbs;
    job.weights.size -= 1;
    EXPECT_FALSE(job.validate());
    job.weights.size += 1;
    job.out_positions.size -= 1;
    EXPECT_FALSE(job.validate());
    job.out_positions.size += 1;
    job.out_normals = {};
    EXPECT_FALSE(job.validate());  // normals in, none out
    job.in_normals = {};
    EXPECT_TRUE(job.validate());   // positions only
    job.out_positions = {const_cast<float*>(mesh.positions.data()) + 3, mesh.positions.size() - 3};
    EXPECT_FALSE(job.validate());  // overlaps its input
    job.joint_matrices = {};
    EXPECT_FALSE(job.validate());
    job.vertex_count = 0;
    EXPECT_TRUE(job.run());  // nothing to do
}

// SIMD (blocks of 4, per-block influence count) vs the scalar reference, LBS and DQS, with
// a tail that is not a multiple of 4, out-of-range joints, in place and positions-only.
TEST(AnimSkinningJob, SimdMatchesScalar) {
    const RandomMesh mesh(203, 7, 5);
    for (bool scaled : {false, true}) {
        const std::vector<glm::mat4> palette = random_palette(7, scaled, 9);
        std::vector<DqsJoint> dq(7);
        uint32_t stretched = 0;
        ASSERT_TRUE(dqs_joints({palette.data(), palette.size()}, {dq.data(), dq.size()}, &stretched));
        EXPECT_EQ(stretched == 0, !scaled);
        for (Skinning method : {Skinning::lbs, Skinning::dqs}) {
            std::vector<float> sp, sn, vp, vn;
            SkinningJob job = make_skinning(method, mesh, palette, dq, &sp, &sn);
            job.dq_rigid = stretched == 0;
            ASSERT_TRUE(job.run_scalar());
            SkinningJob simd_job = make_skinning(method, mesh, palette, dq, &vp, &vn);
            simd_job.dq_rigid = job.dq_rigid;
            ASSERT_TRUE(simd_job.run());
            for (size_t i = 0; i < sp.size(); ++i) {
                ASSERT_NEAR(vp[i], sp[i], 2e-5f) << "position float " << i << " method " << int(method);
                ASSERT_NEAR(vn[i], sn[i], 2e-5f) << "normal float " << i;
            }
            // In place, positions and normals.
            std::vector<float> ip = mesh.positions, in = mesh.normals;
            simd_job.in_positions = {ip.data(), ip.size()};
            simd_job.out_positions = {ip.data(), ip.size()};
            simd_job.in_normals = {in.data(), in.size()};
            simd_job.out_normals = {in.data(), in.size()};
            ASSERT_TRUE(simd_job.run());
            EXPECT_EQ(ip, vp);
            EXPECT_EQ(in, vn);
            // Positions only.
            std::vector<float> po(mesh.positions.size());
            simd_job.in_positions = {mesh.positions.data(), mesh.positions.size()};
            simd_job.out_positions = {po.data(), po.size()};
            simd_job.in_normals = {};
            simd_job.out_normals = {};
            ASSERT_TRUE(simd_job.run());
            EXPECT_EQ(po, vp);
        }
    }
    std::printf("[skinning] SIMD path: %s\n", simd_path());
}

// For rigid joint matrices, DQS reproduces LBS exactly where LBS is exact: one influence,
// or every influence on joints with the same transform.
TEST(AnimSkinningJob, DqsEqualsLbsOnRigidTransforms) {
    RandomMesh mesh(64, 4, 11);
    std::vector<glm::mat4> palette = random_palette(4, false, 12);
    palette[2] = palette[1];  // joints 1 and 2 move together
    for (size_t v = 0; v < 64; ++v) {
        if (v % 2 == 0) {
            // One influence.
            mesh.weights[4 * v] = 1;
            for (int k = 1; k < 4; ++k) mesh.weights[4 * v + size_t(k)] = 0;
            mesh.joints[4 * v] = uint16_t(v % 4);
        } else {
            for (int k = 0; k < 4; ++k) mesh.joints[4 * v + size_t(k)] = uint16_t(1 + k % 2);
        }
    }
    std::vector<DqsJoint> dq(4);
    uint32_t stretched = 1;
    ASSERT_TRUE(dqs_joints({palette.data(), 4}, {dq.data(), 4}, &stretched));
    EXPECT_EQ(stretched, 0u);
    std::vector<float> lp, ln, dp, dn;
    ASSERT_TRUE(make_skinning(Skinning::lbs, mesh, palette, dq, &lp, &ln).run());
    SkinningJob dqs = make_skinning(Skinning::dqs, mesh, palette, dq, &dp, &dn);
    dqs.dq_rigid = true;
    ASSERT_TRUE(dqs.run());
    for (size_t i = 0; i < lp.size(); ++i) {
        EXPECT_NEAR(dp[i], lp[i], 1e-5f) << i;
        EXPECT_NEAR(dn[i], ln[i], 1e-5f) << i;
    }
}

// The candy-wrapper test (Kavan et al. 2007 Fig. 1): a tube along x twisted 90 degrees
// about its axis by the second joint, weights blending over the middle. At the middle ring
// LBS averages identity and the 90-degree rotation, shrinking the radius to cos 45 = 0.707;
// DQS rotates by 45 degrees and keeps it.
TEST(AnimSkinningJob, DqsKeepsVolumeUnderTwistWhereLbsCollapses) {
    std::vector<float> positions, normals, weights;
    std::vector<uint16_t> joints;
    const int rings = 9, sides = 16;
    for (int r = 0; r < rings; ++r) {
        const float x = -1.0f + 2.0f * float(r) / float(rings - 1);
        const float w1 = std::min(std::max(x + 0.5f, 0.0f), 1.0f);
        for (int s = 0; s < sides; ++s) {
            const float a = 6.2831853f * float(s) / float(sides);
            positions.insert(positions.end(), {x, std::cos(a), std::sin(a)});
            normals.insert(normals.end(), {0, std::cos(a), std::sin(a)});
            joints.insert(joints.end(), {0, 1, 0, 0});
            weights.insert(weights.end(), {1 - w1, w1, 0, 0});
        }
    }
    const std::vector<glm::mat4> palette = {
        glm::mat4(1), glm::rotate(glm::mat4(1), glm::radians(90.0f), glm::vec3(1, 0, 0))};
    std::vector<DqsJoint> dq(2);
    uint32_t stretched = 1;
    ASSERT_TRUE(dqs_joints({palette.data(), 2}, {dq.data(), 2}, &stretched));
    ASSERT_EQ(stretched, 0u);
    auto middle_radius = [&](Skinning method) {
        const uint32_t n = uint32_t(positions.size() / 3);
        std::vector<float> out(positions.size()), out_n(normals.size());
        SkinningJob job;
        job.method = method;
        job.vertex_count = n;
        job.joint_matrices = {palette.data(), 2};
        job.dq_joints = {dq.data(), 2};
        job.dq_rigid = true;
        job.joints = {joints.data(), joints.size()};
        job.weights = {weights.data(), weights.size()};
        job.in_positions = {positions.data(), positions.size()};
        job.in_normals = {normals.data(), normals.size()};
        job.out_positions = {out.data(), out.size()};
        job.out_normals = {out_n.data(), out_n.size()};
        EXPECT_TRUE(job.run());
        float radius = 1e9f;
        const int mid = rings / 2;  // x = 0, weights 0.5 / 0.5
        for (int s = 0; s < sides; ++s) {
            const float* p = &out[3 * size_t(mid * sides + s)];
            radius = std::min(radius, std::sqrt(p[1] * p[1] + p[2] * p[2]));
        }
        return radius;
    };
    const float lbs = middle_radius(Skinning::lbs);
    const float dqs = middle_radius(Skinning::dqs);
    std::printf("[twist] middle ring radius: LBS %.4f, DQS %.4f (rest 1)\n", lbs, dqs);
    EXPECT_LT(lbs, 0.8f);
    EXPECT_NEAR(lbs, std::sqrt(0.5f), 1e-4f);
    EXPECT_GE(dqs, 0.95f);
}

// Non-rigid joints: S is blended linearly and applied before the dual quaternion; with one
// influence that is exactly the joint matrix.
TEST(AnimSkinningJob, DqsAppliesStretchOfScaledJoints) {
    RandomMesh mesh(33, 3, 21);
    for (size_t v = 0; v < 33; ++v) {
        mesh.weights[4 * v] = 1;
        for (int k = 1; k < 4; ++k) mesh.weights[4 * v + size_t(k)] = 0;
        mesh.joints[4 * v] = uint16_t(v % 3);
    }
    const std::vector<glm::mat4> palette = random_palette(3, true, 22);
    std::vector<DqsJoint> dq(3);
    uint32_t stretched = 0;
    ASSERT_TRUE(dqs_joints({palette.data(), 3}, {dq.data(), 3}, &stretched));
    EXPECT_EQ(stretched, 3u);
    std::vector<float> lp, ln, dp, dn;
    ASSERT_TRUE(make_skinning(Skinning::lbs, mesh, palette, dq, &lp, &ln).run());
    ASSERT_TRUE(make_skinning(Skinning::dqs, mesh, palette, dq, &dp, &dn).run());
    for (size_t i = 0; i < lp.size(); ++i) {
        EXPECT_NEAR(dp[i], lp[i], 1e-5f) << i;
        EXPECT_NEAR(dn[i], ln[i], 1e-5f) << i;
    }
}

// The hierarchy jobs check their spans.
TEST(AnimHierarchyJobs, JobValidity) {
    const std::vector<int32_t> parents = {-1, 0};
    const std::vector<Trs> rest = {identity_trs(), identity_trs()};
    Skeleton skeleton = make_skeleton(parents, rest);
    const uint32_t joint_nodes[1] = {1};
    const float ibm[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    skeleton.joint_count = 1;
    skeleton.joint_nodes = joint_nodes;
    skeleton.inverse_bind = ibm;
    glm::mat4 models[2], palette[1];
    LocalToModelJob l2m;
    l2m.skeleton = &skeleton;
    l2m.locals = {rest.data(), 1};
    l2m.models = models;
    EXPECT_FALSE(l2m.run());
    l2m.locals = {rest.data(), 2};
    EXPECT_TRUE(l2m.run());
    JointMatrixJob jm;
    jm.skeleton = &skeleton;
    jm.models = {models, 1};
    jm.joint_matrices = palette;
    EXPECT_FALSE(jm.run());
    jm.models = models;
    EXPECT_TRUE(jm.run());
    EXPECT_EQ(palette[0], glm::mat4(1));
    jm.joint_matrices = {};
    EXPECT_FALSE(jm.validate());
}

}  // namespace
