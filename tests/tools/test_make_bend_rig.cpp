// stipple-make-bend-rig (tools/make_bend_rig.cpp, tools/bend_rig.h): a static mesh rigged with
// a chain along its longest axis, every vertex weighted linearly between two neighbouring
// joints, one seamless looping clip; the result bakes and plays, and the clip moves the dots.
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "tests/common/fixtures.h"

namespace {

using stipple::test::ScratchDir;

const std::string kTool = std::string(STIPPLE_BIN_DIR) + "/stipple-make-bend-rig";

template <typename T>
std::vector<T> read_accessor(const tinygltf::Model& m, int index, int components) {
    const tinygltf::Accessor& a = m.accessors.at(size_t(index));
    const tinygltf::BufferView& v = m.bufferViews.at(size_t(a.bufferView));
    const std::vector<unsigned char>& data = m.buffers.at(size_t(v.buffer)).data;
    std::vector<T> out(a.count * size_t(components));
    std::memcpy(out.data(), &data.at(v.byteOffset + a.byteOffset), out.size() * sizeof(T));
    return out;
}

TEST(MakeBendRig, ChainWeightsAndLoopingClip) {
    ScratchDir dir;
    const std::string out = dir.file("teapot.gltf");
    ASSERT_EQ(
        stipple::test::run(kTool + " " + stipple::test::source("assets/UtahTeapot/teapot.obj") +
                           " " + out + " --bones 5"),
        0);
    tinygltf::TinyGLTF loader;
    tinygltf::Model m;
    std::string err, warn;
    ASSERT_TRUE(loader.LoadASCIIFromFile(&m, &err, &warn, out)) << err;
    ASSERT_EQ(m.skins.size(), 1u);
    ASSERT_EQ(m.skins[0].joints.size(), 5u);
    const tinygltf::Primitive& prim = m.meshes.at(0).primitives.at(0);
    const auto joints = read_accessor<uint8_t>(m, prim.attributes.at("JOINTS_0"), 4);
    const auto weights = read_accessor<float>(m, prim.attributes.at("WEIGHTS_0"), 4);
    ASSERT_EQ(joints.size(), weights.size());
    bool used[5] = {};
    for (size_t v = 0; v < weights.size() / 4; ++v) {
        const float* w = &weights[v * 4];
        const uint8_t* j = &joints[v * 4];
        EXPECT_NEAR(w[0] + w[1] + w[2] + w[3], 1.0f, 1e-5f);
        EXPECT_EQ(w[2] + w[3], 0.0f);  // two influences at most
        EXPECT_EQ(j[1], j[0] + 1);     // neighbouring joints of the chain
        EXPECT_LT(j[1], 5);
        used[j[0]] = used[j[0]] || w[0] > 0.5f;
        used[j[1]] = used[j[1]] || w[1] > 0.5f;
    }
    for (bool u : used) EXPECT_TRUE(u);  // every joint carries part of the mesh
    ASSERT_EQ(m.animations.size(), 1u);
    const tinygltf::Animation& clip = m.animations[0];
    EXPECT_EQ(clip.name, "bend");
    ASSERT_EQ(clip.channels.size(), 5u);
    for (const tinygltf::AnimationChannel& c : clip.channels) {
        EXPECT_EQ(c.target_path, "rotation");
        const auto q = read_accessor<float>(m, clip.samplers.at(size_t(c.sampler)).output, 4);
        const size_t last = q.size() - 4;
        for (int k = 0; k < 4; ++k) EXPECT_EQ(q[size_t(k)], q[last + size_t(k)]);  // no seam
    }
}

// Bakes the rigged file and plays two frames of the clip: both play, and the dots move.
TEST(MakeBendRig, BakesAndPlaysAMovingClip) {
    ScratchDir dir;
    const std::string gltf = dir.file("horse.gltf"), stip = dir.file("horse.stip");
    ASSERT_EQ(stipple::test::run(kTool + " " + stipple::test::source("assets/Horse/horse.ply") +
                                 " " + gltf + " --up z"),
              0);
    ASSERT_EQ(stipple::test::run(stipple::test::bin("stipple-bake") + " " + gltf + " -o " + stip +
                                 " --points 4000 --quiet"),
              0);
    ASSERT_EQ(stipple::test::run(stipple::test::play_checked() + " " + stip + " --out " +
                                 dir.path() + " --clip bend --frames 2 --fps 4 --size 320x240 " +
                                 "--dots-out --no-png --no-apng"),
              0);
    const auto a = stipple::test::load_dots(dir.file("dots_0000.csv"));
    const auto b = stipple::test::load_dots(dir.file("dots_0001.csv"));
    ASSERT_GT(a.size(), 20u);
    ASSERT_GT(b.size(), 20u);
    double moved = 0;
    size_t common = 0;
    for (const auto& p : a)
        for (const auto& q : b)
            if (p.id == q.id) {
                moved += std::hypot(p.x - q.x, p.y - q.y);
                ++common;
            }
    ASSERT_GT(common, 0u);
    EXPECT_GT(moved / double(common), 0.5);  // a quarter period apart: pixels, not rounding
}

TEST(MakeBendRig, RefusesBadInput) {
    ScratchDir dir;
    EXPECT_NE(stipple::test::run(kTool + " " + dir.file("missing.ply") + " " + dir.file("o.gltf")),
              0);
    EXPECT_NE(stipple::test::run(kTool + " " + stipple::test::source("assets/Horse/horse.ply") +
                                 " " + dir.file("o.gltf") + " --bones 1"),
              0);
    EXPECT_NE(
        stipple::test::run(kTool + " " + stipple::test::source("assets/CesiumMan/CesiumMan.glb") +
                           " " + dir.file("o.gltf")),
        0);  // already skinned
}

}  // namespace
