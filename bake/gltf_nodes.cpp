// glTF 2.0 nodes, §3.5: the scene's roots, the hierarchy flattened parents-first, and every
// node's local transform (as TRS for the runtime, as an exact matrix for static baking).
#include <algorithm>
#include <cmath>
#include <glm/gtc/quaternion.hpp>

#include "anim/finite.h"
#include "bake/gltf_parts.h"

namespace stipple::bake::gltf {

namespace {

// Roots: the default scene, else scene 0, else every node that is nobody's child.
BakeError select_roots(const Model& model, std::vector<int>* roots) {
    const size_t node_count = model.nodes.size();
    if (!model.scenes.empty()) {
        if (model.defaultScene >= 0 && size_t(model.defaultScene) >= model.scenes.size()) {
            return malformed_input("default scene " + str(model.defaultScene) +
                                   " out of range (scene count " + str(model.scenes.size()) + ")");
        }
        *roots = model.scenes[size_t(std::max(model.defaultScene, 0))].nodes;
        return BakeError();
    }
    std::vector<bool> is_child(node_count, false);
    for (const tinygltf::Node& node : model.nodes) {
        for (int child : node.children) {
            if (child >= 0 && size_t(child) < node_count) is_child[size_t(child)] = true;
        }
    }
    for (size_t i = 0; i < node_count; ++i) {
        if (!is_child[i]) roots->push_back(int(i));
    }
    return BakeError();
}

// Depth-first preorder with an explicit stack (no recursion on deep chains): parents are
// emitted before children. §3.5.2: the hierarchy is a set of disjoint strict trees, so a
// node reached twice means a cycle or a shared child.
BakeError flatten_hierarchy(const Model& model, const std::vector<int>& roots, RawScene* scene,
                            NodeTable* nodes) {
    const size_t node_count = model.nodes.size();
    nodes->out_index.assign(node_count, -1);
    struct Pending {
        int node;
        int32_t parent;
    };
    std::vector<Pending> stack;
    for (auto it = roots.rbegin(); it != roots.rend(); ++it) {
        if (*it < 0 || size_t(*it) >= node_count) {
            return malformed_input("scene node " + str(*it) + " out of range (node count " +
                                   str(node_count) + ")");
        }
        stack.push_back({*it, -1});
    }
    while (!stack.empty()) {
        const Pending item = stack.back();
        stack.pop_back();
        const size_t gi = size_t(item.node);
        if (nodes->out_index[gi] >= 0) {
            return malformed_input(
                "node " + str(gi) +
                " is reached twice (the node hierarchy must be a set of disjoint trees)");
        }
        nodes->out_index[gi] = int32_t(nodes->order.size());
        nodes->order.push_back(gi);
        RawNode raw;
        raw.parent = item.parent;
        raw.name = model.nodes[gi].name;
        scene->nodes.push_back(std::move(raw));
        const std::vector<int>& children = model.nodes[gi].children;
        for (auto it = children.rbegin(); it != children.rend(); ++it) {
            if (*it < 0 || size_t(*it) >= node_count) {
                return malformed_input("node " + str(gi) + ": child " + str(*it) +
                                       " out of range (node count " + str(node_count) + ")");
            }
            stack.push_back({*it, nodes->out_index[gi]});
        }
    }
    return BakeError();
}

// Splits a node matrix into T * R * S (§3.5.3 "Transformations": a matrix MUST be
// decomposable to TRS). A negative determinant becomes a negative x scale. Returns false
// with a warning text when the matrix is not exactly a TRS (shear, projection, zero scale).
bool decompose_trs(const glm::dmat4& m, RawNode* node, std::string* problem) {
    const glm::dvec3 c0(m[0]), c1(m[1]), c2(m[2]);
    glm::dvec3 s(glm::length(c0), glm::length(c1), glm::length(c2));
    if (glm::dot(c0, glm::cross(c1, c2)) < 0.0) s.x = -s.x;
    glm::dquat q(1.0, 0.0, 0.0, 0.0);
    const double tiny = 1e-12;
    const bool degenerate = std::abs(s.x) < tiny || std::abs(s.y) < tiny || std::abs(s.z) < tiny;
    if (!degenerate) {
        q = glm::normalize(glm::quat_cast(glm::dmat3(c0 / s.x, c1 / s.y, c2 / s.z)));
    }
    for (int i = 0; i < 3; ++i) {
        node->translation[i] = float(m[3][i]);
        node->scale[i] = float(s[i]);
    }
    node->rotation[0] = float(q.x);
    node->rotation[1] = float(q.y);
    node->rotation[2] = float(q.z);
    node->rotation[3] = float(q.w);
    if (degenerate) {
        *problem = "matrix has a zero scale; its rotation is dropped";
        return false;
    }
    // Rebuild and compare: any difference is shear or a projective bottom row.
    glm::dmat4 rebuilt = glm::mat4_cast(q);
    for (int c = 0; c < 3; ++c) rebuilt[c] *= s[c];
    rebuilt[3] = glm::dvec4(m[3][0], m[3][1], m[3][2], 1.0);
    double scale = 1.0;
    double diff = 0.0;
    for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) {
            scale = std::max(scale, std::abs(m[c][r]));
            diff = std::max(diff, std::abs(m[c][r] - rebuilt[c][r]));
        }
    }
    if (diff > 1e-4 * scale) {
        *problem = "matrix is not a pure TRS (shear or projection); approximated";
        return false;
    }
    return true;
}

// A node given by translation/rotation/scale (each optional): the TRS as written (rotation
// normalised) and its matrix T * R * S.
BakeError read_trs(const tinygltf::Node& node, const std::string& label, RawNode* raw,
                   glm::dmat4* local) {
    for (size_t i = 0; i < node.translation.size(); ++i) {
        raw->translation[i] = float(node.translation[i]);
    }
    for (size_t i = 0; i < node.scale.size(); ++i) raw->scale[i] = float(node.scale[i]);
    if (!node.rotation.empty()) {
        const glm::dvec4 r(node.rotation[0], node.rotation[1], node.rotation[2], node.rotation[3]);
        const double len = glm::length(r);
        if (!(len > 1e-6)) return malformed_input(label + ": rotation is not a unit quaternion");
        for (int i = 0; i < 4; ++i) raw->rotation[i] = float(r[i] / len);
    }
    const glm::dquat q(raw->rotation[3], raw->rotation[0], raw->rotation[1], raw->rotation[2]);
    *local = glm::mat4_cast(q);
    for (int c = 0; c < 3; ++c) (*local)[c] *= double(raw->scale[c]);
    (*local)[3] = glm::dvec4(raw->translation[0], raw->translation[1], raw->translation[2], 1.0);
    return BakeError();
}

// Reads a node's local transform into `raw` (TRS) and `local` (the exact matrix, used to
// bake static scenes).
BakeError read_node_transform(const tinygltf::Node& node, size_t index, RawNode* raw,
                              glm::dmat4* local, std::vector<std::string>* warnings) {
    const std::string label = "node " + str(index);
    if (!node.matrix.empty()) {
        if (node.matrix.size() != 16 || !all_finite(node.matrix)) {
            return malformed_input(label + ": matrix must be 16 finite numbers");
        }
        for (int c = 0; c < 4; ++c) {
            for (int r = 0; r < 4; ++r) (*local)[c][r] = node.matrix[size_t(c * 4 + r)];
        }
        std::string problem;
        if (!decompose_trs(*local, raw, &problem)) warnings->push_back(label + ": " + problem);
    } else if ((!node.translation.empty() && node.translation.size() != 3) ||
               (!node.rotation.empty() && node.rotation.size() != 4) ||
               (!node.scale.empty() && node.scale.size() != 3) || !all_finite(node.translation) ||
               !all_finite(node.rotation) || !all_finite(node.scale)) {
        return malformed_input(label + ": translation/rotation/scale must be 3/4/3 finite numbers");
    } else {
        const BakeError trs = read_trs(node, label, raw, local);
        if (!trs.ok()) return trs;
    }
    // Finite doubles can still overflow the floats the runtime uses.
    if (!all_finite(raw->translation, 3) || !all_finite(raw->rotation, 4) ||
        !all_finite(raw->scale, 3)) {
        return malformed_input(label + ": transform exceeds the float range");
    }
    return BakeError();
}

}  // namespace

BakeError read_nodes(const Model& model, RawScene* scene, NodeTable* nodes) {
    std::vector<int> roots;
    BakeError error = select_roots(model, &roots);
    if (error.ok()) error = flatten_hierarchy(model, roots, scene, nodes);
    if (!error.ok()) return error;
    // Local transforms and world matrices (parents first, so one forward pass).
    const std::vector<size_t>& order = nodes->order;
    nodes->world.resize(order.size());
    for (size_t i = 0; i < order.size(); ++i) {
        glm::dmat4 local(1.0);
        error = read_node_transform(model.nodes[order[i]], order[i], &scene->nodes[i], &local,
                                    &scene->warnings);
        if (!error.ok()) return error;
        const int32_t parent = scene->nodes[i].parent;
        nodes->world[i] = parent < 0 ? local : nodes->world[size_t(parent)] * local;
    }
    return BakeError();
}

}  // namespace stipple::bake::gltf
