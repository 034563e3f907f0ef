// glTF 2.0 meshes, §3.7: morph weight slots of the nodes that draw meshes, and every
// primitive of every mesh node merged into one RawScene mesh. A static scene is baked into
// world space (default morph weights applied); an animated one keeps skinned primitives in
// bind space and attaches the others rigidly to their node.
#include <algorithm>
#include <cmath>
#include <limits>

#include "anim/finite.h"
#include "bake/gltf_parts.h"

namespace stipple::bake::gltf {

namespace {

// Node `oi`'s morph slots: one per target of its mesh, with default weights from the node,
// else the mesh, else 0.
void add_node_slots(const tinygltf::Node& node, const tinygltf::Mesh& mesh, size_t oi,
                    const std::string& label, size_t count, MorphWeightTable* table,
                    std::vector<std::string>* warnings) {
    for (const tinygltf::Primitive& prim : mesh.primitives) {
        if (prim.targets.size() != count) {
            // §3.7.2.2: all primitives MUST have the same number of targets.
            warnings->push_back(label +
                                ": primitives have different morph target counts; "
                                "target i of every primitive uses weight i");
            break;
        }
    }
    const std::vector<double>* defaults = nullptr;
    if (node.weights.size() == count) {
        defaults = &node.weights;
    } else if (mesh.weights.size() == count) {
        defaults = &mesh.weights;
    }
    if ((!node.weights.empty() && node.weights.size() != count) ||
        (!mesh.weights.empty() && mesh.weights.size() != count && defaults == nullptr)) {
        warnings->push_back(label + ": default morph weights do not match its " + str(count) +
                            " targets; ignored");
    }
    table->slots[oi] = {uint32_t(table->weights.size()), uint32_t(count)};
    for (size_t i = 0; i < count; ++i) {
        double w = defaults != nullptr ? (*defaults)[i] : 0.0;
        if (!std::isfinite(w) || std::abs(w) > 1e30) {
            warnings->push_back(label + ": default morph weight " + str(i) +
                                " is not finite; 0 used");
            w = 0.0;
        }
        table->weights.push_back(float(w));
        table->slot_nodes.push_back(uint32_t(oi));
    }
}

// Static: bake the default morph weights (§3.7.2.2) into the primitive.
void apply_default_weights(const MorphSlots& slots, const std::vector<float>& weights,
                           Primitive* prim) {
    const size_t floats = prim->positions.size();
    for (size_t t = 0; t < prim->target_positions.size() && t < slots.count; ++t) {
        const float w = weights[slots.begin + t];
        if (w == 0.0f) continue;
        for (size_t i = 0; i < floats; ++i) prim->positions[i] += w * prim->target_positions[t][i];
        if (!prim->target_normals[t].empty()) {
            for (size_t i = 0; i < floats; ++i) prim->normals[i] += w * prim->target_normals[t][i];
        }
    }
}

// Static: bake the world transform. Normals use the cofactor matrix (det * inverse
// transpose, valid even for singular matrices), sign-fixed; a mirroring transform flips the
// winding to keep triangles front-facing.
BakeError append_world_baked(const Primitive& prim, const glm::dmat4& m, size_t gi,
                             RawScene* scene) {
    const size_t base = scene->vertex_count();
    const size_t count = prim.positions.size() / 3;
    const glm::dmat3 linear(m);
    const double det = glm::determinant(linear);
    const glm::dmat3 cofactor =
        glm::dmat3(glm::cross(linear[1], linear[2]), glm::cross(linear[2], linear[0]),
                   glm::cross(linear[0], linear[1]));
    for (size_t v = 0; v < count; ++v) {
        const glm::dvec4 pw = m * glm::dvec4(prim.positions[v * 3], prim.positions[v * 3 + 1],
                                             prim.positions[v * 3 + 2], 1.0);
        glm::dvec3 nw = cofactor * glm::dvec3(prim.normals[v * 3], prim.normals[v * 3 + 1],
                                              prim.normals[v * 3 + 2]);
        if (det < 0.0) nw = -nw;
        const double len = glm::length(nw);
        nw = len > 1e-300 ? nw / len : glm::dvec3(0.0, 0.0, 1.0);
        for (int c = 0; c < 3; ++c) {
            scene->positions.push_back(float(pw[c]));
            scene->normals.push_back(float(nw[c]));
        }
    }
    if (!all_finite(scene->positions.data() + base * 3, count * 3)) {
        return malformed_input("node " + str(gi) + ": transformed positions are not finite");
    }
    for (size_t t = 0; t < prim.indices.size(); t += 3) {
        const uint32_t b = uint32_t(base);
        scene->indices.push_back(b + prim.indices[t]);
        scene->indices.push_back(b + prim.indices[det < 0.0 ? t + 2 : t + 1]);
        scene->indices.push_back(b + prim.indices[det < 0.0 ? t + 1 : t + 2]);
    }
    return BakeError();
}

// Animated: the primitive's morph targets over its vertex range [base, base + count);
// all-zero targets are dropped.
void append_morph_targets(const MorphSlots& slots, size_t base, Primitive* prim, RawScene* scene) {
    const size_t count = prim->positions.size() / 3;
    auto nonzero = [](const std::vector<float>& v) {
        return std::any_of(v.begin(), v.end(), [](float x) { return x != 0.0f; });
    };
    for (size_t t = 0; t < prim->target_positions.size() && t < slots.count; ++t) {
        const bool has_p = nonzero(prim->target_positions[t]);
        const bool has_n = nonzero(prim->target_normals[t]);
        if (!has_p && !has_n) continue;
        RawMorphTarget target;
        target.weight = uint32_t(slots.begin + t);
        target.vertex_begin = uint32_t(base);
        target.vertex_count = uint32_t(count);
        target.position_deltas = std::move(prim->target_positions[t]);
        if (has_n) target.normal_deltas = std::move(prim->target_normals[t]);
        scene->morph_targets.push_back(std::move(target));
    }
}

// Animated: bind-space (skinned) or node-space (rigid) vertices. A rigid primitive gets one
// joint per node, with an identity inverse bind matrix.
BakeError append_animated(Primitive* prim, const MorphSlots& slots, size_t oi,
                          std::vector<int64_t>* rigid_joint, SkinTable* skin, RawScene* scene) {
    const size_t base = scene->vertex_count();
    const size_t count = prim->positions.size() / 3;
    append_morph_targets(slots, base, prim, scene);
    scene->positions.insert(scene->positions.end(), prim->positions.begin(), prim->positions.end());
    scene->normals.insert(scene->normals.end(), prim->normals.begin(), prim->normals.end());
    for (uint32_t index : prim->indices) scene->indices.push_back(uint32_t(base) + index);
    if (prim->skinned) {
        scene->joints.insert(scene->joints.end(), prim->joints.begin(), prim->joints.end());
        scene->weights.insert(scene->weights.end(), prim->weights.begin(), prim->weights.end());
        return BakeError();
    }
    int64_t& joint = (*rigid_joint)[oi];
    if (joint < 0) {
        if (skin->joint_nodes.size() >= kMaxJoints) {
            return bake_error(BakeErrorCode::unsupported,
                              "more than " + str(kMaxJoints) + " joints");
        }
        joint = int64_t(skin->joint_nodes.size());
        skin->joint_nodes.push_back(uint32_t(oi));
        for (int k = 0; k < 16; ++k) skin->inverse_bind.push_back(k % 5 == 0 ? 1.0f : 0.0f);
    }
    for (size_t v = 0; v < count; ++v) {
        scene->joints.insert(scene->joints.end(), {uint16_t(joint), 0, 0, 0});
        scene->weights.insert(scene->weights.end(), {1.0f, 0.0f, 0.0f, 0.0f});
    }
    return BakeError();
}

// §3.9.5 (material.doubleSided): back faces are lit and drawn too. The default material
// (no material index) is single-sided.
bool double_sided(const Model& model, const tinygltf::Primitive& prim) {
    return prim.material >= 0 && size_t(prim.material) < model.materials.size() &&
           model.materials[size_t(prim.material)].doubleSided;
}

// The mesh and skin a node refers to must exist.
BakeError check_mesh_node(const Model& model, const tinygltf::Node& node, size_t gi) {
    if (size_t(node.mesh) >= model.meshes.size()) {
        return malformed_input("node " + str(gi) + ": mesh " + str(node.mesh) +
                               " out of range (mesh count " + str(model.meshes.size()) + ")");
    }
    if (node.skin >= 0 && size_t(node.skin) >= model.skins.size()) {
        return malformed_input("node " + str(gi) + ": skin " + str(node.skin) +
                               " out of range (skin count " + str(model.skins.size()) + ")");
    }
    return BakeError();
}

// What merging needs besides the scene: the tables and the rigid joints made so far.
struct MergeState {
    const Model& model;
    const NodeTable& nodes;
    const MorphWeightTable& morph;
    bool animated;
    SkinTable* skin;
    MeshContext ctx;
    std::vector<int64_t> rigid_joint;  // joint of a rigidly attached output node, or -1
    const ImportOptions& options;
    PartTable parts;
};

// The primitive's part per triangle and, with looks, its texture coordinates and colours per
// vertex ((0, 0) where it samples no texture, white where it has no COLOR_0).
BakeError append_looks(MergeState& st, size_t mesh_index, size_t p, const Primitive& prim,
                       RawScene* scene) {
    uint16_t part = 0;
    const BakeError error =
        primitive_part(st.model, mesh_index, p, st.options, &st.parts, scene, &part);
    if (!error.ok()) return error;
    scene->triangle_part.insert(scene->triangle_part.end(), prim.indices.size() / 3, part);
    if (!st.options.looks) return BakeError();
    if (prim.uvs.empty())
        scene->uvs.insert(scene->uvs.end(), prim.positions.size() / 3 * 2, 0.0f);
    else
        scene->uvs.insert(scene->uvs.end(), prim.uvs.begin(), prim.uvs.end());
    if (prim.colours.empty())
        scene->colours.insert(scene->colours.end(), prim.positions.size() / 3 * 4, 1.0f);
    else
        scene->colours.insert(scene->colours.end(), prim.colours.begin(), prim.colours.end());
    return BakeError();
}

// Reads and appends the primitives of output node `oi`'s mesh.
BakeError merge_node_mesh(MergeState& st, size_t oi, RawScene* scene) {
    const size_t gi = st.nodes.order[oi];
    const tinygltf::Node& node = st.model.nodes[gi];
    const BakeError checked = check_mesh_node(st.model, node, gi);
    if (!checked.ok()) return checked;
    const bool skinned_node = st.skin->present && node.skin == 0;
    if (node.skin > 0) {
        scene->warnings.push_back("node " + str(gi) + " uses skin " + str(node.skin) +
                                  "; only the first skin is supported, so its mesh is attached "
                                  "rigidly to the node");
    }
    const size_t mesh_index = size_t(node.mesh);
    const std::vector<tinygltf::Primitive>& primitives = st.model.meshes[mesh_index].primitives;
    for (size_t p = 0; p < primitives.size(); ++p) {
        Primitive prim;
        bool skipped = false;
        BakeError error = read_primitive(st.ctx, mesh_index, p, skinned_node, &prim, &skipped);
        if (!error.ok()) return error;
        if (skipped) continue;
        if (skinned_node && !prim.skinned) {
            scene->warnings.push_back("mesh " + str(mesh_index) + " primitive " + str(p) +
                                      " on skinned node " + str(gi) +
                                      " has no JOINTS_0/WEIGHTS_0; attached rigidly to the node");
        }
        scene->double_sided.insert(scene->double_sided.end(), prim.indices.size() / 3,
                                   uint8_t(double_sided(st.model, primitives[p])));
        if (prim.positions.size() / 3 >
            std::numeric_limits<uint32_t>::max() - scene->vertex_count()) {
            return bake_error(BakeErrorCode::unsupported, "more than 2^32 vertices");
        }
        error = append_looks(st, mesh_index, p, prim, scene);
        if (!error.ok()) return error;
        const MorphSlots& slots = st.morph.slots[oi];
        if (!st.animated) {
            apply_default_weights(slots, st.morph.weights, &prim);
            error = append_world_baked(prim, st.nodes.world[oi], gi, scene);
        } else {
            error = append_animated(&prim, slots, oi, &st.rigid_joint, st.skin, scene);
        }
        if (!error.ok()) return error;
    }
    return BakeError();
}

}  // namespace

MorphWeightTable assign_morph_slots(const Model& model, const NodeTable& nodes,
                                    std::vector<std::string>* warnings) {
    MorphWeightTable table;
    table.slots.resize(nodes.order.size());
    for (size_t oi = 0; oi < nodes.order.size(); ++oi) {
        const tinygltf::Node& node = model.nodes[nodes.order[oi]];
        if (node.mesh < 0 || size_t(node.mesh) >= model.meshes.size()) continue;
        const tinygltf::Mesh& mesh = model.meshes[size_t(node.mesh)];
        size_t count = 0;
        for (const tinygltf::Primitive& prim : mesh.primitives) {
            count = std::max(count, prim.targets.size());
        }
        if (count == 0) continue;
        const std::string label = "node " + str(nodes.order[oi]) + " (mesh " + str(node.mesh) + ")";
        add_node_slots(node, mesh, oi, label, count, &table, warnings);
    }
    return table;
}

BakeError merge_meshes(const Model& model, const NodeTable& nodes, const MorphWeightTable& morph,
                       bool animated, const ImportOptions& options, SkinTable* skin,
                       RawScene* scene) {
    const bool quantized = std::find(model.extensionsUsed.begin(), model.extensionsUsed.end(),
                                     "KHR_mesh_quantization") != model.extensionsUsed.end();
    MergeState st{
        model,
        nodes,
        morph,
        animated,
        skin,
        MeshContext{model, quantized, skin->joint_nodes.size(), &scene->warnings, &options},
        std::vector<int64_t>(nodes.order.size(), -1),
        options,
        PartTable()};
    for (size_t oi = 0; oi < nodes.order.size(); ++oi) {
        if (model.nodes[nodes.order[oi]].mesh < 0) continue;
        const BakeError error = merge_node_mesh(st, oi, scene);
        if (!error.ok()) return error;
    }
    return BakeError();
}

}  // namespace stipple::bake::gltf
