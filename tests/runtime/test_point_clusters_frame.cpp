// The level of detail's per-frame selection (runtime/point_clusters.h): the placed set is the
// run set and every relevant neighbour of it (built from the closure lists, not per point),
// and the AVX2 stretch kernel gives the scalar code's bits, so the selection is the same on
// both SIMD paths.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "runtime/frame_pipeline.h"
#include "runtime/point_clusters.h"
#include "runtime/point_simd.h"
#include "tests/common/point_frame_fixture.h"

namespace {

using stipple::PointSimd;

struct Selection {
    std::vector<uint32_t> run, placed;
    std::vector<float> area, edges;
};

Selection selection(const stipple::Pipeline& p) {
    const stipple::PointClusters& c = p.clusters;
    Selection s;
    s.run.assign(c.run.get(), c.run.get() + c.run_count);
    s.placed.assign(c.placed.get(), c.placed.get() + c.placed_count);
    const uint32_t tris = p.asset->mesh.triangle_count;
    s.area.assign(c.area_ratio.get(), c.area_ratio.get() + tris);
    s.edges.assign(c.edge_ratio.get(), c.edge_ratio.get() + tris);
    return s;
}

using stipple::test::same_bytes;

class PointClustersFrame : public stipple::test::Cesium60kFrame {};

TEST_F(PointClustersFrame, PlacedSetIsTheRunSetAndItsNeighbours) {
    stipple::FrameConfig config;
    config.width = 640;
    config.height = 480;
    auto owner = std::make_unique<stipple::Pipeline>();
    stipple::Pipeline& p = *owner;
    ASSERT_TRUE(stipple::pipeline_init(&p, asset_, gl_.gl(), config).ok());
    ASSERT_TRUE(p.asset->skinned);
    const stipple::PointsView& pts = asset_.points;
    bool some_neighbours_outside = false;
    for (int f = 0; f < 6; ++f) {
        stipple::AnimationState state;
        state.time = float(f) / 7.0f;
        stipple::pipeline_update(&p, state, nullptr);
        const stipple::PointClusters& c = p.clusters;
        ASSERT_GT(c.run_count, 1000u);
        std::vector<uint8_t> want(pts.point_count, 0);
        for (uint32_t j = 0; j < c.run_count; ++j) {
            const uint32_t i = c.run[j];
            want[i] = 1;
            for (uint32_t e = pts.neighbour_offsets[i]; e < pts.neighbour_offsets[i + 1]; ++e)
                want[pts.neighbours[e]] = 1;
        }
        std::vector<uint32_t> expected;
        for (uint32_t i = 0; i < pts.point_count; ++i)
            if (want[i]) expected.push_back(i);
        const std::vector<uint32_t> placed(c.placed.get(), c.placed.get() + c.placed_count);
        EXPECT_EQ(placed, expected) << "frame " << f;
        some_neighbours_outside |= c.placed_count > c.run_count;
        for (uint32_t j = 1; j < c.run_count; ++j) ASSERT_LT(c.run[j - 1], c.run[j]);
    }
    EXPECT_TRUE(some_neighbours_outside);
    stipple::pipeline_destroy(&p);
}

TEST_F(PointClustersFrame, SelectionIsTheSameOnBothSimdPaths) {
    if (!stipple::has_avx2(stipple::point_simd_detected()))
        GTEST_SKIP() << "this CPU has no AVX2 (or STIPPLE_SIMD=baseline): one path only";
    stipple::FrameConfig config;
    config.width = 640;
    config.height = 480;
    std::unique_ptr<stipple::Pipeline> p[2];
    for (auto& q : p) {
        q = std::make_unique<stipple::Pipeline>();
        ASSERT_TRUE(stipple::pipeline_init(q.get(), asset_, gl_.gl(), config).ok());
    }
    for (int f = 0; f < 6; ++f) {
        stipple::AnimationState state;
        state.time = float(f) / 5.0f;
        Selection s[2];
        for (int k = 0; k < 2; ++k) {
            stipple::point_simd_force(k == 0 ? PointSimd::baseline : PointSimd::avx2);
            stipple::pipeline_update(p[k].get(), state, nullptr);
            s[k] = selection(*p[k]);
        }
        EXPECT_EQ(s[0].run, s[1].run) << "frame " << f;
        EXPECT_EQ(s[0].placed, s[1].placed) << "frame " << f;
        EXPECT_TRUE(same_bytes(s[0].area, s[1].area)) << "frame " << f;
        EXPECT_TRUE(same_bytes(s[0].edges, s[1].edges)) << "frame " << f;
    }
    for (auto& q : p) stipple::pipeline_destroy(q.get());
}

// Degenerate and hostile triangles (zero edges, collinear corners, a corner at infinity, NaN)
// over a count that is not a multiple of 8: the AVX2 kernel and the scalar code agree bit for
// bit on both squared stretches.
TEST(PointClustersStretch, SimdKernelMatchesTheScalarCodeOnEdgeCases) {
    if (!stipple::has_avx2(stipple::point_simd_detected()))
        GTEST_SKIP() << "this CPU has no AVX2 (or STIPPLE_SIMD=baseline): one path only";
    const float inf = std::numeric_limits<float>::infinity();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    std::vector<float> bind = {0, 0, 0, 1, 0, 0, 0, 1, 0, 2, 0, 0, 0, 0, 0, 1, 1, 1, 3, 3, 3};
    std::vector<float> posed = {0, 0, 0, 1.5f, 0, 0, 0, 0.5f, 0, 4, 0,
                                0, 0, 0, 1,    1, 1, 1, 3,    3, 3};
    std::vector<uint32_t> indices;
    const uint32_t triangles[][3] = {{0, 1, 2}, {0, 1, 3}, {0, 4, 1}, {0, 0, 0}, {1, 2, 5},
                                     {0, 5, 6}, {2, 1, 0}, {5, 6, 0}, {3, 2, 1}, {4, 5, 6},
                                     {1, 5, 2}, {6, 2, 3}, {0, 2, 6}};
    for (const auto& t : triangles) indices.insert(indices.end(), t, t + 3);
    for (int variant = 0; variant < 3; ++variant) {
        std::vector<float> moved = posed;
        if (variant == 1) moved[5 * 3] = inf;
        if (variant == 2) moved[6 * 3 + 1] = nan;
        moved.resize(moved.size() + stipple::kSimdPadFloats);  // the kernel's 16-byte loads
        stipple::MeshView m;
        m.vertex_count = 7;
        m.triangle_count = uint32_t(indices.size() / 3);
        m.positions = bind.data();
        m.indices = indices.data();
        stipple::PointClusters c[2];
        std::vector<float> out[2][2];
        for (int k = 0; k < 2; ++k) {
            ASSERT_TRUE(stipple::alloc(&c[k].bind_gram, size_t(m.triangle_count) * 3));
            ASSERT_TRUE(stipple::alloc(&c[k].area_ratio, m.triangle_count));
            ASSERT_TRUE(stipple::alloc(&c[k].edge_ratio, m.triangle_count));
            for (uint32_t t = 0; t < m.triangle_count; ++t) {  // bind Gram entries, as at init
                const float* o = &bind[indices[t * 3] * 3];
                const float* p1 = &bind[indices[t * 3 + 1] * 3];
                const float* p2 = &bind[indices[t * 3 + 2] * 3];
                float e1[3], e2[3];
                for (int d = 0; d < 3; ++d) e1[d] = p1[d] - o[d], e2[d] = p2[d] - o[d];
                c[k].bind_gram[t * 3] = (e1[0] * e1[0] + e1[1] * e1[1]) + e1[2] * e1[2];
                c[k].bind_gram[t * 3 + 1] = (e1[0] * e2[0] + e1[1] * e2[1]) + e1[2] * e2[2];
                c[k].bind_gram[t * 3 + 2] = (e2[0] * e2[0] + e2[1] * e2[1]) + e2[2] * e2[2];
            }
            stipple::point_simd_force(k == 0 ? PointSimd::baseline : PointSimd::avx2);
            stipple::point_clusters_stretch(&c[k], m, moved.data());
            out[k][0].assign(c[k].area_ratio.get(), c[k].area_ratio.get() + m.triangle_count);
            out[k][1].assign(c[k].edge_ratio.get(), c[k].edge_ratio.get() + m.triangle_count);
        }
        stipple::point_simd_force(stipple::point_simd_detected());
        EXPECT_TRUE(same_bytes(out[0][0], out[1][0])) << "area, variant " << variant;
        EXPECT_TRUE(same_bytes(out[0][1], out[1][1])) << "edges, variant " << variant;
    }
}

// The cut searched from last frame's (partition_from) is std::partition_point's, from any hint
// and on any prefix length, including empty ranges and hints past the end.
TEST(PointClustersCut, SearchFromAHintIsThePartitionPoint) {
    std::mt19937 rng(7);
    for (int trial = 0; trial < 4000; ++trial) {
        const uint32_t n = rng() % 300;
        std::vector<float> bound(n);
        float r = 1.0f + float(rng() % 100);
        for (float& b : bound) b = r -= float(rng() % 3) * 0.01f;  // non-increasing, with ties
        const float threshold = n ? bound[rng() % n] + float(int(rng() % 3) - 1) * 0.005f : 1.0f;
        const auto pred = [&](float x) { return x > threshold; };
        const uint32_t want =
            uint32_t(std::partition_point(bound.begin(), bound.end(), pred) - bound.begin());
        const uint32_t hint = rng() % (n + 8);
        ASSERT_EQ(stipple::partition_from(bound.data(), n, hint, pred), want)
            << "n " << n << ", hint " << hint;
    }
}

}  // namespace
