// Framing and orientation in the player (issue 7, item 6): the player frames the clip it
// plays, the camera works at pitch +-90, and stipple-inspect reports the up axis and the
// clip bounds the bake stored (BNDS).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "tests/common/fixtures.h"
#include "tests/common/gltf_writer.h"

namespace {

using namespace stipple;
using test::write_running_cube;

class FramingFrames : public ::testing::Test {
  protected:
    static std::string dir;
    static void SetUpTestSuite() {
        dir = test::scratch_path("framing");
        test::run("rm -rf " + dir + " && mkdir -p " + dir);
        write_running_cube(dir + "/cube.gltf");
        ASSERT_EQ(test::run(test::bin("stipple-bake") + " " + dir + "/cube.gltf -o " + dir +
                            "/cube.stip --points 4000 --quiet"),
                  0);
        const std::string cesium =
            test::baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 20000");
        ASSERT_FALSE(cesium.empty());
        ASSERT_EQ(test::run("ln -s " + cesium + " " + dir + "/cesium.stip"), 0);
    }
    static void TearDownTestSuite() { test::run("rm -rf " + dir); }

    // Renders `frames` frames of the object's mask (paper pass on grey, no dots or lines).
    static std::vector<test::Image> masks(const std::string& asset, const std::string& name,
                                          int frames, const std::string& args) {
        const std::string out = dir + "/" + name;
        std::string log;
        EXPECT_EQ(test::run(test::play_checked() + " " + dir + "/" + asset + " --out " + out +
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
