// SkinningJob (anim/anim.h): linear blend skinning against hand-computed values, SIMD vs
// the scalar reference, dual-quaternion skinning (Kavan et al. 2007), and its span checks.
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
    sample_pose(skeleton, clip, 0.0f, locals);
    model_matrices(skeleton, locals, model);
    skin_matrices(skeleton, model, skin);

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
    ASSERT_TRUE(lbs_job(1, skin, 2, joints, weights, in_p, in_n, out_p, out_n).run());
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
    ASSERT_TRUE(lbs_job(4, skin, 3, joints, weights, in_p, in_n, out_p, out_n).run());

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
    ASSERT_TRUE(lbs_job(2, skin, 2, joints, weights, in_p, in_n, out_p, out_n).run());
    expect_vec3(out_p + 0, 1, 0, 0);
    expect_vec3(out_n + 0, 0, 1, 0);
    // v1: 0.5 ((2,2,2) + (1,0,0)) + 0.5 ((2,2,2) + (0,10,0)) = (1.5,1,1) + (1,6,1) = (2.5,7,2)
    expect_vec3(out_p + 3, 2.5f, 7, 2);
    expect_vec3(out_n + 3, 1, 0, 0);
}

// Without a joint there is nothing to skin by: the job refuses (the unchecked API this replaced
// copied the bind pose) and leaves the outputs as they were.
TEST(AnimSkinning, NoJointsIsRejectedAndTheOutputIsUntouched) {
    const uint16_t joints[] = {3, 0, 0, 0};
    const float weights[] = {1, 0, 0, 0};
    const float in_p[] = {1, 2, 3};
    const float in_n[] = {0, 0, 1};
    float out_p[3] = {7, 7, 7};
    float out_n[3] = {7, 7, 7};
    const SkinningJob job = lbs_job(1, nullptr, 0, joints, weights, in_p, in_n, out_p, out_n);
    EXPECT_FALSE(job.validate());
    EXPECT_FALSE(job.run());
    expect_vec3(out_p, 7, 7, 7);
    expect_vec3(out_n, 7, 7, 7);
}

TEST(AnimSkinning, ZeroNormalStaysFinite) {
    const glm::mat4 skin[1] = {glm::mat4(1.0f)};
    const uint16_t joints[] = {0, 0, 0, 0};
    const float weights[] = {1, 0, 0, 0};
    const float in_p[] = {1, 2, 3};
    const float in_n[] = {0, 0, 0};
    float out_p[3];
    float out_n[3];
    ASSERT_TRUE(lbs_job(1, skin, 1, joints, weights, in_p, in_n, out_p, out_n).run());
    expect_vec3(out_p, 1, 2, 3);
    expect_vec3(out_n, 0, 0, 0);
}

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
        m = glm::rotate(m, 3.0f * u(rng),
                        glm::normalize(glm::vec3(u(rng), u(rng), u(rng) + 0.01f)));
        if (scaled) m = glm::scale(m, glm::vec3(1 + 0.3f * u(rng), 1 + 0.3f * u(rng), 1));
        palette.push_back(m);
    }
    return palette;
}

SkinningJob make_skinning(Skinning method, const RandomMesh& mesh,
                          const std::vector<glm::mat4>& palette, const std::vector<DqsJoint>& dq,
                          std::vector<float>* out_p, std::vector<float>* out_n) {
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
    EXPECT_TRUE(job.validate());  // positions only
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
        ASSERT_TRUE(
            dqs_joints({palette.data(), palette.size()}, {dq.data(), dq.size()}, &stretched));
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
                ASSERT_NEAR(vp[i], sp[i], 2e-5f)
                    << "position float " << i << " method " << int(method);
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

}  // namespace
