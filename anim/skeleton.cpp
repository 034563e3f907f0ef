// Local-to-model transforms and skinning matrices: glTF 2.0 §3.5.3 "Transformations"
// (local matrix = T * R * S) and §3.7.3 "Skins" (joint matrix = global transform of the joint
// node * inverse bind matrix); and the joint decomposition for dual-quaternion skinning.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "anim/anim.h"
#include "anim/finite.h"
#include "anim/simd.h"

namespace stipple::anim {
namespace {

using simd::f4;

// parent (4 columns) * local, where local = T * R * S from a Trs: the rotation matrix's
// columns scaled by S, then T as column 3 (bottom row 0 0 0 1). parent == nullptr: identity.
void compose(const float* parent, const Trs& local, float* out) {
    const float x = local.rotation[0];
    const float y = local.rotation[1];
    const float z = local.rotation[2];
    const float w = local.rotation[3];
    const float sx = local.scale[0];
    const float sy = local.scale[1];
    const float sz = local.scale[2];
    // Columns of R * S (the unit-quaternion rotation matrix).
    const float r[3][3] = {
        {(1.0f - 2.0f * (y * y + z * z)) * sx, 2.0f * (x * y + w * z) * sx,
         2.0f * (x * z - w * y) * sx},
        {2.0f * (x * y - w * z) * sy, (1.0f - 2.0f * (x * x + z * z)) * sy,
         2.0f * (y * z + w * x) * sy},
        {2.0f * (x * z + w * y) * sz, 2.0f * (y * z - w * x) * sz,
         (1.0f - 2.0f * (x * x + y * y)) * sz},
    };
    const float* t = local.translation;
    if (parent == nullptr) {
        for (int c = 0; c < 3; ++c) {
            simd::store(out + 4 * c, simd::set(r[c][0], r[c][1], r[c][2], 0.0f));
        }
        simd::store(out + 12, simd::set(t[0], t[1], t[2], 1.0f));
        return;
    }
    const f4 p0 = simd::load(parent);
    const f4 p1 = simd::load(parent + 4);
    const f4 p2 = simd::load(parent + 8);
    const f4 p3 = simd::load(parent + 12);
    for (int c = 0; c < 3; ++c) {
        const f4 col =
            simd::madd(p0, simd::splat(r[c][0]),
                       simd::madd(p1, simd::splat(r[c][1]), simd::mul(p2, simd::splat(r[c][2]))));
        simd::store(out + 4 * c, col);
    }
    const f4 col3 =
        simd::madd(p0, simd::splat(t[0]),
                   simd::madd(p1, simd::splat(t[1]), simd::madd(p2, simd::splat(t[2]), p3)));
    simd::store(out + 12, col3);
}

// out = a * b, 4x4 column-major (out may not alias a or b).
void mul4(const float* a, const float* b, float* out) {
    const f4 a0 = simd::load(a);
    const f4 a1 = simd::load(a + 4);
    const f4 a2 = simd::load(a + 8);
    const f4 a3 = simd::load(a + 12);
    for (int c = 0; c < 4; ++c) {
        const float* bc = b + 4 * c;
        const f4 col = simd::madd(
            a0, simd::splat(bc[0]),
            simd::madd(a1, simd::splat(bc[1]),
                       simd::madd(a2, simd::splat(bc[2]), simd::mul(a3, simd::splat(bc[3])))));
        simd::store(out + 4 * c, col);
    }
}

}  // namespace

bool LocalToModelJob::validate() const {
    if (skeleton == nullptr) return false;
    const uint32_t n = skeleton->node_count;
    if (n > 0 && (skeleton->parents == nullptr || locals.data == nullptr || models.data == nullptr))
        return false;
    return locals.size >= n && models.size >= n;
}

bool LocalToModelJob::run() const {
    if (!validate()) return false;
    for (uint32_t i = 0; i < skeleton->node_count; ++i) {
        const int32_t parent = skeleton->parents[i];
        // parents[i] < i, so the parent's model matrix is already written. Anything else
        // (-1, or a malformed forward reference) makes the node a root.
        const float* p =
            parent >= 0 && static_cast<uint32_t>(parent) < i ? &models.data[parent][0][0] : nullptr;
        compose(p, locals.data[i], &models.data[i][0][0]);
    }
    return true;
}

bool JointMatrixJob::validate() const {
    if (skeleton == nullptr) return false;
    const uint32_t j = skeleton->joint_count;
    if (j > 0 && (skeleton->joint_nodes == nullptr || skeleton->inverse_bind == nullptr ||
                  joint_matrices.data == nullptr))
        return false;
    if (skeleton->node_count > 0 && models.data == nullptr) return false;
    return models.size >= skeleton->node_count && joint_matrices.size >= j;
}

bool JointMatrixJob::run() const {
    if (!validate()) return false;
    for (uint32_t j = 0; j < skeleton->joint_count; ++j) {
        const uint32_t node = skeleton->joint_nodes[j];
        float* out = &joint_matrices.data[j][0][0];
        if (node < skeleton->node_count) {
            // Column-major, as glTF stores it.
            mul4(&models.data[node][0][0], skeleton->inverse_bind + 16 * static_cast<size_t>(j),
                 out);
        } else {
            // A joint naming a node outside the skeleton (malformed asset) keeps its bind pose.
            joint_matrices.data[j] = glm::mat4(1.0f);
        }
    }
    return true;
}

// Kavan et al. 2007 §4 / 2008 §3.3 ("non-rigid joint transformations"): the joint matrix's
// 3x3 part A is split A = R * S with R a rotation (Gram-Schmidt on A's columns: exact for
// any A, and S = R^T A is the identity exactly when A is a rotation, diagonal when A is a
// rotation times an axis scale). The rigid part [R | t] becomes the unit dual quaternion
// real + eps * dual with dual = 0.5 * (t, 0) * real.
bool dqs_joints(Span<const glm::mat4> joint_matrices, Span<DqsJoint> out, uint32_t* stretched) {
    if (out.size < joint_matrices.size) return false;
    if (joint_matrices.size > 0 && (joint_matrices.data == nullptr || out.data == nullptr))
        return false;
    uint32_t non_rigid = 0;
    for (size_t j = 0; j < joint_matrices.size; ++j) {
        const glm::mat4& m = joint_matrices[j];
        const glm::vec3 a0(m[0]), a1(m[1]), a2(m[2]);
        const glm::vec3 t(m[3]);
        glm::mat3 r(1.0f);
        const float l0 = glm::length(a0);
        if (l0 > 1e-12f && std::isfinite(l0)) {
            const glm::vec3 c0 = a0 / l0;
            const glm::vec3 b1 = a1 - glm::dot(c0, a1) * c0;
            const float l1 = glm::length(b1);
            if (l1 > 1e-12f * std::max(1.0f, glm::length(a1))) {
                const glm::vec3 c1 = b1 / l1;
                r = glm::mat3(c0, c1, glm::cross(c0, c1));
            }
        }
        // S = R^T A, column by column.
        const glm::mat3 s = glm::transpose(r) * glm::mat3(a0, a1, a2);
        glm::quat q = glm::quat_cast(r);
        q = glm::normalize(q);
        if (q.w < 0.0f) q = -q;  // canonical hemisphere; DQS re-aligns per vertex anyway
        // dual = 0.5 * (t, 0) * q: vector part q.w t + t x q.xyz, scalar part -t . q.xyz.
        const glm::vec3 qv(q.x, q.y, q.z);
        const glm::vec3 dv = 0.5f * (q.w * t + glm::cross(t, qv));
        const float dw = -0.5f * glm::dot(t, qv);
        DqsJoint& o = out[j];
        o.real[0] = q.x;
        o.real[1] = q.y;
        o.real[2] = q.z;
        o.real[3] = q.w;
        o.dual[0] = dv.x;
        o.dual[1] = dv.y;
        o.dual[2] = dv.z;
        o.dual[3] = dw;
        bool identity = true;
        for (int c = 0; c < 3; ++c) {
            for (int row = 0; row < 3; ++row) {
                o.stretch[4 * c + row] = s[c][row];
                const float expect = c == row ? 1.0f : 0.0f;
                if (!(std::fabs(s[c][row] - expect) <= 1e-5f)) identity = false;
            }
            o.stretch[4 * c + 3] = 0.0f;
        }
        if (!identity) ++non_rigid;
    }
    if (stretched != nullptr) *stretched = non_rigid;
    return true;
}

DataError check_skeleton(const Skeleton& skeleton) {
    for (uint32_t i = 0; i < skeleton.node_count; ++i) {
        if (skeleton.parents[i] < -1 || skeleton.parents[i] >= static_cast<int32_t>(i))
            return DataError::parent_out_of_range;
    }
    for (uint32_t j = 0; j < skeleton.joint_count; ++j) {
        if (skeleton.joint_nodes[j] >= skeleton.node_count) return DataError::joint_out_of_range;
    }
    if (skeleton.node_count > 0 &&
        !all_finite(&skeleton.rest[0].translation[0], size_t{skeleton.node_count} * 10))
        return DataError::non_finite_value;
    if (skeleton.joint_count > 0 &&
        !all_finite(skeleton.inverse_bind, size_t{skeleton.joint_count} * 16))
        return DataError::non_finite_value;
    return DataError::ok;
}

const char* simd_path() {
    return simd::kPath;
}

}  // namespace stipple::anim
