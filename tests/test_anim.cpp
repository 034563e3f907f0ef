// Tests for anim/: clip sampling (glTF 2.0 §3.11 "Animation", Appendix C interpolation),
// local-to-model transforms, joint matrices and linear blend skinning, against hand-computed
// values.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <vector>

#include "anim/anim.h"

namespace {

using stipple::anim::Channel;
using stipple::anim::Clip;
using stipple::anim::Interp;
using stipple::anim::Path;
using stipple::anim::Skeleton;
using stipple::anim::SkinJob;
using stipple::anim::Trs;

constexpr float kEps = 1e-6f;
const float kHalfSqrt2 = std::sqrt(0.5f);  // cos 45° = sin 45°

Trs identity_trs() {
    return Trs{{0, 0, 0}, {0, 0, 0, 1}, {1, 1, 1}};
}

// A skeleton of `rest.size()` nodes with the given parents and no joints.
Skeleton make_skeleton(const std::vector<int32_t>& parents, const std::vector<Trs>& rest) {
    Skeleton s{};
    s.node_count = static_cast<uint32_t>(rest.size());
    s.parents = parents.data();
    s.rest = rest.data();
    return s;
}

Clip make_clip(const std::vector<Channel>& channels, float duration) {
    return Clip{"test", duration, static_cast<uint32_t>(channels.size()), channels.data()};
}

// Rotates v by the unit quaternion q (x, y, z, w).
glm::vec3 rotate(const float* q, glm::vec3 v) {
    return glm::quat(q[3], q[0], q[1], q[2]) * v;
}

void expect_vec3(const float* got, float x, float y, float z, float eps = kEps) {
    EXPECT_NEAR(got[0], x, eps);
    EXPECT_NEAR(got[1], y, eps);
    EXPECT_NEAR(got[2], z, eps);
}

void expect_mat4(const glm::mat4& got, const glm::mat4& want, float eps = 1e-5f) {
    for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) {
            EXPECT_NEAR(got[c][r], want[c][r], eps) << "column " << c << " row " << r;
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Sampling

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

    stipple::anim::sample_clip(skeleton, clip, 0.0f, &pose);
    expect_vec3(pose.translation, 0, 0, 0);
    stipple::anim::sample_clip(skeleton, clip, 0.5f, &pose);  // halfway between key 0 and 1
    expect_vec3(pose.translation, 1, 2, -3);
    stipple::anim::sample_clip(skeleton, clip, 1.0f, &pose);
    expect_vec3(pose.translation, 2, 4, -6);
    // 1.5: halfway between (2, 4, -6) and (4, 0, 10) = (3, 2, 2).
    stipple::anim::sample_clip(skeleton, clip, 1.5f, &pose);
    expect_vec3(pose.translation, 3, 2, 2);
    // 1.75: (2, 4, -6) + 0.75 * (2, -4, 16) = (3.5, 1, 6).
    stipple::anim::sample_clip(skeleton, clip, 1.75f, &pose);
    expect_vec3(pose.translation, 3.5f, 1, 6);
    stipple::anim::sample_clip(skeleton, clip, 2.0f, &pose);
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

    stipple::anim::sample_clip(skeleton, clip, -1.0f, &pose);
    expect_vec3(pose.translation, 0, 0, 0);
    stipple::anim::sample_clip(skeleton, clip, 2.5f, &pose);
    expect_vec3(pose.translation, 4, 0, 10);
    stipple::anim::sample_clip(skeleton, clip, 1e9f, &pose);
    expect_vec3(pose.translation, 4, 0, 10);
    stipple::anim::sample_clip(skeleton, clip, std::nanf(""), &pose);  // NaN samples the start
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
    stipple::anim::sample_clip(skeleton, clip, 0.25f, &pose);
    expect_vec3(pose.scale, 5, 5, 5);
    stipple::anim::sample_clip(skeleton, clip, 1.25f, &pose);  // 5 + 0.25 * 2
    expect_vec3(pose.scale, 5.5f, 5.5f, 5.5f);
    stipple::anim::sample_clip(skeleton, clip, 3.0f, &pose);
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

    stipple::anim::sample_clip(skeleton, clip, 0.0f, &pose);
    expect_vec3(pose.translation, 0, 0, 0);
    stipple::anim::sample_clip(skeleton, clip, 0.99f, &pose);
    expect_vec3(pose.translation, 0, 0, 0);
    stipple::anim::sample_clip(skeleton, clip, 1.0f, &pose);
    expect_vec3(pose.translation, 2, 4, -6);
    stipple::anim::sample_clip(skeleton, clip, 1.5f, &pose);
    expect_vec3(pose.translation, 2, 4, -6);
    stipple::anim::sample_clip(skeleton, clip, 2.0f, &pose);
    expect_vec3(pose.translation, 4, 0, 10);
    stipple::anim::sample_clip(skeleton, clip, -3.0f, &pose);
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
    stipple::anim::sample_clip(skeleton, clip, 0.5f, &pose);
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
    stipple::anim::sample_clip(skeleton, clip, 0.25f, &pose);
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
    stipple::anim::sample_clip(skeleton, clip, 0.5f, &pose);
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
    stipple::anim::sample_clip(skeleton, clip, 0.3f, &pose);
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
            stipple::anim::sample_clip(skeleton, clip, t, &pose);
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
    stipple::anim::sample_clip(skeleton, clip, 0.5f, pose);
    EXPECT_EQ(std::memcmp(&pose[0], &rest[0], sizeof(Trs)), 0);
    EXPECT_EQ(std::memcmp(&pose[2], &rest[2], sizeof(Trs)), 0);
    expect_vec3(pose[1].translation, 1, 2, -3);
    EXPECT_EQ(std::memcmp(pose[1].rotation, rest[1].rotation, sizeof(float) * 4), 0);
    EXPECT_EQ(std::memcmp(pose[1].scale, rest[1].scale, sizeof(float) * 3), 0);

    Trs copy[3];
    stipple::anim::rest_pose(skeleton, copy);
    EXPECT_EQ(std::memcmp(copy, rest.data(), sizeof(copy)), 0);
}

// ---------------------------------------------------------------------------------------------
// Local to model

TEST(AnimSkeleton, LocalToModelTwoNodeChain) {
    // Node 0 (root): T = (1, 2, 3), R = 90° about Z, S = 2.
    // Node 1 (child): T = (1, 0, 0), R = 90° about X, S = (1, 2, 3).
    const std::vector<int32_t> parents = {-1, 0};
    const std::vector<Trs> rest = {Trs{{1, 2, 3}, {0, 0, kHalfSqrt2, kHalfSqrt2}, {2, 2, 2}},
                                   Trs{{1, 0, 0}, {kHalfSqrt2, 0, 0, kHalfSqrt2}, {1, 2, 3}}};
    const Skeleton skeleton = make_skeleton(parents, rest);
    glm::mat4 model[2];
    stipple::anim::local_to_model(skeleton, rest.data(), model);

    // model0 = T * Rz(90) * S(2): Rz(90) maps x -> y, y -> -x, so the columns are
    // Rz * (2,0,0) = (0,2,0), Rz * (0,2,0) = (-2,0,0), (0,0,2), and T = (1,2,3).
    const glm::mat4 model0(0, 2, 0, 0,   // column 0
                           -2, 0, 0, 0,  // column 1
                           0, 0, 2, 0,   // column 2
                           1, 2, 3, 1);  // column 3
    expect_mat4(model[0], model0);

    // local1 = T(1,0,0) * Rx(90) * S(1,2,3): Rx(90) maps y -> z, z -> -y, so its columns are
    // (1,0,0), Rx * (0,2,0) = (0,0,2), Rx * (0,0,3) = (0,-3,0), T = (1,0,0).
    // model1 = model0 * local1 where model0's 3x3 maps (x,y,z) -> (-2y, 2x, 2z):
    //   column 0: A(1,0,0)  = (0,2,0)
    //   column 1: A(0,0,2)  = (0,0,4)
    //   column 2: A(0,-3,0) = (6,0,0)
    //   column 3: A(1,0,0) + (1,2,3) = (0,2,0) + (1,2,3) = (1,4,3)
    const glm::mat4 model1(0, 2, 0, 0,   //
                           0, 0, 4, 0,   //
                           6, 0, 0, 0,   //
                           1, 4, 3, 1);  //
    expect_mat4(model[1], model1);
}

TEST(AnimSkeleton, JointMatricesApplyInverseBind) {
    // Node 0 at (0, 5, 0); joint 0 is node 0 with inverse bind T(0, -5, 0): at rest the skin
    // matrix is the identity.
    const std::vector<int32_t> parents = {-1};
    std::vector<Trs> rest = {Trs{{0, 5, 0}, {0, 0, 0, 1}, {1, 1, 1}}};
    Skeleton skeleton = make_skeleton(parents, rest);
    const glm::mat4 inverse_bind = glm::translate(glm::mat4(1.0f), glm::vec3(0, -5, 0));
    const uint32_t joint_nodes[] = {0, 9};  // joint 1 names a node that does not exist
    float ibm[32];
    std::memcpy(ibm, &inverse_bind[0][0], 64);
    std::memcpy(ibm + 16, &inverse_bind[0][0], 64);
    skeleton.joint_count = 2;
    skeleton.joint_nodes = joint_nodes;
    skeleton.inverse_bind = ibm;

    glm::mat4 model[1];
    glm::mat4 skin[2];
    stipple::anim::local_to_model(skeleton, rest.data(), model);
    stipple::anim::joint_matrices(skeleton, model, skin);
    expect_mat4(skin[0], glm::mat4(1.0f));
    expect_mat4(skin[1], glm::mat4(1.0f));  // bad node: stays in bind pose

    // Move node 0 up by 1: the skin matrix is T(0, 1, 0).
    rest[0].translation[1] = 6;
    stipple::anim::local_to_model(skeleton, rest.data(), model);
    stipple::anim::joint_matrices(skeleton, model, skin);
    expect_mat4(skin[0], glm::translate(glm::mat4(1.0f), glm::vec3(0, 1, 0)));
}

// ---------------------------------------------------------------------------------------------
// Skinning

SkinJob make_job(uint32_t vertex_count, const glm::mat4* skin, uint32_t joint_count,
                 const uint16_t* joints, const float* weights, const float* in_positions,
                 const float* in_normals, float* out_positions, float* out_normals) {
    return SkinJob{vertex_count, skin,       joint_count,   joints,     weights,
                   in_positions, in_normals, out_positions, out_normals};
}

TEST(AnimSkinning, HalfBlendOfRotatedJointThroughThePipeline) {
    // Two nodes = two joints. Node 0 is the root at the origin. Node 1 is its child at (0, 1, 0)
    // and is rotated 90° about Z by the clip: a pivot at (0, 1, 0). Inverse bind matrices:
    // identity and T(0, -1, 0).
    const std::vector<int32_t> parents = {-1, 0};
    const std::vector<Trs> rest = {identity_trs(), Trs{{0, 1, 0}, {0, 0, 0, 1}, {1, 1, 1}}};
    Skeleton skeleton = make_skeleton(parents, rest);
    const uint32_t joint_nodes[] = {0, 1};
    const glm::mat4 ib0(1.0f);
    const glm::mat4 ib1 = glm::translate(glm::mat4(1.0f), glm::vec3(0, -1, 0));
    float ibm[32];
    std::memcpy(ibm, &ib0[0][0], 64);
    std::memcpy(ibm + 16, &ib1[0][0], 64);
    skeleton.joint_count = 2;
    skeleton.joint_nodes = joint_nodes;
    skeleton.inverse_bind = ibm;

    const float times[] = {0.0f};
    const float rot[] = {0, 0, kHalfSqrt2, kHalfSqrt2};  // 90° about Z
    const std::vector<Channel> channels = {{1, Path::rotation, Interp::linear, 1, times, rot}};
    const Clip clip = make_clip(channels, 1.0f);

    Trs locals[2];
    glm::mat4 model[2];
    glm::mat4 skin[2];
    stipple::anim::sample_clip(skeleton, clip, 0.0f, locals);
    stipple::anim::local_to_model(skeleton, locals, model);
    stipple::anim::joint_matrices(skeleton, model, skin);

    // Vertex (1, 2, 0), weights 0.5 / 0.5, normal (1, 0, 0).
    //   joint 0 (identity):          p0 = (1, 2, 0),  n0 = (1, 0, 0)
    //   joint 1 (Rz90 about (0,1,0)): p - pivot = (1, 1, 0); Rz90 (x,y) -> (-y,x) gives (-1, 1, 0);
    //                                 + pivot = p1 = (-1, 2, 0);  n1 = Rz90 (1,0,0) = (0, 1, 0)
    //   position: 0.5 * (1,2,0) + 0.5 * (-1,2,0) = (0, 2, 0)
    //   normal:   0.5 * (1,0,0) + 0.5 * (0,1,0) = (0.5, 0.5, 0), normalised (0.70711, 0.70711, 0)
    const uint16_t joints[] = {0, 1, 0, 0};
    const float weights[] = {0.5f, 0.5f, 0.0f, 0.0f};
    const float in_p[] = {1, 2, 0};
    const float in_n[] = {1, 0, 0};
    float out_p[3];
    float out_n[3];
    stipple::anim::skin_lbs(make_job(1, skin, 2, joints, weights, in_p, in_n, out_p, out_n));
    expect_vec3(out_p, 0.0f, 2.0f, 0.0f, 1e-5f);
    expect_vec3(out_n, 0.70710678f, 0.70710678f, 0.0f, 1e-5f);
}

TEST(AnimSkinning, SeveralVerticesAgainstHandComputedValues) {
    // skin[0] = identity, skin[1] = rotation 90° about Z around pivot (0, 1, 0)
    //         = T(0,1,0) * Rz(90) * T(0,-1,0), skin[2] = T(2, -1, 5).
    glm::mat4 skin[3];
    skin[0] = glm::mat4(1.0f);
    skin[1] = glm::mat4(0, 1, 0, 0,   // Rz90 * (1,0,0) = (0,1,0)
                        -1, 0, 0, 0,  // Rz90 * (0,1,0) = (-1,0,0)
                        0, 0, 1, 0,   //
                        1, 1, 0, 1);  // pivot - Rz90 * pivot = (0,1,0) - (-1,0,0) = (1,1,0)
    skin[2] = glm::translate(glm::mat4(1.0f), glm::vec3(2, -1, 5));

    const uint16_t joints[] = {
        0, 1, 0, 0,  // v0: half identity, half rotated
        2, 0, 0, 0,  // v1: weight 1 on the translated joint
        1, 0, 0, 0,  // v2: weight 1 on the rotated joint
        0, 1, 2, 0,  // v3: 0.25 / 0.25 / 0.5
    };
    const float weights[] = {
        0.5f,  0.5f,  0.0f, 0.0f,  //
        1.0f,  0.0f,  0.0f, 0.0f,  //
        1.0f,  0.0f,  0.0f, 0.0f,  //
        0.25f, 0.25f, 0.5f, 0.0f,  //
    };
    const float in_p[] = {1, 2, 0, /**/ 1, 1, 1, /**/ 0, 1, 7, /**/ 1, 2, 0};
    const float in_n[] = {1, 0, 0, /**/ 0, 0, 1, /**/ 0, 1, 0, /**/ 0, 0, 1};
    float out_p[12];
    float out_n[12];
    stipple::anim::skin_lbs(make_job(4, skin, 3, joints, weights, in_p, in_n, out_p, out_n));

    // v0: (see previous test) p = 0.5 (1,2,0) + 0.5 (-1,2,0) = (0,2,0);
    //     n = normalize(0.5 (1,0,0) + 0.5 (0,1,0)) = (0.70711, 0.70711, 0)
    expect_vec3(out_p + 0, 0, 2, 0);
    expect_vec3(out_n + 0, 0.70710678f, 0.70710678f, 0);
    // v1: (1,1,1) + (2,-1,5) = (3,0,6); a translation leaves the normal (0,0,1) unchanged.
    expect_vec3(out_p + 3, 3, 0, 6);
    expect_vec3(out_n + 3, 0, 0, 1);
    // v2: the pivot itself (0,1,7) does not move; n = Rz90 (0,1,0) = (-1,0,0).
    expect_vec3(out_p + 6, 0, 1, 7);
    expect_vec3(out_n + 6, -1, 0, 0);
    // v3: p = 0.25 (1,2,0) + 0.25 (-1,2,0) + 0.5 ((1,2,0) + (2,-1,5))
    //       = (0.25, 0.5, 0) + (-0.25, 0.5, 0) + (1.5, 0.5, 2.5) = (1.5, 1.5, 2.5);
    //     n: all three joints leave (0,0,1) as it is -> (0,0,1).
    expect_vec3(out_p + 9, 1.5f, 1.5f, 2.5f);
    expect_vec3(out_n + 9, 0, 0, 1);
}

TEST(AnimSkinning, OutOfRangeJointIndexUsesJointZero) {
    // skin[0] = T(1, 0, 0), skin[1] = T(0, 10, 0). Indices 2, 7 and 65535 are past joint_count
    // = 2, so they read skin[0].
    glm::mat4 skin[2];
    skin[0] = glm::translate(glm::mat4(1.0f), glm::vec3(1, 0, 0));
    skin[1] = glm::translate(glm::mat4(1.0f), glm::vec3(0, 10, 0));
    const uint16_t joints[] = {
        7,     0, 0, 0,  // v0: all weight on a bad index -> T(1,0,0)
        65535, 1, 2, 0,  // v1: 0.5 bad (-> joint 0), 0.5 on joint 1
    };
    const float weights[] = {1, 0, 0, 0, /**/ 0.5f, 0.5f, 0, 0};
    const float in_p[] = {0, 0, 0, /**/ 2, 2, 2};
    const float in_n[] = {0, 1, 0, /**/ 1, 0, 0};
    float out_p[6];
    float out_n[6];
    stipple::anim::skin_lbs(make_job(2, skin, 2, joints, weights, in_p, in_n, out_p, out_n));
    expect_vec3(out_p + 0, 1, 0, 0);
    expect_vec3(out_n + 0, 0, 1, 0);
    // v1: 0.5 ((2,2,2) + (1,0,0)) + 0.5 ((2,2,2) + (0,10,0)) = (1.5,1,1) + (1,6,1) = (2.5,7,2)
    expect_vec3(out_p + 3, 2.5f, 7, 2);
    expect_vec3(out_n + 3, 1, 0, 0);
}

TEST(AnimSkinning, NoJointsLeavesTheBindPose) {
    const uint16_t joints[] = {3, 0, 0, 0};
    const float weights[] = {1, 0, 0, 0};
    const float in_p[] = {1, 2, 3};
    const float in_n[] = {0, 0, 1};
    float out_p[3];
    float out_n[3];
    stipple::anim::skin_lbs(make_job(1, nullptr, 0, joints, weights, in_p, in_n, out_p, out_n));
    expect_vec3(out_p, 1, 2, 3);
    expect_vec3(out_n, 0, 0, 1);
}

TEST(AnimSkinning, ZeroNormalStaysFinite) {
    const glm::mat4 skin[1] = {glm::mat4(1.0f)};
    const uint16_t joints[] = {0, 0, 0, 0};
    const float weights[] = {1, 0, 0, 0};
    const float in_p[] = {1, 2, 3};
    const float in_n[] = {0, 0, 0};
    float out_p[3];
    float out_n[3];
    stipple::anim::skin_lbs(make_job(1, skin, 1, joints, weights, in_p, in_n, out_p, out_n));
    expect_vec3(out_p, 1, 2, 3);
    expect_vec3(out_n, 0, 0, 0);
}

}  // namespace
