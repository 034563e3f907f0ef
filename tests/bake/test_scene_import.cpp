// Scene importers: glTF 2.0 (CesiumMan and small hand-written files) and static meshes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <limits>
#include <string>
#include <vector>

#include "bake/scene_import.h"
#include "tests/common/bake_result.h"
#include "tests/common/gltf_writer.h"
#include "tests/common/scratch.h"

namespace stipple::bake {
namespace {

const char* const kCesiumMan = STIPPLE_SOURCE_DIR "/assets/CesiumMan/CesiumMan.glb";

std::string temp_path(const std::string& name) {
    return stipple::test::scratch_path(name);
}

std::string write_file(const std::string& name, const std::string& content) {
    const std::string path = temp_path(name);
    std::ofstream(path, std::ios::binary) << content;
    return path;
}

// Little-endian binary buffer built value by value (tests/common/gltf_writer.h).
using Bin = stipple::test::GltfBin;

void replace_all(std::string* s, const std::string& from, const std::string& to) {
    for (size_t at = s->find(from); at != std::string::npos; at = s->find(from, at + to.size())) {
        s->replace(at, from.size(), to);
    }
}

// Writes a .gltf whose "@BUFFER@" placeholder becomes buffer 0 holding `bin` as a data URI.
std::string write_named_gltf(const std::string& name, std::string json, const Bin& bin) {
    replace_all(&json, "@BUFFER@",
                R"({"uri": "data:application/octet-stream;base64,)" +
                    stipple::test::gltf_base64(bin.bytes) + R"(", "byteLength": )" +
                    std::to_string(bin.bytes.size()) + "}");
    return write_file(name, json);
}

// Positions of the triangle (0,0,0), (1,0,0), (0,1,0) followed by uint16 indices.
Bin triangle_bin(std::initializer_list<uint16_t> indices) {
    Bin bin;
    bin.put<float>({0, 0, 0, 1, 0, 0, 0, 1, 0}).put<uint16_t>(indices).pad4();
    return bin;
}

// One indexed triangle on node 0, translated by (1, 2, 3).
const char* const kTriangleJson = R"({
  "asset": {"version": "2.0"},
  "scene": 0,
  "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0, "translation": [1, 2, 3]}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
  "buffers": [@BUFFER@],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                  {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
     "min": [0, 0, 0], "max": [1, 1, 0]},
    {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}]
})";

bool contains_text(const std::vector<std::string>& lines, const std::string& text) {
    for (const std::string& line : lines) {
        if (line.find(text) != std::string::npos) return true;
    }
    return false;
}

void expect_one_line_error(const std::string& error) {
    EXPECT_FALSE(error.empty());
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
}

glm::mat4 trs_matrix(const RawNode& n) {
    const glm::quat q(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]);
    glm::mat4 m = glm::mat4_cast(q);
    for (int c = 0; c < 3; ++c) m[c] *= n.scale[c];
    m[3] = glm::vec4(n.translation[0], n.translation[1], n.translation[2], 1.0f);
    return m;
}

// ---------------------------------------------------------------------------------------

TEST(GltfImport, CesiumManHasOneSkinOneClipAndValidWeights) {
    RawScene s;
    std::string error;
    ASSERT_TRUE(stipple::test::bake_ok(import_gltf(kCesiumMan, &s), &error)) << error;
    ASSERT_TRUE(s.animated());
    EXPECT_EQ(s.joint_nodes.size(), 19u);
    EXPECT_EQ(s.inverse_bind.size(), 19u * 16u);
    ASSERT_EQ(s.clips.size(), 1u);

    const size_t vc = s.vertex_count();
    ASSERT_GT(vc, 0u);
    ASSERT_GT(s.triangle_count(), 0u);
    ASSERT_EQ(s.normals.size(), vc * 3);
    ASSERT_EQ(s.joints.size(), vc * 4);
    ASSERT_EQ(s.weights.size(), vc * 4);
    for (uint32_t index : s.indices) ASSERT_LT(index, vc);
    for (size_t v = 0; v < vc; ++v) {
        float sum = 0.0f;
        for (int k = 0; k < 4; ++k) {
            ASSERT_LT(s.joints[v * 4 + k], s.joint_nodes.size()) << "vertex " << v;
            ASSERT_GE(s.weights[v * 4 + k], 0.0f);
            sum += s.weights[v * 4 + k];
        }
        ASSERT_NEAR(sum, 1.0f, 1e-5f) << "vertex " << v;
        const glm::vec3 n = glm::make_vec3(&s.normals[v * 3]);
        ASSERT_NEAR(glm::length(n), 1.0f, 1e-4f) << "vertex " << v;
    }

    // Parents before children, joints and channels name existing nodes.
    for (size_t i = 0; i < s.nodes.size(); ++i) ASSERT_LT(s.nodes[i].parent, int32_t(i));
    for (uint32_t node : s.joint_nodes) ASSERT_LT(node, s.nodes.size());
    const RawClip& clip = s.clips[0];
    EXPECT_GT(clip.duration, 0.0f);
    ASSERT_FALSE(clip.channels.empty());
    for (const RawChannel& ch : clip.channels) {
        ASSERT_LT(ch.node, s.nodes.size());
        ASSERT_FALSE(ch.times.empty());
        const size_t width = ch.path == RawPath::rotation ? 4 : 3;
        ASSERT_EQ(ch.values.size(), ch.times.size() * width);
        for (size_t k = 1; k < ch.times.size(); ++k) ASSERT_LT(ch.times[k - 1], ch.times[k]);
        ASSERT_LE(ch.times.back(), clip.duration);
        if (ch.path == RawPath::rotation) {
            for (size_t k = 0; k < ch.times.size(); ++k) {
                ASSERT_NEAR(glm::length(glm::make_vec4(&ch.values[k * 4])), 1.0f, 1e-5f);
            }
        }
    }

    // Bind-pose sanity: the mesh, and the mesh skinned with the rest pose (world(joint) *
    // inverse bind), both have finite, non-degenerate bounding boxes of similar size.
    std::vector<glm::mat4> world(s.nodes.size());
    for (size_t i = 0; i < s.nodes.size(); ++i) {
        const glm::mat4 local = trs_matrix(s.nodes[i]);
        world[i] = s.nodes[i].parent < 0 ? local : world[size_t(s.nodes[i].parent)] * local;
    }
    std::vector<glm::mat4> skin(s.joint_nodes.size());
    for (size_t j = 0; j < skin.size(); ++j) {
        skin[j] = world[s.joint_nodes[j]] * glm::make_mat4(&s.inverse_bind[j * 16]);
    }
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    glm::vec3 skinned_lo = lo, skinned_hi = hi;
    for (size_t v = 0; v < vc; ++v) {
        const glm::vec4 p(glm::make_vec3(&s.positions[v * 3]), 1.0f);
        glm::mat4 m(0.0f);
        for (int k = 0; k < 4; ++k) m += s.weights[v * 4 + k] * skin[s.joints[v * 4 + k]];
        const glm::vec3 q(m * p);
        lo = glm::min(lo, glm::vec3(p));
        hi = glm::max(hi, glm::vec3(p));
        skinned_lo = glm::min(skinned_lo, q);
        skinned_hi = glm::max(skinned_hi, q);
    }
    for (int c = 0; c < 3; ++c) {
        ASSERT_TRUE(std::isfinite(lo[c]) && std::isfinite(hi[c]));
        ASSERT_TRUE(std::isfinite(skinned_lo[c]) && std::isfinite(skinned_hi[c]));
        EXPECT_GT(hi[c] - lo[c], 1e-3f);
        EXPECT_GT(skinned_hi[c] - skinned_lo[c], 1e-3f);
    }
    const float diagonal = glm::length(hi - lo);
    const float skinned_diagonal = glm::length(skinned_hi - skinned_lo);
    EXPECT_GT(skinned_diagonal, 0.5f * diagonal);
    EXPECT_LT(skinned_diagonal, 2.0f * diagonal);
}

TEST(GltfImport, StaticTriangleIsBakedToWorldSpace) {
    const std::string path =
        write_named_gltf("static_triangle.gltf", kTriangleJson, triangle_bin({0, 1, 2}));
    RawScene s;
    std::string error;
    ASSERT_TRUE(stipple::test::bake_ok(import_gltf(path, &s), &error)) << error;
    EXPECT_FALSE(s.animated());
    EXPECT_TRUE(s.joints.empty());
    EXPECT_TRUE(s.weights.empty());
    EXPECT_TRUE(s.inverse_bind.empty());
    EXPECT_TRUE(s.clips.empty());
    const std::vector<float> expected = {1, 2, 3, 2, 2, 3, 1, 3, 3};
    EXPECT_EQ(s.positions, expected);
    EXPECT_EQ(s.indices, (std::vector<uint32_t>{0, 1, 2}));
    // No NORMAL attribute: computed from the triangle.
    for (size_t v = 0; v < 3; ++v) {
        EXPECT_FLOAT_EQ(s.normals[v * 3 + 0], 0.0f);
        EXPECT_FLOAT_EQ(s.normals[v * 3 + 1], 0.0f);
        EXPECT_FLOAT_EQ(s.normals[v * 3 + 2], 1.0f);
    }
}

TEST(GltfImport, HierarchyAndMatrixNodesComposeInStaticScenes) {
    // Parent: matrix = rotate 90 degrees about z, translate (10, 0, 0). Child: scale 2.
    // The child's triangle (0,0,0), (1,0,0), (0,1,0) lands at (10,0,0), (10,2,0), (8,0,0).
    std::string json = kTriangleJson;
    replace_all(&json, R"("scenes": [{"nodes": [0]}],)", R"("scenes": [{"nodes": [1]}],)");
    replace_all(&json, R"("nodes": [{"mesh": 0, "translation": [1, 2, 3]}],)",
                R"("nodes": [{"mesh": 0, "scale": [2, 2, 2]},
                             {"children": [0],
                              "matrix": [0, 1, 0, 0, -1, 0, 0, 0, 0, 0, 1, 0, 10, 0, 0, 1]}],)");
    const std::string path = write_named_gltf("hierarchy.gltf", json, triangle_bin({0, 1, 2}));
    RawScene s;
    std::string error;
    ASSERT_TRUE(stipple::test::bake_ok(import_gltf(path, &s), &error)) << error;
    ASSERT_EQ(s.nodes.size(), 2u);
    EXPECT_EQ(s.nodes[0].parent, -1);  // the matrix node, reordered before its child
    EXPECT_EQ(s.nodes[1].parent, 0);
    EXPECT_FLOAT_EQ(s.nodes[0].translation[0], 10.0f);
    EXPECT_NEAR(s.nodes[0].rotation[2], std::sqrt(0.5f), 1e-6f);
    EXPECT_NEAR(s.nodes[0].rotation[3], std::sqrt(0.5f), 1e-6f);
    EXPECT_NEAR(s.nodes[0].scale[0], 1.0f, 1e-6f);
    const float expected[9] = {10, 0, 0, 10, 2, 0, 8, 0, 0};
    ASSERT_EQ(s.positions.size(), 9u);
    for (int i = 0; i < 9; ++i) EXPECT_NEAR(s.positions[i], expected[i], 1e-5f) << i;
    EXPECT_TRUE(s.warnings.empty());
}

TEST(GltfImport, OutOfRangeIndexFails) {
    const std::string path =
        write_named_gltf("bad_index.gltf", kTriangleJson, triangle_bin({0, 1, 5}));
    RawScene s;
    std::string error;
    EXPECT_FALSE(stipple::test::bake_ok(import_gltf(path, &s), &error));
    expect_one_line_error(error);
    EXPECT_NE(error.find("out of range"), std::string::npos) << error;
    EXPECT_NE(error.find("index 5"), std::string::npos) << error;
    EXPECT_EQ(s.vertex_count(), 0u);
}

TEST(GltfImport, AccessorPastTheEndOfItsBufferFails) {
    std::string json = kTriangleJson;
    replace_all(&json, R"("count": 3, "type": "VEC3")", R"("count": 4, "type": "VEC3")");
    const std::string path = write_named_gltf("short_buffer.gltf", json, triangle_bin({0, 1, 2}));
    RawScene s;
    std::string error;
    EXPECT_FALSE(stipple::test::bake_ok(import_gltf(path, &s), &error));
    expect_one_line_error(error);
    EXPECT_NE(error.find("exceed bufferView 0"), std::string::npos) << error;
}

TEST(GltfImport, NonGltfFilesFail) {
    std::string random(256, '\0');
    uint32_t state = 12345;
    for (char& c : random) {
        state = state * 1664525u + 1013904223u;
        c = char(state >> 24);
    }
    const std::vector<std::string> paths = {
        write_file("text.gltf", "this is not json\nsecond line\n"),
        write_file("random.glb", random),
        write_file("bad_header.glb", "glTF" + random),
        write_file("empty.gltf", ""),
        write_file("json_not_gltf.gltf", R"({"hello": [1, 2, 3]})"),
        temp_path("does_not_exist.gltf"),
    };
    for (const std::string& path : paths) {
        RawScene s;
        std::string error;
        EXPECT_FALSE(stipple::test::bake_ok(import_gltf(path, &s), &error)) << path;
        expect_one_line_error(error);
        EXPECT_EQ(error.rfind(path, 0), 0u) << error;  // names the file
    }
}

TEST(GltfImport, TriangleStripKeepsWindingAndStrideIsHonoured) {
    // Interleaved POSITION + NORMAL (byteStride 24) of a 4-vertex strip; the normals are
    // (0, 0, 2) and come out normalised.
    Bin bin;
    bin.put<float>({0, 0, 0, 0, 0, 2, 1, 0, 0, 0, 0, 2, 0, 1, 0, 0, 0, 2, 1, 1, 0, 0, 0, 2});
    const std::string json = R"({
      "asset": {"version": "2.0"},
      "nodes": [{"mesh": 0}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "mode": 5}]}],
      "buffers": [@BUFFER@],
      "bufferViews": [{"buffer": 0, "byteLength": 96, "byteStride": 24}],
      "accessors": [
        {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
         "min": [0, 0, 0], "max": [1, 1, 0]},
        {"bufferView": 0, "byteOffset": 12, "componentType": 5126, "count": 4, "type": "VEC3"}]
    })";
    const std::string path = write_named_gltf("strip.gltf", json, bin);
    RawScene s;
    std::string error;
    ASSERT_TRUE(stipple::test::bake_ok(import_gltf(path, &s), &error)) << error;
    ASSERT_EQ(s.triangle_count(), 2u);
    ASSERT_EQ(s.vertex_count(), 4u);
    for (size_t t = 0; t < 2; ++t) {
        const glm::vec3 a = glm::make_vec3(&s.positions[s.indices[t * 3] * 3]);
        const glm::vec3 b = glm::make_vec3(&s.positions[s.indices[t * 3 + 1] * 3]);
        const glm::vec3 c = glm::make_vec3(&s.positions[s.indices[t * 3 + 2] * 3]);
        EXPECT_GT(glm::cross(b - a, c - a).z, 0.0f) << "triangle " << t;
    }
    for (size_t v = 0; v < 4; ++v) EXPECT_FLOAT_EQ(s.normals[v * 3 + 2], 1.0f);
}

// Skin 0 = joints {node 0 "root", node 1 "bone"}, no inverse bind matrices. Node 2 draws
// mesh 0 skinned; node 3 (a second root) draws the same mesh without a skin. JOINTS_0 are
// UNSIGNED_BYTE, WEIGHTS_0 normalized UNSIGNED_BYTE:
//   vertex 0: joints (0, 1, 0, 0), weights (128, 64, 0, 0) -> 2/3 root, 1/3 bone
//   vertex 1: weights all 0 -> bound to joint 0
//   vertex 2: joints (0, 1, 9, 0), weights (0, 255, w2, 0): joint 9 does not exist, which
//             is harmless while its weight w2 is 0.
std::string write_skinned_gltf(const std::string& name, uint8_t w2) {
    Bin bin;
    bin.put<float>({0, 0, 0, 1, 0, 0, 0, 1, 0});                   // 0: positions
    bin.put<uint8_t>({0, 1, 0, 0, 0, 0, 0, 0, 0, 1, 9, 0});        // 36: joints
    bin.put<uint8_t>({128, 64, 0, 0, 0, 0, 0, 0, 0, 255, w2, 0});  // 48: weights
    const std::string json = R"({
      "asset": {"version": "2.0"},
      "scenes": [{"nodes": [0, 3]}],
      "nodes": [{"name": "root", "children": [1, 2]},
                {"name": "bone", "translation": [0, 1, 0]},
                {"name": "skinned", "mesh": 0, "skin": 0},
                {"name": "rigid", "mesh": 0, "translation": [5, 0, 0]}],
      "skins": [{"joints": [0, 1]}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "JOINTS_0": 1, "WEIGHTS_0": 2}}]}],
      "buffers": [@BUFFER@],
      "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                      {"buffer": 0, "byteOffset": 36, "byteLength": 12},
                      {"buffer": 0, "byteOffset": 48, "byteLength": 12}],
      "accessors": [
        {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
         "min": [0, 0, 0], "max": [1, 1, 0]},
        {"bufferView": 1, "componentType": 5121, "count": 3, "type": "VEC4"},
        {"bufferView": 2, "componentType": 5121, "normalized": true, "count": 3, "type": "VEC4"}]
    })";
    return write_named_gltf(name, json, bin);
}

TEST(GltfImport, SkinWeightsAreRenormalisedAndUnskinnedMeshesBecomeRigidJoints) {
    RawScene s;
    std::string error;
    ASSERT_TRUE(
        stipple::test::bake_ok(import_gltf(write_skinned_gltf("skinned.gltf", 0), &s), &error))
        << error;
    ASSERT_TRUE(s.animated());
    ASSERT_EQ(s.nodes.size(), 4u);
    EXPECT_EQ(s.nodes[3].name, "rigid");
    // Skin joints first, then the rigidly attached node, all with identity inverse binds.
    EXPECT_EQ(s.joint_nodes, (std::vector<uint32_t>{0, 1, 3}));
    ASSERT_EQ(s.inverse_bind.size(), 3u * 16u);
    for (size_t k = 0; k < s.inverse_bind.size(); ++k) {
        EXPECT_EQ(s.inverse_bind[k], k % 16 % 5 == 0 ? 1.0f : 0.0f) << k;
    }
    ASSERT_EQ(s.vertex_count(), 6u);
    EXPECT_EQ(s.joints, (std::vector<uint16_t>{0, 1, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0,  // skinned
                                               2, 0, 0, 0, 2, 0, 0, 0, 2, 0, 0, 0}));
    EXPECT_NEAR(s.weights[0], 2.0f / 3.0f, 1e-6f);
    EXPECT_NEAR(s.weights[1], 1.0f / 3.0f, 1e-6f);
    const std::vector<float> tail(s.weights.begin() + 4, s.weights.end());
    EXPECT_EQ(tail, (std::vector<float>{1, 0, 0, 0, 1, 0, 0, 0,                 // skinned
                                        1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}));  // rigid
    // Both copies keep their local (bind-space) positions.
    const std::vector<float> triangle = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    EXPECT_EQ(std::vector<float>(s.positions.begin(), s.positions.begin() + 9), triangle);
    EXPECT_EQ(std::vector<float>(s.positions.begin() + 9, s.positions.end()), triangle);
    EXPECT_TRUE(contains_text(s.warnings, "1 vertices have no positive weight"));
}

TEST(GltfImport, WeightedJointOutsideTheSkinFails) {
    RawScene s;
    std::string error;
    EXPECT_FALSE(
        stipple::test::bake_ok(import_gltf(write_skinned_gltf("bad_joint.gltf", 10), &s), &error));
    expect_one_line_error(error);
    EXPECT_NE(error.find("joint index 9 out of range (skin 0 has 2 joints)"), std::string::npos)
        << error;
}

TEST(GltfImport, SparseAccessorWithoutBufferViewIsZerosWithSubstitutions) {
    // POSITION: 3 zero vectors, with vertices 1 and 2 replaced by (1,0,0) and (0,1,0).
    Bin bin;
    bin.put<uint16_t>({1, 2}).put<float>({1, 0, 0, 0, 1, 0});
    const std::string json = R"({
      "asset": {"version": "2.0"},
      "nodes": [{"mesh": 0}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
      "buffers": [@BUFFER@],
      "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 4},
                      {"buffer": 0, "byteOffset": 4, "byteLength": 24}],
      "accessors": [
        {"componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0],
         "sparse": {"count": 2,
                    "indices": {"bufferView": 0, "componentType": 5123},
                    "values": {"bufferView": 1}}}]
    })";
    RawScene s;
    std::string error;
    ASSERT_TRUE(
        stipple::test::bake_ok(import_gltf(write_named_gltf("sparse.gltf", json, bin), &s), &error))
        << error;
    EXPECT_EQ(s.positions, (std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0}));
    EXPECT_EQ(s.triangle_count(), 1u);
}

// A non-indexed triangle on node 0 (translation (1, 2, 3)) with one animation:
// channel 0 LINEAR translation, channel 1 CUBICSPLINE scale, channel 2 STEP rotation with
// normalized BYTE quaternions, channel 3 targets a node that does not exist.
std::string write_animated_gltf(const std::string& name, const std::string& channels) {
    Bin bin;
    bin.put<float>({0, 0, 0, 1, 0, 0, 0, 1, 0});  // 0: positions, 36 bytes
    bin.put<float>({0.0f, 1.5f});                 // 36: times, 8 bytes
    bin.put<float>({0, 0, 0, 0, 5, 0});           // 44: translations, 24
    for (int k = 0; k < 2; ++k) bin.put<float>({0, 0, 0, 1, 1, 1, 0, 0, 0});  // 68: cubic, 72
    bin.put<int8_t>({0, 0, 0, 127, 0, 0, 127, 0});                            // 140: rotations, 8
    std::string json = R"({
      "asset": {"version": "2.0"},
      "scenes": [{"nodes": [0]}],
      "nodes": [{"mesh": 0, "translation": [1, 2, 3]}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
      "buffers": [@BUFFER@],
      "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                      {"buffer": 0, "byteOffset": 36, "byteLength": 8},
                      {"buffer": 0, "byteOffset": 44, "byteLength": 24},
                      {"buffer": 0, "byteOffset": 68, "byteLength": 72},
                      {"buffer": 0, "byteOffset": 140, "byteLength": 8}],
      "accessors": [
        {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
         "min": [0, 0, 0], "max": [1, 1, 0]},
        {"bufferView": 1, "componentType": 5126, "count": 2, "type": "SCALAR",
         "min": [0], "max": [1.5]},
        {"bufferView": 2, "componentType": 5126, "count": 2, "type": "VEC3"},
        {"bufferView": 3, "componentType": 5126, "count": 6, "type": "VEC3"},
        {"bufferView": 4, "componentType": 5120, "normalized": true, "count": 2, "type": "VEC4"}],
      "animations": [{
        "name": "Walk",
        "samplers": [{"input": 1, "output": 2, "interpolation": "LINEAR"},
                     {"input": 1, "output": 3, "interpolation": "CUBICSPLINE"},
                     {"input": 1, "output": 4, "interpolation": "STEP"}],
        "channels": [@CHANNELS@]}]
    })";
    replace_all(&json, "@CHANNELS@", channels);
    return write_named_gltf(name, json, bin);
}

TEST(GltfImport, CubicsplineIsImportedAndBadChannelsAreSkippedWithWarnings) {
    const std::string path = write_animated_gltf("cubic.gltf", R"(
        {"sampler": 0, "target": {"node": 0, "path": "translation"}},
        {"sampler": 1, "target": {"node": 0, "path": "scale"}},
        {"sampler": 2, "target": {"node": 0, "path": "rotation"}},
        {"sampler": 0, "target": {"node": 7, "path": "translation"}})");
    RawScene s;
    std::string error;
    ASSERT_TRUE(stipple::test::bake_ok(import_gltf(path, &s), &error)) << error;
    EXPECT_FALSE(contains_text(s.warnings, "animation 'Walk' channel 1"));
    EXPECT_TRUE(
        contains_text(s.warnings, "animation 'Walk' channel 3: target node 7 out of range"));

    ASSERT_EQ(s.clips.size(), 1u);
    const RawClip& clip = s.clips[0];
    EXPECT_EQ(clip.name, "Walk");
    EXPECT_FLOAT_EQ(clip.duration, 1.5f);
    ASSERT_EQ(clip.channels.size(), 3u);
    EXPECT_EQ(clip.channels[0].path, RawPath::translation);
    EXPECT_EQ(clip.channels[0].interp, RawInterp::linear);
    EXPECT_EQ(clip.channels[0].values, (std::vector<float>{0, 0, 0, 0, 5, 0}));
    // CUBICSPLINE keeps glTF's (in-tangent, value, out-tangent) triple per key.
    const RawChannel& cubic = clip.channels[1];
    EXPECT_EQ(cubic.path, RawPath::scale);
    EXPECT_EQ(cubic.interp, RawInterp::cubic_spline);
    EXPECT_EQ(cubic.values, (std::vector<float>{0, 0, 0, 1, 1, 1, 0, 0, 0,  //
                                                0, 0, 0, 1, 1, 1, 0, 0, 0}));
    const RawChannel& rotation = clip.channels[2];
    EXPECT_EQ(rotation.path, RawPath::rotation);
    EXPECT_EQ(rotation.interp, RawInterp::step);
    EXPECT_EQ(rotation.values, (std::vector<float>{0, 0, 0, 1, 0, 0, 1, 0}));

    // No skin, but animated: the mesh node is attached rigidly as joint 0, local space.
    ASSERT_TRUE(s.animated());
    EXPECT_EQ(s.joint_nodes, (std::vector<uint32_t>{0}));
    const std::vector<float> identity = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    EXPECT_EQ(s.inverse_bind, identity);
    EXPECT_EQ(s.positions, (std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0}));
    EXPECT_EQ(s.joints, (std::vector<uint16_t>(12, 0)));
    EXPECT_EQ(s.weights, (std::vector<float>{1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}));
    EXPECT_FLOAT_EQ(s.nodes[0].translation[1], 2.0f);
}

TEST(GltfImport, ClipWithOnlyUnsupportedChannelsIsDroppedAndSceneIsStatic) {
    // Morph weights on a node whose mesh has no morph targets: skipped.
    const std::string path = write_animated_gltf(
        "weights_only.gltf", R"({"sampler": 0, "target": {"node": 0, "path": "weights"}})");
    RawScene s;
    std::string error;
    ASSERT_TRUE(stipple::test::bake_ok(import_gltf(path, &s), &error)) << error;
    EXPECT_TRUE(contains_text(s.warnings, "has no mesh with morph targets"));
    EXPECT_TRUE(contains_text(s.warnings, "clip dropped"));
    EXPECT_TRUE(s.clips.empty());
    EXPECT_FALSE(s.animated());
    EXPECT_EQ(s.positions, (std::vector<float>{1, 2, 3, 2, 2, 3, 1, 3, 3}));
}

// ---------------------------------------------------------------------------------------

TEST(StaticMeshImport, ObjCubeOfQuadsIsTriangulatedWithOutwardNormals) {
    const std::string path = write_file("cube.obj",
                                        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                                        "v 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                                        "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\n"
                                        "f 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n");
    RawScene s;
    std::string error;
    ASSERT_TRUE(stipple::test::bake_ok(import_static_mesh(path, &s), &error)) << error;
    EXPECT_FALSE(s.animated());
    EXPECT_EQ(s.triangle_count(), 12u);
    ASSERT_EQ(s.vertex_count(), 8u);
    ASSERT_EQ(s.normals.size(), 24u);
    const glm::vec3 center(0.5f);
    for (size_t v = 0; v < 8; ++v) {
        const glm::vec3 p = glm::make_vec3(&s.positions[v * 3]);
        const glm::vec3 n = glm::make_vec3(&s.normals[v * 3]);
        EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
        EXPECT_GT(glm::dot(n, p - center), 0.0f) << "vertex " << v;
    }
    // The dispatcher takes the same path, whatever the extension's case.
    const std::string upper = write_file("CUBE.OBJ", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    ASSERT_TRUE(stipple::test::bake_ok(import_scene(upper, &s), &error)) << error;
    EXPECT_EQ(s.triangle_count(), 1u);
}

TEST(StaticMeshImport, FilesWithoutTrianglesFail) {
    RawScene s;
    std::string error;
    EXPECT_FALSE(stipple::test::bake_ok(
        import_static_mesh(write_file("points.obj", "v 0 0 0\nv 1 0 0\n"), &s), &error));
    expect_one_line_error(error);
    EXPECT_NE(error.find("no triangles"), std::string::npos) << error;
    EXPECT_FALSE(stipple::test::bake_ok(import_static_mesh(temp_path("missing.stl"), &s), &error));
    expect_one_line_error(error);
    EXPECT_NE(error.find("cannot open"), std::string::npos) << error;
}

TEST(SceneImport, DispatchesOnExtensionAndRejectsUnknownOnes) {
    RawScene s;
    std::string error;
    EXPECT_FALSE(
        stipple::test::bake_ok(import_scene(write_file("mesh.fbx", "whatever"), &s), &error));
    expect_one_line_error(error);
    EXPECT_NE(error.find("unsupported file extension"), std::string::npos) << error;
    EXPECT_FALSE(stipple::test::bake_ok(import_scene(temp_path("no_extension"), &s), &error));
    EXPECT_NE(error.find("unsupported file extension"), std::string::npos) << error;

    ASSERT_TRUE(stipple::test::bake_ok(import_scene(kCesiumMan, &s), &error)) << error;
    EXPECT_TRUE(s.animated());
}

}  // namespace
}  // namespace stipple::bake
