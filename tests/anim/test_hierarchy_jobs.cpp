// LocalToModelJob and JointMatrixJob (anim/anim.h): model matrices (glTF 2.0 §3.5.3) and
// joint matrices (§3.7.3) against hand-computed values, and their span checks.
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

TEST(AnimSkeleton, LocalToModelTwoNodeChain) {
    // Node 0 (root): T = (1, 2, 3), R = 90° about Z, S = 2.
    // Node 1 (child): T = (1, 0, 0), R = 90° about X, S = (1, 2, 3).
    const std::vector<int32_t> parents = {-1, 0};
    const std::vector<Trs> rest = {Trs{{1, 2, 3}, {0, 0, kHalfSqrt2, kHalfSqrt2}, {2, 2, 2}},
                                   Trs{{1, 0, 0}, {kHalfSqrt2, 0, 0, kHalfSqrt2}, {1, 2, 3}}};
    const Skeleton skeleton = make_skeleton(parents, rest);
    glm::mat4 model[2];
    model_matrices(skeleton, rest.data(), model);

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
    model_matrices(skeleton, rest.data(), model);
    skin_matrices(skeleton, model, skin);
    expect_mat4(skin[0], glm::mat4(1.0f));
    expect_mat4(skin[1], glm::mat4(1.0f));  // bad node: stays in bind pose

    // Move node 0 up by 1: the skin matrix is T(0, 1, 0).
    rest[0].translation[1] = 6;
    model_matrices(skeleton, rest.data(), model);
    skin_matrices(skeleton, model, skin);
    expect_mat4(skin[0], glm::translate(glm::mat4(1.0f), glm::vec3(0, 1, 0)));
}

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
