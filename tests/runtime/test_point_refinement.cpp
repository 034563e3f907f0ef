// Unit tests of the run-time refinement (runtime/point_refinement.h): where the extra points
// lie, how many a frame asks for, how they follow stretching, culling and the budget.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <vector>

#include "runtime/point_refinement.h"
#include "runtime/refinement_order.h"
#include "tests/common/refined_points_buffer.h"

namespace {

using namespace stipple;

// Nearest-neighbour distances of 2D points (brute force; the tests use a few thousand).
std::vector<float> nearest(const std::vector<glm::vec2>& p) {
    std::vector<float> d(p.size(), 1e30f);
    for (size_t i = 0; i < p.size(); ++i)
        for (size_t j = 0; j < p.size(); ++j)
            if (i != j) d[i] = std::min(d[i], glm::length(p[i] - p[j]));
    return d;
}

float cv(const std::vector<float>& d) {
    double mean = 0, var = 0;
    for (float x : d) mean += x;
    mean /= double(d.size());
    for (float x : d) var += (x - mean) * (x - mean);
    return float(std::sqrt(var / double(d.size())) / mean);
}

// A square of side `side` in the z = 0 plane as two triangles, normals +Z.
struct Square {
    std::vector<float> positions, normals;
    std::vector<uint32_t> indices = {0, 1, 2, 0, 2, 3};
    explicit Square(float side, float x0 = 0.0f) {
        positions = {x0, 0, 0, x0 + side, 0, 0, x0 + side, side, 0, x0, side, 0};
        normals = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    }
    // The unit square centred on the origin.
    static Square centred() {
        Square sq(1.0f, -0.5f);
        sq.positions[1] = sq.positions[4] = -0.5f;
        sq.positions[7] = sq.positions[10] = 0.5f;
        return sq;
    }
    MeshView view() const {
        MeshView m;
        m.vertex_count = uint32_t(positions.size() / 3);
        m.triangle_count = uint32_t(indices.size() / 3);
        m.positions = positions.data();
        m.normals = normals.data();
        m.indices = indices.data();
        return m;
    }
};

// Camera on +Z looking at (cx, cy, 0) from `distance`, 90-degree vertical field of view.
SizeParams camera(float cx, float cy, float distance, float tone) {
    SizeParams s;
    s.eye = glm::vec3(cx, cy, distance);
    const glm::mat4 view = glm::lookAt(s.eye, glm::vec3(cx, cy, 0), glm::vec3(0, 1, 0));
    s.view_projection =
        glm::perspective(glm::radians(90.0f), 1.0f, 0.01f * distance, 10.0f * distance) * view;
    s.viewport_height = 512.0f;
    s.constant_tone = tone;
    return s;
}

using Extra = stipple::test::RefinedPointsBuffer;

PointsView no_points() {
    static const uint32_t offsets[1] = {0};
    PointsView p;
    p.neighbour_offsets = offsets;
    return p;
}

TEST(PointRefinement, SequenceStaysInsideItsTriangleAndIsEvenAtEveryPrefix) {
    // Equilateral triangle of side 1 in its isometric frame: B = (1, 0), C = (0.5, 0.866).
    const float frame[3] = {1.0f, 0.5f, 0.8660254f};
    const glm::vec2 B(1, 0), C(0.5f, 0.8660254f);
    std::vector<glm::vec2> points;
    for (uint32_t k = 0; k < 6000; ++k) {
        const glm::vec2 b = refinement_barycentric(frame, 0, 0, k);
        ASSERT_GE(b.x, -1e-6f);
        ASSERT_GE(b.y, -1e-6f);
        ASSERT_LE(b.x + b.y, 1.0f + 1e-6f);
        points.push_back(b.y * B + (1.0f - b.x - b.y) * C);
        EXPECT_EQ(b, refinement_barycentric(frame, 0, 0, k));  // deterministic
        const uint32_t n = k + 1;
        const uint32_t p = pattern_points();
        if (n == 16 || n == 64 || n == 256 || n == p / 2 || n == p || n == 6000) {
            const std::vector<float> d = nearest(points);
            const float spacing = std::sqrt(0.4330127f / float(n));  // sqrt(area / n)
            const float closest = *std::min_element(d.begin(), d.end());
            std::printf("prefix %u: NN cv %.3f, min NN / spacing %.3f\n", n, cv(d),
                        closest / spacing);
            // Within the pattern every prefix is even; past it the four sub-cells continue the
            // pattern without knowing the parent's points exactly, which costs evenness (a
            // known limit, docs/tone.md) but never duplicates a point.
            EXPECT_LT(cv(d), n <= p ? 0.2f : 0.5f) << n;
            EXPECT_GT(closest, (n <= p ? 0.5f : 0.01f) * spacing) << n;
        }
    }
}

TEST(PointRefinement, SliversAreSplitAlongTheirLength) {
    // A 20:1 sliver: the first points spread along it instead of bunching in the middle.
    const float frame[3] = {20.0f, 10.0f, 1.0f};
    const glm::vec2 B(20, 0), C(10, 1);
    float lo = 1e9f, hi = -1e9f;
    for (uint32_t k = 0; k < 8; ++k) {
        const glm::vec2 b = refinement_barycentric(frame, 4, 0, k);
        const glm::vec2 p = b.y * B + (1.0f - b.x - b.y) * C;
        lo = std::min(lo, p.x);
        hi = std::max(hi, p.x);
    }
    EXPECT_GT(hi - lo, 12.0f);
    Square sq(1.0f);
    std::vector<float> sliver = {0, 0, 0, 20, 0, 0, 10, 1, 0};
    std::vector<uint32_t> tri = {0, 1, 2};
    MeshView m = sq.view();
    m.positions = sliver.data();
    m.vertex_count = 3;
    m.triangle_count = 1;
    m.indices = tri.data();
    RefinementMesh r;
    ASSERT_TRUE(refinement_init(&r, m, no_points(), nullptr).ok());
    EXPECT_GE(r.root_depth[0], 3);
    ASSERT_TRUE(refinement_init(&r, sq.view(), no_points(), nullptr).ok());
    EXPECT_EQ(r.root_depth[0], 0);  // a right isosceles half-square is no sliver
}

TEST(PointRefinement, CountFollowsTheDensityTheSizeRuleAsksFor) {
    // A 1x1 square seen straight on from distance 1 with a 90-degree view: 256 px per unit at
    // the centre. Tone 0.3 asks for ink / dot area of the drawn density (per unit^2 of surface
    // times pixels^2 per unit^2); the number of extra points generated is at most that density
    // over the area, and not much less (corners bound the density from above).
    const Square sq = Square::centred();
    RefinementMesh r;
    ASSERT_TRUE(refinement_init(&r, sq.view(), no_points(), nullptr).ok());
    EXPECT_EQ(r.finest_density, 0.0f);
    SizeParams s = camera(0, 0, 1.0f, 0.3f);
    Extra e(1 << 20);
    RefinementStats stats;
    refine_points(&r, sq.view(), sq.positions.data(), sq.normals.data(), nullptr, s, true, &e.out,
                  &stats);
    const float dot_area = 0.785398f * 9.0f;
    const float centre_density = ink_for_tone(s, 0.3f) * 256.0f * 256.0f / dot_area;
    std::printf("extra points %u, centre density %.0f\n", e.out.count, centre_density);
    EXPECT_GT(float(e.out.count), 0.8f * centre_density);
    EXPECT_LT(float(e.out.count), 1.3f * centre_density);
    EXPECT_EQ(stats.budget_scale, 1.0f);
    // Every point lies in the square, on the plane, with the plane's normal, and its region
    // follows the A / i law of its triangle: region = area / (k + phase).
    for (uint32_t i = 0; i < e.out.count; ++i) {
        ASSERT_LE(std::fabs(e.positions[i * 3]), 0.5f + 1e-5f);
        ASSERT_LE(std::fabs(e.positions[i * 3 + 1]), 0.5f + 1e-5f);
        ASSERT_EQ(e.positions[i * 3 + 2], 0.0f);
        ASSERT_FLOAT_EQ(e.normals[i * 3 + 2], 1.0f);
        const uint32_t t = e.triangle[i], k = e.index[i];
        ASSERT_LT(t, 2u);
        const float region = 0.5f / (float(k) + r.phase[t]);
        ASSERT_NEAR(e.radius[i] * e.radius[i] * kRegionPerRadiusSquared, region, 1e-4f * region);
    }
    // Twice as far away: a quarter of the points.
    Extra far(1 << 20);
    refine_points(&r, sq.view(), sq.positions.data(), sq.normals.data(), nullptr,
                  camera(0, 0, 2.0f, 0.3f), true, &far.out, nullptr);
    EXPECT_NEAR(float(far.out.count) / float(e.out.count), 0.25f, 0.05f);
}

TEST(PointRefinement, StretchingGrowsTheRegionsAndTheCount) {
    Square sq(1.0f);
    RefinementMesh r;
    ASSERT_TRUE(refinement_init(&r, sq.view(), no_points(), nullptr).ok());
    std::vector<float> stretched = sq.positions;
    for (size_t i = 0; i < stretched.size(); i += 3) stretched[i] *= 2.0f;  // 2x along x
    const SizeParams s = camera(1.0f, 0.5f, 2.0f, 0.3f);
    Extra a(1 << 20), b(1 << 20);
    refine_points(&r, sq.view(), stretched.data(), sq.normals.data(), nullptr, s, false, &a.out,
                  nullptr);
    refine_points(&r, sq.view(), stretched.data(), sq.normals.data(), nullptr, s, true, &b.out,
                  nullptr);
    // Without stretch the bind-pose regions are kept; with it every region doubles, so the
    // size rule draws twice as many points of each triangle's sequence.
    EXPECT_NEAR(float(b.out.count) / float(a.out.count), 2.0f, 0.1f);
    for (uint32_t i = 0; i < std::min(a.out.count, b.out.count); ++i) {
        if (a.triangle[i] != b.triangle[i] || a.index[i] != b.index[i]) continue;
        ASSERT_NEAR(b.radius[i] * b.radius[i], 2.0f * a.radius[i] * a.radius[i],
                    1e-4f * b.radius[i]);
    }
}

TEST(PointRefinement, BakedPointsComeFirstThenHandOver) {
    // 2,000 baked points on the unit square. Seen from distance 2 the size rule wants ~1,200
    // points: the bake suffices, no extra point, baked points at full size. From distance 0.7
    // it wants ~9,000, over twice the bake everywhere: the sequence has taken over (baked
    // points faded to nothing, as many extra points as without a bake).
    const Square sq = Square::centred();
    const uint32_t n = 2000;
    std::vector<uint32_t> host(n), offsets(n + 1, 0);
    std::vector<float> u(n), v(n), radius(n, 0.01f), bind(size_t(n) * 3);
    for (uint32_t i = 0; i < n; ++i) {
        host[i] = i % 2;
        u[i] = v[i] = 1.0f / 3.0f;
        const uint32_t* tri = sq.indices.data() + host[i] * 3;
        for (int d = 0; d < 3; ++d)
            bind[i * 3 + d] = (sq.positions[tri[0] * 3 + d] + sq.positions[tri[1] * 3 + d] +
                               sq.positions[tri[2] * 3 + d]) /
                              3.0f;
    }
    PointsView pv;
    pv.point_count = n;
    pv.host_triangle = host.data();
    pv.bary_u = u.data();
    pv.bary_v = v.data();
    pv.radius = radius.data();
    pv.neighbour_offsets = offsets.data();
    RefinementMesh baked, none;
    ASSERT_TRUE(refinement_init(&baked, sq.view(), pv, bind.data()).ok());
    ASSERT_TRUE(refinement_init(&none, sq.view(), no_points(), nullptr).ok());
    EXPECT_NEAR(baked.finest_density, 2000.0f, 1.0f);
    std::vector<float> size(n);
    Extra far(1 << 20);
    refine_points(&baked, sq.view(), sq.positions.data(), sq.normals.data(), nullptr,
                  camera(0, 0, 2.0f, 0.3f), true, &far.out, nullptr);
    EXPECT_EQ(far.out.count, 0u);
    std::fill(size.begin(), size.end(), 2.0f);
    fade_baked_points(baked, pv, size.data());
    EXPECT_EQ(size[0], 2.0f);
    EXPECT_EQ(size[1], 2.0f);
    Extra near(1 << 20), alone(1 << 20);
    const SizeParams s = camera(0, 0, 0.7f, 0.3f);
    refine_points(&baked, sq.view(), sq.positions.data(), sq.normals.data(), nullptr, s, true,
                  &near.out, nullptr);
    refine_points(&none, sq.view(), sq.positions.data(), sq.normals.data(), nullptr, s, true,
                  &alone.out, nullptr);
    std::printf("extra points with 2000 baked / without: %u / %u\n", near.out.count,
                alone.out.count);
    EXPECT_EQ(near.out.count, alone.out.count);
    fade_baked_points(baked, pv, size.data());
    EXPECT_EQ(size[0], 0.0f);
    EXPECT_EQ(size[1], 0.0f);
}

TEST(PointRefinement, OnlyWhatTheViewShowsAndTheBudgetHolds) {
    const Square sq = Square::centred();
    RefinementMesh r;
    ASSERT_TRUE(refinement_init(&r, sq.view(), no_points(), nullptr).ok());
    Extra whole(1 << 20), half(1 << 20), away(1 << 20);
    refine_points(&r, sq.view(), sq.positions.data(), sq.normals.data(), nullptr,
                  camera(0, 0, 0.25f, 0.3f), true, &whole.out, nullptr);
    // Looking at the square's right edge: the left half is outside the view.
    refine_points(&r, sq.view(), sq.positions.data(), sq.normals.data(), nullptr,
                  camera(0.5f, 0.0f, 0.25f, 0.3f), true, &half.out, nullptr);
    // Looking somewhere else entirely.
    refine_points(&r, sq.view(), sq.positions.data(), sq.normals.data(), nullptr,
                  camera(5.0f, 0.0f, 0.25f, 0.3f), true, &away.out, nullptr);
    std::printf("close-up extra points: whole %u, right edge %u, away %u\n", whole.out.count,
                half.out.count, away.out.count);
    EXPECT_EQ(away.out.count, 0u);
    EXPECT_LT(half.out.count, whole.out.count);
    // Seen from behind (normals away from the eye) nothing is generated.
    SizeParams behind = camera(0, 0, 1.0f, 0.3f);
    behind.eye.z = -1.0f;
    behind.view_projection = glm::perspective(glm::radians(90.0f), 1.0f, 0.01f, 10.0f) *
                             glm::lookAt(behind.eye, glm::vec3(0), glm::vec3(0, 1, 0));
    Extra back(1 << 20);
    refine_points(&r, sq.view(), sq.positions.data(), sq.normals.data(), nullptr, behind, true,
                  &back.out, nullptr);
    EXPECT_EQ(back.out.count, 0u);
    // Unless the square is double-sided: then the back draws like the front, normals turned.
    const uint8_t both[2] = {1, 1};
    Extra back2(1 << 20), front(1 << 20);
    refine_points(&r, sq.view(), sq.positions.data(), sq.normals.data(), both, behind, true,
                  &back2.out, nullptr);
    refine_points(&r, sq.view(), sq.positions.data(), sq.normals.data(), both,
                  camera(0, 0, 1.0f, 0.3f), true, &front.out, nullptr);
    EXPECT_EQ(back2.out.count, front.out.count);
    ASSERT_GT(back2.out.count, 0u);
    EXPECT_FLOAT_EQ(back2.normals[2], -1.0f);
    EXPECT_FLOAT_EQ(front.normals[2], 1.0f);
    // A budget of a tenth: the frame fits, every triangle keeps its lowest ranks.
    const uint32_t budget = whole.out.count / 10;
    Extra small(budget);
    RefinementStats stats;
    refine_points(&r, sq.view(), sq.positions.data(), sq.normals.data(), nullptr,
                  camera(0, 0, 0.25f, 0.3f), true, &small.out, &stats);
    EXPECT_LE(small.out.count, budget);
    EXPECT_GT(small.out.count, budget * 8 / 10);
    EXPECT_LT(stats.budget_scale, 0.11f);
    EXPECT_EQ(stats.wanted, whole.out.count);
    uint32_t max_rank = 0;
    for (uint32_t i = 0; i < small.out.count; ++i) max_rank = std::max(max_rank, small.index[i]);
    // Ranks stay coarse: the view shows a quarter of the square, so the budget's points are
    // every rank up to about 2 x budget of each of the two triangles, where visible.
    EXPECT_LT(max_rank, budget * 5 / 2);
}

}  // namespace
