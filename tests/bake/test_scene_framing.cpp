// Framing and orientation in the bake (issue 7, item 6): each clip's animated bounds
// (bake/scene_bounds.h) and --up z turning scenes upright (bake/scene_orientation.h).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "bake/scene_bounds.h"
#include "bake/scene_import.h"
#include "bake/scene_orientation.h"
#include "runtime/asset_format.h"
#include "tests/common/bake_result.h"
#include "tests/common/fixtures.h"
#include "tests/common/gltf_writer.h"

namespace {

using namespace stipple;
using test::write_running_cube;

std::string temp(const char* name) {
    return test::scratch_path(std::string("framing_") + name);
}

TEST(Framing, ClipBoundsCoverEveryPoseOfTheClip) {
    const std::string path = temp("cube.gltf");
    write_running_cube(path);
    bake::RawScene scene;
    std::string error;
    ASSERT_TRUE(stipple::test::bake_ok(bake::import_scene(path, &scene), &error)) << error;
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
    ASSERT_TRUE(stipple::test::bake_ok(bake::import_scene(path, &scene), &error)) << error;
    bake::apply_up_axis(format::kUpZ, &scene);
    ASSERT_EQ(scene.nodes.size(), 2u);
    EXPECT_EQ(scene.nodes[1].parent, 0);
    EXPECT_EQ(scene.clips[0].channels[0].node, 1u);
    bake::SceneBounds b = bake::compute_scene_bounds(scene);
    const float run[6] = {-0.5f, -0.5f, -4.5f, 12.5f, 0.5f, 0.5f};  // (x, y, z) -> (x, z, -y)
    for (int k = 0; k < 6; ++k) EXPECT_NEAR(b.clips[size_t(k)], run[k], 1e-5) << k;
}

}  // namespace
