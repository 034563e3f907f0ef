// Hand-built anim/ inputs for the anim tests (part of the shared fixtures in tests/common/):
// skeletons, channels and clips from vectors, the jobs run with the settings the tests use,
// and expectations on vectors and matrices.
#pragma once
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <vector>

#include "anim/anim.h"

namespace stipple::test {

constexpr float kEps = 1e-6f;
inline const float kHalfSqrt2 = std::sqrt(0.5f);  // cos 45° = sin 45°

inline anim::Trs identity_trs() {
    return anim::Trs{{0, 0, 0}, {0, 0, 0, 1}, {1, 1, 1}};
}

// A skeleton of `rest.size()` nodes with the given parents and no joints.
inline anim::Skeleton make_skeleton(const std::vector<int32_t>& parents,
                                    const std::vector<anim::Trs>& rest) {
    anim::Skeleton s{};
    s.node_count = uint32_t(rest.size());
    s.parents = parents.data();
    s.rest = rest.data();
    return s;
}

inline anim::Channel channel(uint32_t node, anim::Path path, anim::Interp interp,
                             const std::vector<float>& times, const std::vector<float>& values,
                             uint32_t weight_begin = 0, uint32_t weight_count = 0) {
    return anim::Channel{node,         path,          interp,       uint32_t(times.size()),
                         times.data(), values.data(), weight_begin, weight_count};
}

inline anim::Clip make_clip(const std::vector<anim::Channel>& channels, float duration) {
    return anim::Clip{"test", duration, uint32_t(channels.size()), channels.data()};
}

inline bool same_trs(const anim::Trs& a, const anim::Trs& b) {
    return std::memcmp(&a, &b, sizeof(anim::Trs)) == 0;
}

// SamplingJob with clamp wrap and no context into locals[0, node_count); fails the test if
// the job does not run.
inline void sample_pose(const anim::Skeleton& skeleton, const anim::Clip& clip, float time,
                        anim::Trs* locals) {
    anim::SamplingJob job;
    job.skeleton = &skeleton;
    job.clip = &clip;
    job.time = time;
    job.locals = anim::Span<anim::Trs>(locals, skeleton.node_count);
    EXPECT_TRUE(job.run()) << "SamplingJob at t = " << time;
}

// LocalToModelJob over the whole skeleton.
inline void model_matrices(const anim::Skeleton& skeleton, const anim::Trs* locals,
                           glm::mat4* models) {
    anim::LocalToModelJob job;
    job.skeleton = &skeleton;
    job.locals = anim::Span<const anim::Trs>(locals, skeleton.node_count);
    job.models = anim::Span<glm::mat4>(models, skeleton.node_count);
    EXPECT_TRUE(job.run());
}

// JointMatrixJob over the whole skin.
inline void skin_matrices(const anim::Skeleton& skeleton, const glm::mat4* models,
                          glm::mat4* palette) {
    anim::JointMatrixJob job;
    job.skeleton = &skeleton;
    job.models = anim::Span<const glm::mat4>(models, skeleton.node_count);
    job.joint_matrices = anim::Span<glm::mat4>(palette, skeleton.joint_count);
    EXPECT_TRUE(job.run());
}

// An LBS SkinningJob of `vertex_count` vertices on a palette of `joint_count` matrices,
// every span exactly as large as it needs to be.
inline anim::SkinningJob lbs_job(uint32_t vertex_count, const glm::mat4* palette,
                                 uint32_t joint_count, const uint16_t* joints, const float* weights,
                                 const float* in_positions, const float* in_normals,
                                 float* out_positions, float* out_normals) {
    anim::SkinningJob job;
    job.method = anim::Skinning::lbs;
    job.vertex_count = vertex_count;
    job.joint_matrices = anim::Span<const glm::mat4>(palette, joint_count);
    job.joints = anim::Span<const uint16_t>(joints, size_t{vertex_count} * 4);
    job.weights = anim::Span<const float>(weights, size_t{vertex_count} * 4);
    job.in_positions = anim::Span<const float>(in_positions, size_t{vertex_count} * 3);
    job.in_normals = anim::Span<const float>(in_normals, size_t{vertex_count} * 3);
    job.out_positions = anim::Span<float>(out_positions, size_t{vertex_count} * 3);
    job.out_normals = anim::Span<float>(out_normals, size_t{vertex_count} * 3);
    return job;
}

// Rotates v by the unit quaternion q (x, y, z, w).
inline glm::vec3 rotate(const float* q, glm::vec3 v) {
    return glm::quat(q[3], q[0], q[1], q[2]) * v;
}

inline void expect_vec3(const float* got, float x, float y, float z, float eps = 1e-6f) {
    EXPECT_NEAR(got[0], x, eps);
    EXPECT_NEAR(got[1], y, eps);
    EXPECT_NEAR(got[2], z, eps);
}

inline void expect_mat4(const glm::mat4& got, const glm::mat4& want, float eps = 1e-5f) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            EXPECT_NEAR(got[c][r], want[c][r], eps) << "column " << c << " row " << r;
}

}  // namespace stipple::test
