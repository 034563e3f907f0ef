// Unit tests of runtime/point_placement.h: barycentric placement (Alg. 6.3) and the
// relevance recompute (Alg. 6.4).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "runtime/point_placement.h"

namespace {

using stipple::PointsView;

// Two triangles of a unit quad in the z=0 plane.
const float kQuad[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
const float kUp[] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
const uint32_t kQuadIndices[] = {0, 1, 2, 0, 2, 3};

TEST(PointPlacement, BarycentricPointFollowsItsHostTriangle) {
    const uint32_t host[] = {0, 1};
    const float u[] = {0.2f, 1.0f}, v[] = {0.3f, 0.0f}, r[] = {1, 1};
    const uint32_t offsets[] = {0, 0, 0};
    PointsView pv;
    pv.point_count = 2;
    pv.host_triangle = host;
    pv.bary_u = u;
    pv.bary_v = v;
    pv.radius = r;
    pv.neighbour_offsets = offsets;
    float pos[6], nrm[6];
    stipple::place_points(pv, kQuadIndices, kQuad, kUp, pos, nrm);
    // Point 0: 0.2*(0,0,0) + 0.3*(1,0,0) + 0.5*(1,1,0) = (0.8, 0.5, 0).
    EXPECT_FLOAT_EQ(pos[0], 0.8f);
    EXPECT_FLOAT_EQ(pos[1], 0.5f);
    EXPECT_FLOAT_EQ(pos[2], 0.0f);
    // Point 1 sits on vertex 0 of triangle 1.
    EXPECT_FLOAT_EQ(pos[3], 0.0f);
    EXPECT_FLOAT_EQ(pos[4], 0.0f);
    EXPECT_FLOAT_EQ(nrm[2], 1.0f);

    // Deform: stretch the quad to twice its width; the point moves with it.
    float stretched[12];
    for (int i = 0; i < 12; ++i) stretched[i] = kQuad[i] * (i % 3 == 0 ? 2.0f : 1.0f);
    stipple::place_points(pv, kQuadIndices, stretched, kUp, pos, nrm);
    EXPECT_FLOAT_EQ(pos[0], 1.6f);
    EXPECT_FLOAT_EQ(pos[1], 0.5f);
}

TEST(Relevance, RegionFollowsTheAreaAroundThePoint) {
    // Point 0 at the origin with neighbours at (1,0,0), (0,3,0) and (-1,0,0).
    const float positions[] = {0, 0, 0, 1, 0, 0, 0, 3, 0, -1, 0, 0};
    const uint32_t offsets[] = {0, 3, 3, 3, 3};
    const uint32_t neighbours[] = {1, 2, 3};
    const float fallback[] = {9, 7, 5, 3};
    float baked[4] = {2, 0, 0, 0};
    PointsView pv;
    pv.point_count = 4;
    pv.neighbour_offsets = offsets;
    pv.neighbours = neighbours;
    pv.radius = baked;
    float scale[4], radius[4];
    stipple::relevance_scale(pv, positions, scale);
    EXPECT_FLOAT_EQ(scale[1], 0.0f);  // no neighbours
    stipple::recompute_relevance(pv, positions, scale, fallback, radius);
    EXPECT_FLOAT_EQ(radius[0], 2.0f);  // the bind pose gives back the baked radius
    EXPECT_FLOAT_EQ(radius[1], 7.0f);  // no neighbours: keeps its fallback
    // Stretch x by 4: the area around point 0 grows 4x, so its region (radius^2) does too.
    const float stretched[] = {0, 0, 0, 4, 0, 0, 0, 3, 0, -4, 0, 0};
    stipple::recompute_relevance(pv, stretched, scale, fallback, radius);
    EXPECT_NEAR(radius[0] * radius[0], 4.0f * 4.0f, 1e-4f);
    // Stretch x by 2 and squash y by 2: area unchanged, radius unchanged (the mean distance of
    // Alg. 6.4 as printed would grow by 1.25x here).
    const float sheared[] = {0, 0, 0, 2, 0, 0, 0, 1.5f, 0, -2, 0, 0};
    stipple::recompute_relevance(pv, sheared, scale, fallback, radius);
    EXPECT_NEAR(radius[0], 2.0f, 1e-5f);
    // Rotating the whole neighbourhood changes nothing.
    const float turned[] = {0, 0, 0, 0, 1, 0, 0, 0, 3, 0, -1, 0};
    stipple::recompute_relevance(pv, turned, scale, fallback, radius);
    EXPECT_NEAR(radius[0], 2.0f, 1e-5f);
}

TEST(Relevance, CollinearNeighboursUseTheMeanDistance) {
    // Neighbours on a line span no area: the mean distance (Alg. 6.4) measures the spacing.
    const float positions[] = {0, 0, 0, 1, 0, 0, -3, 0, 0};
    const uint32_t offsets[] = {0, 2, 2, 2};
    const uint32_t neighbours[] = {1, 2};
    const float fallback[] = {9, 7, 5};
    float baked[3] = {3, 0, 0};
    PointsView pv;
    pv.point_count = 3;
    pv.neighbour_offsets = offsets;
    pv.neighbours = neighbours;
    pv.radius = baked;
    float scale[3], radius[3];
    stipple::relevance_scale(pv, positions, scale);
    EXPECT_FLOAT_EQ(scale[0], -1.5f);  // baked 3 over mean distance 2, marked by the sign
    const float stretched[] = {0, 0, 0, 2, 0, 0, -6, 0, 0};
    stipple::recompute_relevance(pv, stretched, scale, fallback, radius);
    EXPECT_FLOAT_EQ(radius[0], 6.0f);
}

}  // namespace
