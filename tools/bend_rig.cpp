#include "tools/bend_rig.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <vector>

#include "bake/raw_scene.h"
#include "bake/scene_import.h"
#include "bake/scene_orientation.h"
#include "tools/gltf_build.h"

namespace stipple::tools {

namespace {

constexpr float kPi = 3.14159265358979f;
using gltf_build::add_values;
using gltf_build::kArrayBuffer;
using gltf_build::kElementArrayBuffer;

// The chain: joint positions along the longest axis of the bounds, through their centre.
struct Chain {
    int axis = 0;                      // 0 x, 1 y, 2 z
    float lo = 0.0f, length = 0.0f;    // along the axis
    glm::vec3 centre{0.0f};            // of the bounds
    glm::vec3 sway{0.0f, 1.0f, 0.0f};  // up (Y), or Z for a chain that is itself vertical
    glm::vec3 bend{0.0f};              // perpendicular to the chain and to `sway`
    std::vector<glm::vec3> joints;     // bones
    int root = 0;                      // the middle joint; the chain hangs from it both ways
};

Chain make_chain(const std::vector<float>& positions, int bones) {
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (size_t i = 0; i + 2 < positions.size(); i += 3) {
        const glm::vec3 p(positions[i], positions[i + 1], positions[i + 2]);
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    Chain c;
    const glm::vec3 extent = hi - lo;
    c.axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    c.lo = lo[c.axis];
    c.length = extent[c.axis];
    c.centre = 0.5f * (lo + hi);
    glm::vec3 along(0.0f);
    along[c.axis] = 1.0f;
    if (c.axis == 1) c.sway = glm::vec3(0.0f, 0.0f, 1.0f);
    c.bend = glm::normalize(glm::cross(c.sway, along));
    for (int i = 0; i < bones; ++i) {
        glm::vec3 p = c.centre;
        p[c.axis] = c.lo + c.length * float(i) / float(bones - 1);
        c.joints.push_back(p);
    }
    c.root = (bones - 1) / 2;
    return c;
}

// Each vertex between its two neighbouring joints, weights linear in its position along the
// chain (4 joints, 4 weights per vertex as glTF's JOINTS_0 / WEIGHTS_0).
void chain_weights(const Chain& c, const std::vector<float>& positions,
                   std::vector<uint8_t>* joints, std::vector<float>* weights) {
    const int bones = int(c.joints.size());
    for (size_t i = 0; i + 2 < positions.size(); i += 3) {
        float s = c.length > 0.0f ? (positions[i + size_t(c.axis)] - c.lo) / c.length : 0.0f;
        s = std::clamp(s, 0.0f, 1.0f) * float(bones - 1);
        const int j = std::min(int(s), bones - 2);
        const float f = std::clamp(s - float(j), 0.0f, 1.0f);
        joints->insert(joints->end(), {uint8_t(j), uint8_t(j + 1), 0, 0});
        weights->insert(weights->end(), {1.0f - f, f, 0.0f, 0.0f});
    }
}

// The parent of joint i: joints hang from the root toward both ends.
int parent_of(const Chain& c, int i) {
    if (i == c.root) return -1;
    return i < c.root ? i + 1 : i - 1;
}

// Joint i's rotation at phase `t` in [0, 1): a wave running down the chain. The two halves
// turn in opposite senses (they point opposite ways), so the arch lifts both ends together.
glm::quat joint_rotation(const Chain& c, const BendRigOptions& o, int i, float t) {
    const int bones = int(c.joints.size());
    const float wave = 2.0f * kPi * t - kPi * float(i) / float(bones - 1);
    const float side = i < c.root ? -1.0f : 1.0f;
    const float bend = i == c.root ? 0.0f : side * glm::radians(o.bend_degrees) * std::sin(wave);
    const float sway = side * glm::radians(o.sway_degrees) * std::cos(wave);
    return glm::angleAxis(sway, c.sway) * glm::angleAxis(bend, c.bend);
}

tinygltf::Primitive add_primitive(tinygltf::Model* model, const bake::RawScene& scene,
                                  const Chain& chain) {
    std::vector<uint8_t> joints;
    std::vector<float> weights;
    chain_weights(chain, scene.positions, &joints, &weights);
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (size_t i = 0; i + 2 < scene.positions.size(); i += 3) {
        const glm::vec3 p = glm::make_vec3(scene.positions.data() + i);
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    const size_t n = scene.vertex_count();
    constexpr int kFloat = TINYGLTF_COMPONENT_TYPE_FLOAT;
    tinygltf::Primitive prim;
    prim.mode = TINYGLTF_MODE_TRIANGLES;
    prim.attributes["POSITION"] =
        add_values(model, scene.positions, kArrayBuffer, kFloat, TINYGLTF_TYPE_VEC3, n,
                   {lo.x, lo.y, lo.z}, {hi.x, hi.y, hi.z});
    if (scene.normals.size() == scene.positions.size())
        prim.attributes["NORMAL"] =
            add_values(model, scene.normals, kArrayBuffer, kFloat, TINYGLTF_TYPE_VEC3, n);
    prim.attributes["JOINTS_0"] = add_values(
        model, joints, kArrayBuffer, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_VEC4, n);
    prim.attributes["WEIGHTS_0"] =
        add_values(model, weights, kArrayBuffer, kFloat, TINYGLTF_TYPE_VEC4, n);
    prim.indices =
        add_values(model, scene.indices, kElementArrayBuffer, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT,
                   TINYGLTF_TYPE_SCALAR, scene.indices.size());
    return prim;
}

// Nodes 0..bones-1 are the joints (the root at the chain's middle), node `bones` the mesh.
void add_skeleton(tinygltf::Model* model, const Chain& c) {
    const int bones = int(c.joints.size());
    std::vector<float> inverse_binds;
    tinygltf::Skin skin;
    skin.name = "bend_chain";
    for (int i = 0; i < bones; ++i) {
        tinygltf::Node node;
        node.name = "bone" + std::to_string(i);
        const int parent = parent_of(c, i);
        const glm::vec3 t =
            parent < 0 ? c.joints[size_t(i)] : c.joints[size_t(i)] - c.joints[size_t(parent)];
        node.translation = {t.x, t.y, t.z};
        if (i > 0 && i <= c.root) node.children.push_back(i - 1);
        if (i >= c.root && i + 1 < bones) node.children.push_back(i + 1);
        model->nodes.push_back(node);
        const glm::mat4 inverse = glm::translate(glm::mat4(1.0f), -c.joints[size_t(i)]);
        inverse_binds.insert(inverse_binds.end(), glm::value_ptr(inverse),
                             glm::value_ptr(inverse) + 16);
        skin.joints.push_back(i);
    }
    tinygltf::Node mesh;
    mesh.name = "body";
    mesh.mesh = 0;
    mesh.skin = 0;
    model->nodes.push_back(mesh);
    skin.skeleton = c.root;
    skin.inverseBindMatrices = add_values(model, inverse_binds, 0, TINYGLTF_COMPONENT_TYPE_FLOAT,
                                          TINYGLTF_TYPE_MAT4, size_t(bones));
    model->skins.push_back(skin);
}

// "bend": one rotation channel per joint, `keys` LINEAR keys over one period, the last key
// equal to the first so the loop has no seam.
void add_bend_clip(tinygltf::Model* model, const Chain& c, const BendRigOptions& o) {
    std::vector<float> times;
    for (int k = 0; k < o.keys; ++k)
        times.push_back(o.period_seconds * float(k) / float(o.keys - 1));
    const int input =
        add_values(model, times, 0, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_SCALAR,
                   times.size(), {times.front()}, {times.back()});
    tinygltf::Animation clip;
    clip.name = "bend";
    for (int i = 0; i < int(c.joints.size()); ++i) {
        std::vector<float> values;
        for (int k = 0; k < o.keys; ++k) {
            const float phase = k == o.keys - 1 ? 0.0f : float(k) / float(o.keys - 1);
            const glm::quat q = joint_rotation(c, o, i, phase);
            values.insert(values.end(), {q.x, q.y, q.z, q.w});
        }
        tinygltf::AnimationSampler sampler;
        sampler.input = input;
        sampler.output = add_values(model, values, 0, TINYGLTF_COMPONENT_TYPE_FLOAT,
                                    TINYGLTF_TYPE_VEC4, size_t(o.keys));
        sampler.interpolation = "LINEAR";
        clip.samplers.push_back(sampler);
        tinygltf::AnimationChannel channel;
        channel.sampler = int(clip.samplers.size() - 1);
        channel.target_node = i;
        channel.target_path = "rotation";
        clip.channels.push_back(channel);
    }
    model->animations.push_back(clip);
}

tinygltf::Model build_model(const bake::RawScene& scene, const Chain& chain,
                            const BendRigOptions& o) {
    tinygltf::Model model;
    model.asset.version = "2.0";
    model.asset.generator = "stipple tools/make_bend_rig.cpp";
    model.buffers.resize(1);
    tinygltf::Mesh mesh;
    mesh.name = "body";
    mesh.primitives.push_back(add_primitive(&model, scene, chain));
    model.meshes.push_back(mesh);
    add_skeleton(&model, chain);
    add_bend_clip(&model, chain, o);
    tinygltf::Scene s;
    s.name = "bend_rig";
    s.nodes = {chain.root, int(chain.joints.size())};
    model.scenes.push_back(s);
    model.defaultScene = 0;
    return model;
}

}  // namespace

bool write_bend_rig(const std::string& in, const std::string& out, const BendRigOptions& o,
                    BendRigSummary* summary, std::string* error) {
    if (o.bones < 2 || o.bones > 64 || o.keys < 2 || !(o.period_seconds > 0.0f)) {
        *error = "bones must be 2..64, keys at least 2 and the period positive";
        return false;
    }
    bake::RawScene scene;
    const bake::BakeError imported = bake::import_scene(in, &scene);
    if (!imported.ok()) {
        *error = imported.message;
        return false;
    }
    if (scene.animated()) {
        *error = in + ": already has a skin or clips; give a static mesh";
        return false;
    }
    if (scene.vertex_count() == 0 || scene.triangle_count() == 0) {
        *error = in + ": no triangles";
        return false;
    }
    bake::apply_up_axis(o.up_axis, &scene);  // static scenes: positions and normals turned
    const Chain chain = make_chain(scene.positions, o.bones);
    const tinygltf::Model model = build_model(scene, chain, o);
    tinygltf::TinyGLTF writer;
    if (!writer.WriteGltfSceneToFile(&model, out, true, true, false, false)) {
        *error = "cannot write '" + out + "'";
        return false;
    }
    summary->vertices = scene.vertex_count();
    summary->triangles = scene.triangle_count();
    summary->chain_axis = chain.axis;
    summary->chain_length = chain.length;
    return true;
}

}  // namespace stipple::tools
