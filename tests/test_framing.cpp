// Framing and orientation (issue 7, item 6): the bake stores each clip's animated bounds and
// the input's up axis (BNDS), the player frames the clip it plays, --up z stands Z-up meshes
// upright, and the camera works at pitch +-90.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "bake/asset_writer.h"
#include "bake/scene_bounds.h"
#include "bake/scene_import.h"
#include "bake/scene_orientation.h"
#include "runtime/asset.h"
#include "runtime/asset_format.h"
#include "tests/frame_check_util.h"
#include "tests/gltf_test_util.h"

namespace {

using namespace stipple;

// A unit cube (outward faces) on node 0, whose clip "run" moves it 12 units along +x and 4
// up and back in 2 seconds: far outside the rest pose's bounds.
void write_running_cube(const std::string& path) {
    test::GltfBin bin;
    bin.put<float>({-0.5f, -0.5f, -0.5f, 0.5f, -0.5f, -0.5f, 0.5f, 0.5f, -0.5f, -0.5f, 0.5f, -0.5f,
                    -0.5f, -0.5f, 0.5f,  0.5f, -0.5f, 0.5f,  0.5f, 0.5f, 0.5f,  -0.5f, 0.5f, 0.5f});
    bin.put<uint16_t>({0, 3, 2, 0, 2, 1, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                       3, 7, 6, 3, 6, 2, 0, 4, 7, 0, 7, 3, 1, 2, 6, 1, 6, 5});
    bin.put<float>({0, 1, 2});
    bin.put<float>({0, 0, 0, 12, 4, 0, 0, 0, 0});
    test::write_gltf(path, R"({
      "asset": {"version": "2.0"},
      "scene": 0, "scenes": [{"nodes": [0]}],
      "nodes": [{"mesh": 0}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
      "animations": [{"name": "run",
        "channels": [{"sampler": 0, "target": {"node": 0, "path": "translation"}}],
        "samplers": [{"input": 2, "output": 3, "interpolation": "LINEAR"}]}],
      "buffers": [@BUFFER@],
      "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 96},
                      {"buffer": 0, "byteOffset": 96, "byteLength": 72},
                      {"buffer": 0, "byteOffset": 168, "byteLength": 12},
                      {"buffer": 0, "byteOffset": 180, "byteLength": 36}],
      "accessors": [
        {"bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3",
         "min": [-0.5, -0.5, -0.5], "max": [0.5, 0.5, 0.5]},
        {"bufferView": 1, "componentType": 5123, "count": 36, "type": "SCALAR"},
        {"bufferView": 2, "componentType": 5126, "count": 3, "type": "SCALAR",
         "min": [0], "max": [2]},
        {"bufferView": 3, "componentType": 5126, "count": 3, "type": "VEC3"}]
    })",
                     bin);
}

std::string temp(const char* name) {
    return ::testing::TempDir() + "stipple_framing_" + name;
}

TEST(Framing, ClipBoundsCoverEveryPoseOfTheClip) {
    const std::string path = temp("cube.gltf");
    write_running_cube(path);
    bake::RawScene scene;
    std::string error;
    ASSERT_TRUE(bake::import_scene(path, &scene, &error)) << error;
    ASSERT_TRUE(scene.animated());
    bake::SceneBounds b = bake::compute_scene_bounds(scene);
    const float rest[6] = {-0.5f, -0.5f, -0.5f, 0.5f, 0.5f, 0.5f};
    const float run[6] = {-0.5f, -0.5f, -0.5f, 12.5f, 4.5f, 0.5f};  // key 1: (12, 4, 0)
    ASSERT_EQ(b.clips.size(), 6u);
    for (int k = 0; k < 6; ++k) {
        EXPECT_NEAR(b.rest[k], rest[k], 1e-5) << k;
        EXPECT_NEAR(b.clips[size_t(k)], run[k], 1e-5) << k;
    }
}

TEST(Framing, UpZTurnsStaticAndAnimatedScenesUpright) {
    // Static: positions and normals turn, +Z -> +Y, +Y -> -Z.
    bake::RawScene s;
    s.positions = {0, 0, 0, 1, 0, 0, 0, 2, 3};
    s.normals = {0, 0, 1, 0, 0, 1, 0, 0, 1};
    s.indices = {0, 1, 2};
    bake::apply_up_axis(format::kUpZ, &s);
    EXPECT_EQ(s.up_axis, format::kUpZ);
    EXPECT_EQ(s.positions, (std::vector<float>{0, 0, 0, 1, 0, 0, 0, 3, -2}));
    EXPECT_EQ(s.normals, (std::vector<float>{0, 1, -0.0f, 0, 1, -0.0f, 0, 1, -0.0f}));
    // Animated: a new root turns every pose, so the clip's box turns too.
    const std::string path = temp("cube_z.gltf");
    write_running_cube(path);
    bake::RawScene scene;
    std::string error;
    ASSERT_TRUE(bake::import_scene(path, &scene, &error)) << error;
    bake::apply_up_axis(format::kUpZ, &scene);
    ASSERT_EQ(scene.nodes.size(), 2u);
    EXPECT_EQ(scene.nodes[1].parent, 0);
    EXPECT_EQ(scene.clips[0].channels[0].node, 1u);
    bake::SceneBounds b = bake::compute_scene_bounds(scene);
    const float run[6] = {-0.5f, -0.5f, -4.5f, 12.5f, 0.5f, 0.5f};  // (x, y, z) -> (x, z, -y)
    for (int k = 0; k < 6; ++k) EXPECT_NEAR(b.clips[size_t(k)], run[k], 1e-5) << k;
}

class FramingFrames : public ::testing::Test {
  protected:
    static std::string dir;
    static void SetUpTestSuite() {
        dir = ::testing::TempDir() + "stipple_framing_" + std::to_string(getpid());
        test::run("rm -rf " + dir + " && mkdir -p " + dir);
        write_running_cube(dir + "/cube.gltf");
        const std::string bake = test::bin("stipple-bake") + " ";
        ASSERT_EQ(
            test::run(bake + dir + "/cube.gltf -o " + dir + "/cube.stip --points 4000 --quiet"), 0);
        ASSERT_EQ(test::run(bake + test::source("assets/CesiumMan/CesiumMan.glb") + " -o " + dir +
                            "/cesium.stip --points 20000 --quiet"),
                  0);
    }
    static void TearDownTestSuite() { test::run("rm -rf " + dir); }

    // Renders `frames` frames of the object's mask (paper pass on grey, no dots or lines).
    static std::vector<test::Image> masks(const std::string& asset, const std::string& name,
                                          int frames, const std::string& args) {
        const std::string out = dir + "/" + name;
        std::string log;
        EXPECT_EQ(test::run(test::bin("stipple-play") + " " + dir + "/" + asset + " --out " + out +
                                " --no-apng --size 240x180 --tone 0 --no-silhouettes "
                                "--background 808080 --frames " +
                                std::to_string(frames) + " " + args,
                            &log),
                  0)
            << log;
        std::vector<test::Image> images(static_cast<size_t>(frames));
        for (int f = 0; f < frames; ++f) {
            char file[32];
            std::snprintf(file, sizeof(file), "/frame_%04d.png", f);
            EXPECT_TRUE(test::load_png(out + file, &images[size_t(f)])) << out << file;
        }
        return images;
    }

    // Object pixels in the whole image and on its one-pixel border.
    static void count(const test::Image& img, size_t* object, size_t* border) {
        std::vector<uint8_t> mask = test::silhouette(img);
        *object = *border = 0;
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x) {
                const bool on = mask[size_t(y) * size_t(img.width) + size_t(x)];
                *object += on;
                *border += on && (x == 0 || y == 0 || x == img.width - 1 || y == img.height - 1);
            }
    }
};
std::string FramingFrames::dir;

// At zoom 1 every frame of the clip shows the whole object: no object pixel on the border.
TEST_F(FramingFrames, EveryFrameOfTheClipStaysInsideTheImage) {
    struct Case {
        const char* asset;
        const char* name;
        int frames;
        const char* args;
    };
    const Case cases[] = {{"cube.stip", "cube", 21, "--fps 10 --yaw 20 --pitch 15"},
                          {"cube.stip", "cube_side", 21, "--fps 10 --yaw 90"},
                          {"cesium.stip", "cesium", 20, "--fps 10"},
                          {"cesium.stip", "cesium_side", 20, "--fps 10 --yaw -90"}};
    for (const Case& c : cases) {
        size_t least = SIZE_MAX, border_total = 0;
        for (const test::Image& img : masks(c.asset, c.name, c.frames, c.args)) {
            size_t object = 0, border = 0;
            count(img, &object, &border);
            least = std::min(least, object);
            border_total += border;
        }
        std::printf("%s: smallest object %zu px of %d, object pixels on the border %zu\n", c.name,
                    least, 240 * 180, border_total);
        EXPECT_GT(least, 100u) << c.name;
        EXPECT_EQ(border_total, 0u) << c.name;
    }
}

// Looking straight down or up (pitch +-90) the view is well defined: the object is drawn.
TEST_F(FramingFrames, PitchNinetyRendersTheObject) {
    for (const char* pitch : {"90", "-90"}) {
        for (const char* asset : {"cesium.stip", "cube.stip"}) {
            size_t object = 0, border = 0;
            count(masks(asset, std::string("pitch") + pitch + asset, 1,
                        std::string("--pitch ") + pitch)[0],
                  &object, &border);
            EXPECT_GT(object, 100u) << asset << " at pitch " << pitch;
            EXPECT_EQ(border, 0u) << asset << " at pitch " << pitch;
        }
    }
}

// stipple-inspect reports the up axis and the clip bounds; --up z is recorded.
TEST_F(FramingFrames, InspectReportsUpAxisAndClipBounds) {
    std::string log;
    ASSERT_EQ(test::run(test::bin("stipple-bake") + " " + dir + "/cube.gltf -o " + dir +
                        "/cube_z.stip --points 500 --quiet --up z"),
              0);
    ASSERT_EQ(test::run(test::bin("stipple-inspect") + " " + dir + "/cube_z.stip", &log), 0);
    EXPECT_NE(log.find("\"version\": 3"), std::string::npos) << log;
    EXPECT_NE(log.find("\"up\": \"z\""), std::string::npos) << log;
    EXPECT_NE(log.find("\"name\": \"run\", \"duration\": 2, \"box\": {\"min\": [-0.5, -0.5, -4.5], "
                       "\"max\": [12.5, 0.5, 0.5]}"),
              std::string::npos)
        << log;
    EXPECT_NE(
        test::run(test::bin("stipple-bake") + " " + dir + "/cube.gltf -o " + dir + "/x.stip --up x",
                  &log),
        0);
    EXPECT_NE(log.find("--up must be y or z"), std::string::npos) << log;
}

}  // namespace
