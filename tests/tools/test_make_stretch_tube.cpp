// make-stretch-tube (tools/make_stretch_tube.cpp): the generated skinned tube asset matches
// its specification, its options change the mesh, and bad options are refused.
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "tests/common/fixtures.h"

namespace {

namespace fs = std::filesystem;
using stipple::test::ScratchDir;

int run_command(const std::string& command) {
    return stipple::test::run(command);
}

const std::string kTubeTool = std::string(STIPPLE_BIN_DIR) + "/make-stretch-tube";

// Reads `count` elements of `components` floats, honouring byteStride.
std::vector<float> read_floats(const tinygltf::Model& m, int accessor_index, int components) {
    const tinygltf::Accessor& a = m.accessors.at(accessor_index);
    EXPECT_EQ(a.componentType, TINYGLTF_COMPONENT_TYPE_FLOAT);
    const tinygltf::BufferView& v = m.bufferViews.at(a.bufferView);
    const std::vector<unsigned char>& data = m.buffers.at(v.buffer).data;
    const size_t stride = v.byteStride ? v.byteStride : components * sizeof(float);
    std::vector<float> out(a.count * components);
    for (size_t i = 0; i < a.count; ++i) {
        std::memcpy(&out[i * components], &data.at(v.byteOffset + a.byteOffset + i * stride),
                    components * sizeof(float));
    }
    return out;
}

std::vector<uint32_t> read_uints(const tinygltf::Model& m, int accessor_index, int components) {
    const tinygltf::Accessor& a = m.accessors.at(accessor_index);
    const tinygltf::BufferView& v = m.bufferViews.at(a.bufferView);
    const std::vector<unsigned char>& data = m.buffers.at(v.buffer).data;
    const size_t size = tinygltf::GetComponentSizeInBytes(a.componentType);
    const size_t stride = v.byteStride ? v.byteStride : components * size;
    std::vector<uint32_t> out(a.count * components);
    for (size_t i = 0; i < a.count; ++i) {
        for (int c = 0; c < components; ++c) {
            const unsigned char* p = &data.at(v.byteOffset + a.byteOffset + i * stride + c * size);
            uint32_t value = 0;
            if (size == 1) {
                value = p[0];
            } else if (size == 2) {
                uint16_t s;
                std::memcpy(&s, p, 2);
                value = s;
            } else {
                std::memcpy(&value, p, 4);
            }
            out[i * components + c] = value;
        }
    }
    return out;
}

int find_node(const tinygltf::Model& m, const std::string& name) {
    for (size_t i = 0; i < m.nodes.size(); ++i) {
        if (m.nodes[i].name == name) return static_cast<int>(i);
    }
    return -1;
}

// Bad usage: one line on stderr and exit status 1, like every tool (tools/cli_options.h).
TEST(StretchTube, CliUsageAndBadOptions) {
    ASSERT_TRUE(fs::exists(kTubeTool)) << kTubeTool << " is not built";
    EXPECT_EQ(run_command("'" + kTubeTool + "' --help > /dev/null"), 0);
    EXPECT_EQ(run_command("'" + kTubeTool + "' 2> /dev/null"), 1);
    EXPECT_EQ(run_command("'" + kTubeTool + "' x.gltf --bogus 1 2> /dev/null"), 1);
    EXPECT_EQ(run_command("'" + kTubeTool + "' x.gltf --segments-around 2 2> /dev/null"), 1);
    EXPECT_EQ(run_command("'" + kTubeTool + "' x.gltf --segments-along abc 2> /dev/null"), 1);
}

TEST(StretchTube, GeneratedAssetMatchesSpecification) {
    ASSERT_TRUE(fs::exists(kTubeTool)) << kTubeTool << " is not built";
    ScratchDir dir;
    const std::string path = dir.file("tube.gltf");
    ASSERT_EQ(run_command("'" + kTubeTool + "' '" + path + "' > /dev/null"), 0);

    tinygltf::TinyGLTF loader;
    tinygltf::Model m;
    std::string err, warn;
    ASSERT_TRUE(loader.LoadASCIIFromFile(&m, &err, &warn, path)) << err;

    // Rig: "lower" root at the origin, "upper" its child at (0, 0.5, 0).
    ASSERT_EQ(m.skins.size(), 1u);
    const tinygltf::Skin& skin = m.skins[0];
    ASSERT_EQ(skin.joints.size(), 2u);
    const int lower = find_node(m, "lower"), upper = find_node(m, "upper");
    ASSERT_GE(lower, 0);
    ASSERT_GE(upper, 0);
    EXPECT_EQ(skin.joints[0], lower);
    EXPECT_EQ(skin.joints[1], upper);
    EXPECT_EQ(m.nodes[lower].children, std::vector<int>{upper});
    EXPECT_TRUE(m.nodes[lower].translation.empty() ||
                m.nodes[lower].translation == std::vector<double>({0, 0, 0}));
    EXPECT_EQ(m.nodes[upper].translation, std::vector<double>({0, 0.5, 0}));
    const std::vector<float> ibm = read_floats(m, skin.inverseBindMatrices, 16);
    ASSERT_EQ(ibm.size(), 32u);
    for (int i = 0; i < 16; ++i) {
        const float identity = (i % 5 == 0) ? 1.0f : 0.0f;
        EXPECT_FLOAT_EQ(ibm[i], identity) << "lower IBM " << i;
        EXPECT_FLOAT_EQ(ibm[16 + i], i == 13 ? -0.5f : identity) << "upper IBM " << i;
    }

    // Scene 0 holds the joint root and the skinned mesh node.
    ASSERT_FALSE(m.scenes.empty());
    const std::vector<int>& roots = m.scenes[m.defaultScene >= 0 ? m.defaultScene : 0].nodes;
    int mesh_node = -1;
    for (size_t i = 0; i < m.nodes.size(); ++i) {
        if (m.nodes[i].mesh >= 0) mesh_node = static_cast<int>(i);
    }
    ASSERT_GE(mesh_node, 0);
    EXPECT_EQ(m.nodes[mesh_node].skin, 0);
    EXPECT_NE(std::find(roots.begin(), roots.end(), lower), roots.end());
    EXPECT_NE(std::find(roots.begin(), roots.end(), mesh_node), roots.end());

    // Animations: "stretch" scales upper 1 -> (1,2,1) -> 1 at t = 0, 1, 2; "rest" holds 1.
    const tinygltf::Animation* stretch = nullptr;
    const tinygltf::Animation* rest = nullptr;
    for (const tinygltf::Animation& a : m.animations) {
        if (a.name == "stretch") stretch = &a;
        if (a.name == "rest") rest = &a;
    }
    ASSERT_NE(stretch, nullptr);
    ASSERT_NE(rest, nullptr);
    ASSERT_EQ(stretch->channels.size(), 1u);
    EXPECT_EQ(stretch->channels[0].target_node, upper);
    EXPECT_EQ(stretch->channels[0].target_path, "scale");
    const tinygltf::AnimationSampler& sampler = stretch->samplers.at(stretch->channels[0].sampler);
    EXPECT_EQ(sampler.interpolation, "LINEAR");
    EXPECT_EQ(read_floats(m, sampler.input, 1), std::vector<float>({0, 1, 2}));
    EXPECT_EQ(read_floats(m, sampler.output, 3), std::vector<float>({1, 1, 1, 1, 2, 1, 1, 1, 1}));
    ASSERT_EQ(rest->channels.size(), 1u);
    EXPECT_EQ(rest->channels[0].target_node, upper);
    EXPECT_EQ(rest->channels[0].target_path, "scale");
    const tinygltf::AnimationSampler& rest_sampler = rest->samplers.at(rest->channels[0].sampler);
    EXPECT_EQ(read_floats(m, rest_sampler.output, 3), std::vector<float>({1, 1, 1}));

    // Geometry: side on the radius-0.25 cylinder, flat caps at y = 0 and 2, outward normals.
    ASSERT_EQ(m.meshes.size(), 1u);
    ASSERT_EQ(m.meshes[0].primitives.size(), 1u);
    const tinygltf::Primitive& prim = m.meshes[0].primitives[0];
    EXPECT_EQ(prim.mode, TINYGLTF_MODE_TRIANGLES);
    const std::vector<float> pos = read_floats(m, prim.attributes.at("POSITION"), 3);
    const std::vector<float> nrm = read_floats(m, prim.attributes.at("NORMAL"), 3);
    const std::vector<uint32_t> joints = read_uints(m, prim.attributes.at("JOINTS_0"), 4);
    const std::vector<float> weights = read_floats(m, prim.attributes.at("WEIGHTS_0"), 4);
    const std::vector<uint32_t> indices = read_uints(m, prim.indices, 1);
    const size_t n = pos.size() / 3;
    EXPECT_EQ(n, 65u * 48 + 2 * 49) << "48 around x 64 along, plus two cap fans";
    EXPECT_EQ(indices.size(), 3u * (64 * 48 * 2 + 2 * 48));
    ASSERT_EQ(nrm.size(), pos.size());
    ASSERT_EQ(weights.size(), n * 4);
    ASSERT_EQ(joints.size(), n * 4);
    int side = 0, cap = 0;
    for (size_t i = 0; i < n; ++i) {
        const float x = pos[3 * i], y = pos[3 * i + 1], z = pos[3 * i + 2];
        const float r2 = x * x + z * z;
        ASSERT_GE(y, 0.0f) << "vertex " << i;
        ASSERT_LE(y, 2.0f) << "vertex " << i;
        const bool is_cap = std::fabs(nrm[3 * i + 1]) > 0.5f;
        if (is_cap) {
            ++cap;
            EXPECT_TRUE(y == 0.0f || y == 2.0f) << "cap vertex " << i << " y " << y;
            EXPECT_EQ(nrm[3 * i + 1], y == 0.0f ? -1.0f : 1.0f) << "cap normal " << i;
            EXPECT_TRUE(r2 < 1e-8f || std::fabs(r2 - 0.0625f) <= 1e-4f) << "cap vertex " << i;
        } else {
            ++side;
            EXPECT_NEAR(r2, 0.0625f, 1e-4f) << "side vertex " << i;
            EXPECT_NEAR(nrm[3 * i], x / 0.25f, 1e-4f);
            EXPECT_NEAR(nrm[3 * i + 2], z / 0.25f, 1e-4f);
        }
        // Skin weights: sum to 1, rigid outside the 0.45..0.55 blend band, linear inside.
        float sum = 0.0f, w_upper = 0.0f;
        for (int k = 0; k < 4; ++k) {
            sum += weights[4 * i + k];
            ASSERT_LT(joints[4 * i + k], 2u);
            if (joints[4 * i + k] == 1) w_upper += weights[4 * i + k];
        }
        EXPECT_NEAR(sum, 1.0f, 1e-6f) << "vertex " << i;
        const float expected_upper = y <= 0.45f ? 0.0f : (y >= 0.55f ? 1.0f : (y - 0.45f) / 0.1f);
        EXPECT_NEAR(w_upper, expected_upper, 1e-5f) << "vertex " << i << " y " << y;
    }
    EXPECT_EQ(side, 65 * 48);
    EXPECT_EQ(cap, 2 * 49);

    // Counter-clockwise seen from outside: each face normal agrees with its vertex normals.
    for (size_t t = 0; t + 2 < indices.size(); t += 3) {
        const uint32_t a = indices[t], b = indices[t + 1], c = indices[t + 2];
        ASSERT_LT(std::max({a, b, c}), n);
        float e1[3], e2[3], nsum[3];
        for (int k = 0; k < 3; ++k) {
            e1[k] = pos[3 * b + k] - pos[3 * a + k];
            e2[k] = pos[3 * c + k] - pos[3 * a + k];
            nsum[k] = nrm[3 * a + k] + nrm[3 * b + k] + nrm[3 * c + k];
        }
        const float face[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                               e1[0] * e2[1] - e1[1] * e2[0]};
        EXPECT_GT(face[0] * nsum[0] + face[1] * nsum[1] + face[2] * nsum[2], 0.0f)
            << "triangle " << t / 3;
    }
}

TEST(StretchTube, SegmentOptionsChangeTheMesh) {
    ASSERT_TRUE(fs::exists(kTubeTool)) << kTubeTool << " is not built";
    ScratchDir dir;
    const std::string path = dir.file("small.gltf");
    ASSERT_EQ(run_command("'" + kTubeTool + "' '" + path +
                          "' --segments-around 8 --segments-along=4 > /dev/null"),
              0);
    tinygltf::TinyGLTF loader;
    tinygltf::Model m;
    std::string err, warn;
    ASSERT_TRUE(loader.LoadASCIIFromFile(&m, &err, &warn, path)) << err;
    const tinygltf::Primitive& prim = m.meshes.at(0).primitives.at(0);
    EXPECT_EQ(m.accessors.at(prim.attributes.at("POSITION")).count, 5u * 8 + 2 * 9);
    EXPECT_EQ(m.accessors.at(prim.indices).count, 3u * (4 * 8 * 2 + 2 * 8));
}

}  // namespace
