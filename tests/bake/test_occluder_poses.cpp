// The occluder's deviation over the clips' poses (bake/occluder.h, bake/scene_poser.h,
// bake/triangle_grid.h): the one-sided gap query, the poser's rest pose and sample count,
// and CesiumMan's walk, where skinning swings the arms and legs against the body so the
// occluder cuts in front of the surface by more than it does in the bind pose.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "bake/occluder.h"
#include "bake/scene_import.h"
#include "bake/scene_poser.h"
#include "bake/triangle_grid.h"
#include "tests/common/bake_result.h"

namespace {

using namespace stipple;

const char* const kCesiumMan = STIPPLE_SOURCE_DIR "/assets/CesiumMan/CesiumMan.glb";

TEST(TriangleGrid, OneSidedGapIsTheDistanceOnTheAskedSideOnly) {
    // One triangle in z = 0, its winding normal +z.
    const std::vector<float> p = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const std::vector<uint32_t> tri = {0, 1, 2};
    const bake::TriangleGrid g = bake::build_triangle_grid(p.data(), tri);
    EXPECT_NEAR(bake::one_sided_gap(g, {0.2f, 0.2f, 0.3f}, 1.0f), 0.3f, 1e-6f);
    EXPECT_EQ(bake::one_sided_gap(g, {0.2f, 0.2f, 0.3f}, -1.0f), 0.0f);
    EXPECT_NEAR(bake::one_sided_gap(g, {0.2f, 0.2f, -0.25f}, -1.0f), 0.25f, 1e-6f);
    // Past an edge the distance is to the edge: (1, 1) is sqrt(0.5) from the hypotenuse's
    // midpoint, 0.1 above the plane.
    EXPECT_NEAR(bake::one_sided_gap(g, {1.0f, 1.0f, 0.1f}, 1.0f), std::sqrt(0.5f + 0.01f), 1e-5f);
    // Nothing within 6 cells: no gap.
    EXPECT_EQ(bake::one_sided_gap(g, {100.0f, 0.0f, 5.0f}, 1.0f), 0.0f);
}

TEST(ScenePoser, RestPoseFirstThenEveryClipsSamples) {
    bake::RawScene s;
    std::string error;
    ASSERT_TRUE(test::bake_ok(bake::import_scene(kCesiumMan, &s), &error)) << error;
    bake::PoseSampling sampling;
    sampling.samples_per_second = 4.0f;
    sampling.max_samples_per_clip = 6;
    int rest = 0, posed = 0;
    float rest_error = 0.0f, largest_move = 0.0f;
    bake::for_each_pose(s, sampling, [&](int clip, const float* positions) {
        float move = 0.0f;
        for (size_t i = 0; i < s.positions.size(); ++i)
            move = std::max(move, std::abs(positions[i] - s.positions[i]));
        if (clip < 0) {
            ++rest;
            rest_error = move;
        } else {
            EXPECT_EQ(clip, 0);
            ++posed;
            largest_move = std::max(largest_move, move);
        }
    });
    EXPECT_EQ(rest, 1);
    EXPECT_EQ(posed, 6);            // the walk has more key times than the cap: thinned to 6
    EXPECT_GT(rest_error, 0.0f);    // the nodes' rest pose, skinned (not the bind pose as given)
    EXPECT_GT(largest_move, 0.1f);  // the walk moves the limbs
}

TEST(OccluderBake, DeviationCoversTheClipsPosesNotOnlyTheBindPose) {
    bake::RawScene s;
    std::string error;
    ASSERT_TRUE(test::bake_ok(bake::import_scene(kCesiumMan, &s), &error)) << error;
    const bake::BakedOccluder o = bake::bake_occluder(s, 0.6);
    bake::RawScene rest_only = s;
    rest_only.clips.clear();
    const float bind = bake::occluder_deviation(rest_only, o.indices);
    EXPECT_EQ(o.deviation, bake::occluder_deviation(s, o.indices));
    // Measured: 0.0090 over the walk, several times the rest pose's alone (CesiumMan is ~1.7
    // tall).
    EXPECT_GT(o.deviation, 4.0f * bind);
    EXPECT_LT(o.deviation, 0.05f);
}

}  // namespace
