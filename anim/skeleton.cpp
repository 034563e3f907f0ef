// Local-to-model transforms and skinning matrices: glTF 2.0 §3.5.3 "Transformations"
// (local matrix = T * R * S) and §3.7.3 "Skins" (joint matrix = global transform of the joint
// node * inverse bind matrix).
#include <cstring>

#include "anim/anim.h"

namespace stipple::anim {
namespace {

// T * R * S from a Trs: the rotation matrix's columns scaled by S, then T as column 3.
glm::mat4 trs_matrix(const Trs& local) {
    const float x = local.rotation[0];
    const float y = local.rotation[1];
    const float z = local.rotation[2];
    const float w = local.rotation[3];
    const float sx = local.scale[0];
    const float sy = local.scale[1];
    const float sz = local.scale[2];
    glm::mat4 m;
    m[0] = glm::vec4((1.0f - 2.0f * (y * y + z * z)) * sx, 2.0f * (x * y + w * z) * sx,
                     2.0f * (x * z - w * y) * sx, 0.0f);
    m[1] = glm::vec4(2.0f * (x * y - w * z) * sy, (1.0f - 2.0f * (x * x + z * z)) * sy,
                     2.0f * (y * z + w * x) * sy, 0.0f);
    m[2] = glm::vec4(2.0f * (x * z + w * y) * sz, 2.0f * (y * z - w * x) * sz,
                     (1.0f - 2.0f * (x * x + y * y)) * sz, 0.0f);
    m[3] = glm::vec4(local.translation[0], local.translation[1], local.translation[2], 1.0f);
    return m;
}

}  // namespace

void local_to_model(const Skeleton& skeleton, const Trs* locals, glm::mat4* model) {
    for (uint32_t i = 0; i < skeleton.node_count; ++i) {
        const glm::mat4 local = trs_matrix(locals[i]);
        const int32_t parent = skeleton.parents[i];
        // parents[i] < i, so the parent's model matrix is already written. Anything else
        // (-1, or a malformed forward reference) makes the node a root.
        if (parent >= 0 && static_cast<uint32_t>(parent) < i) {
            model[i] = model[parent] * local;
        } else {
            model[i] = local;
        }
    }
}

void joint_matrices(const Skeleton& skeleton, const glm::mat4* model, glm::mat4* skin) {
    for (uint32_t j = 0; j < skeleton.joint_count; ++j) {
        glm::mat4 inverse_bind;
        std::memcpy(&inverse_bind[0][0], skeleton.inverse_bind + 16 * static_cast<size_t>(j),
                    sizeof(inverse_bind));  // column-major, as glTF stores it
        const uint32_t node = skeleton.joint_nodes[j];
        // A joint naming a node outside the skeleton (malformed asset) keeps its bind pose.
        skin[j] = node < skeleton.node_count ? model[node] * inverse_bind : glm::mat4(1.0f);
    }
}

}  // namespace stipple::anim
