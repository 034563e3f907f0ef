// The per-point cull fused with relevance and size (runtime/point_cull.h) and the selection
// over the thread pool (runtime/point_clusters_select.cpp):
//  - on random views, tones, lights and poses, the frame's sizes and drawn dots are the bytes
//    of the stages without the cull, and the cull skips a real share of the run points;
//  - the scalar and AVX2 passes keep the same points and write the same bits, with and without
//    the (opt-in) radius bound, also on hostile inputs (NaN normals, infinite stretch factors,
//    forced points);
//  - the selection on 2 and 3 threads is the one on 1.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "runtime/frame_pipeline.h"
#include "runtime/point_cull.h"
#include "runtime/point_simd.h"
#include "runtime/point_stages.h"
#include "tests/common/fixtures.h"

namespace {

using stipple::Pipeline;

bool same_floats(const float* a, const float* b, size_t n) {
    return n == 0 || std::memcmp(a, b, n * 4) == 0;  // (empty vectors' data() may be null)
}

class PointCull : public ::testing::Test {
  protected:
    void SetUp() override {
        std::string error;
        ASSERT_TRUE(stipple::test::load_baked(
            stipple::test::baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 60000"), &asset_,
            &error))
            << error;
        ASSERT_TRUE(gl_.open(&error)) << error;
    }
    void TearDown() override {
        stipple::point_simd_force(stipple::point_simd_detected());
        stipple::point_cull_set_mode(stipple::PointCullMode::off);  // the default
    }

    std::unique_ptr<Pipeline> make(const stipple::FrameConfig& config) {
        auto p = std::make_unique<Pipeline>();
        const stipple::Status st = stipple::pipeline_init(p.get(), asset_, gl_.gl(), config);
        EXPECT_TRUE(st.ok()) << st.message;
        return st.ok() ? std::move(p) : nullptr;
    }

    stipple::Asset asset_;
    stipple::test::HeadlessGl gl_;
};

// A random view: yaw, pitch, zoom 0.3 .. 6, lighting or a constant tone, 1-2 lights, ambient,
// relevance updates on or off; no run-time refinement (its fade rescales baked sizes).
stipple::FrameConfig random_config(std::mt19937* rng) {
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    stipple::FrameConfig c;
    c.width = 640;
    c.height = 480;
    c.yaw_degrees = 360.0f * u(*rng);
    c.pitch_degrees = -60.0f + 120.0f * u(*rng);
    c.zoom = 0.3f * std::pow(20.0f, u(*rng));
    c.constant_tone = u(*rng) < 0.3f ? 0.05f + 0.9f * u(*rng) : stipple::kLightingTone;
    c.light_count = 1 + int(u(*rng) < 0.5f);
    for (int l = 0; l < c.light_count; ++l) {
        c.lights[l].direction[0] = 2.0f * u(*rng) - 1.0f;
        c.lights[l].direction[1] = 2.0f * u(*rng) - 1.0f;
        c.lights[l].direction[2] = 2.0f * u(*rng) - 1.0f;
        c.lights[l].intensity = 0.3f + u(*rng);
        c.lights[l].camera_space = u(*rng) < 0.5f;
    }
    c.ambient = 0.2f * u(*rng);
    c.relevance_update = u(*rng) < 0.8f;
    c.refinement_budget = 0;
    return c;
}

// Every dot of the last update the renderer would keep (centre inside the image and the depth
// range): index, screen position and size. The level of detail skips the rest.
std::vector<float> drawable_dots(const Pipeline& p) {
    std::vector<float> out;
    for (uint32_t i = 0; i < p.asset->points.point_count; ++i) {
        if (!(p.size[i] > 0.0f)) continue;
        const glm::vec3 s = stipple::pipeline_project(p, i);
        if (s.x >= 0.0f && s.y >= 0.0f && s.x < float(p.config.width) &&
            s.y < float(p.config.height) && s.z >= 0.0f && s.z <= 1.0f)
            out.insert(out.end(), {float(i), s.x, s.y, p.size[i]});
    }
    return out;
}

// The level of detail with each per-point cull mode (none, the default; the facing list, then
// the separate relevance and size kernels; the fused pass) draws the dots of the full stages,
// which run every point through relevance and size without the level of detail: the same
// points at the same places with the same sizes bit for bit.
TEST_F(PointCull, SizesAndDotsAreThoseWithoutTheCullOnRandomCases) {
    std::mt19937 rng(1234);
    uint64_t run_total = 0, sized_total = 0, drawn_total = 0;
    for (int trial = 0; trial < 12; ++trial) {
        const stipple::FrameConfig config = random_config(&rng);
        stipple::FrameConfig every = config;
        every.lod = false;
        std::unique_ptr<Pipeline> p = make(config), full = make(every);
        ASSERT_TRUE(p && full);
        for (int f = 0; f < 3; ++f) {
            stipple::AnimationState state;
            state.time = std::uniform_real_distribution<float>(0.0f, 2.0f)(rng);
            stipple::pipeline_update(full.get(), state, nullptr);
            const std::vector<float> dots = drawable_dots(*full);
            for (stipple::PointCullMode mode :
                 {stipple::PointCullMode::off, stipple::PointCullMode::fused,
                  stipple::PointCullMode::facing}) {  // a culling mode last: the stats below
                const std::string what = "trial " + std::to_string(trial) + ", frame " +
                                         std::to_string(f) + ", mode " + std::to_string(int(mode));
                stipple::point_cull_set_mode(mode);
                stipple::pipeline_update(p.get(), state, nullptr);
                const std::vector<float> lod = drawable_dots(*p);
                ASSERT_EQ(lod.size(), dots.size()) << what;
                EXPECT_TRUE(same_floats(lod.data(), dots.data(), dots.size())) << what;
                EXPECT_LE(p->clusters.stats.points_sized, p->clusters.run_count);
                EXPECT_GE(p->clusters.stats.points_sized, p->points_drawn);
            }
            run_total += p->clusters.run_count;
            sized_total += p->clusters.stats.points_sized;
            drawn_total += dots.size() / 4;
        }
        stipple::pipeline_destroy(p.get());
        stipple::pipeline_destroy(full.get());
    }
    EXPECT_GT(drawn_total, 1000u);
    // The cull does its job: fewer points get relevance and size than the cut runs (the
    // points facing away; runtime/point_cull.h).
    EXPECT_LT(sized_total * 10, run_total * 8) << sized_total << " of " << run_total;
}

// The scalar and AVX2 passes over the same inputs, with hostile ones mixed in: the same
// points kept, the same radius and size bits.
TEST_F(PointCull, SimdPassMatchesTheScalarPass) {
    if (stipple::point_simd_detected() != stipple::PointSimd::avx2)
        GTEST_SKIP() << "this CPU has no AVX2 (or STIPPLE_SIMD=baseline): one path only";
    stipple::FrameConfig config;
    config.width = 640;
    config.height = 480;
    config.refinement_budget = 0;
    std::unique_ptr<Pipeline> p = make(config);
    ASSERT_TRUE(p);
    stipple::AnimationState state;
    state.time = 0.4f;
    stipple::pipeline_update(p.get(), state, nullptr);
    const uint32_t n = asset_.points.point_count;
    const stipple::PointClusters& c = p->clusters;
    ASSERT_GT(c.run_count, 1000u);
    std::vector<uint32_t> list(c.run.get(), c.run.get() + c.run_count);
    std::vector<float> normals(p->point_normals.get(), p->point_normals.get() + size_t(n) * 3);
    for (uint32_t j = 5; j < list.size(); j += 41)
        normals[size_t(list[j]) * 3] = std::numeric_limits<float>::quiet_NaN();
    std::vector<float> factor(c.cluster_factor.get(),
                              c.cluster_factor.get() + size_t(c.cluster_count) * 2);
    for (uint32_t k = 3; k < c.cluster_count; k += 17) factor[size_t(k) * 2] = INFINITY;
    std::vector<uint64_t> forced(c.word_count, 0);
    for (uint32_t j = 0; j < list.size(); j += 23) forced[list[j] >> 6] |= 1ull << (list[j] & 63);
    for (const int mode : {0, 1, 2}) {
        const bool relevance = mode != 1, radius_bound = mode != 0;
        std::vector<float> radius[2], size[2];
        uint32_t kept[2];
        for (int path = 0; path < 2; ++path) {
            radius[path].assign(n, -1.0f);
            size[path].assign(n, 0.0f);
            stipple::PointStageFrame f = stipple::point_stage_frame(p.get());
            f.normals = normals.data();
            f.radius = radius[path].data();
            f.size = size[path].data();
            stipple::CullKernelFrame k(f, c, relevance);
            k.cluster_factor = factor.data();
            k.radius_bound = radius_bound;
            k.forced_bits = forced.data();
            // Ranges with tails that are not multiples of 8.
            const uint32_t count = uint32_t(list.size());
            const uint32_t cuts[3] = {0, count / 3 + 5, count};
            kept[path] = 0;
            for (int r = 0; r < 2; ++r)
                kept[path] +=
                    path == 0
                        ? stipple::cull_relevance_size(k, list.data(), cuts[r], cuts[r + 1])
                        : stipple::cull_relevance_size_avx2(k, list.data(), cuts[r], cuts[r + 1]);
        }
        const std::string what = std::string(relevance ? "relevance updates" : "rest radii") +
                                 (radius_bound ? ", radius bound" : "");
        EXPECT_EQ(kept[0], kept[1]) << what;
        EXPECT_GT(kept[0], 0u) << what;
        EXPECT_LT(kept[0], list.size()) << what;
        EXPECT_TRUE(same_floats(radius[0].data(), radius[1].data(), n)) << what;
        EXPECT_TRUE(same_floats(size[0].data(), size[1].data(), n)) << what;
        for (uint32_t j = 0; j < list.size(); j += 23)  // forced points always get a radius
            EXPECT_GE(radius[0][list[j]], 0.0f) << what << ", forced point " << list[j];
    }
}

// The clusters' tests and the stretches over 2 and 3 threads: the same selection as on one.
TEST_F(PointCull, SelectionIsTheSameOnAnyThreadCount) {
    std::unique_ptr<Pipeline> p[3];
    for (int k = 0; k < 3; ++k) {
        stipple::FrameConfig config;
        config.width = 640;
        config.height = 480;
        config.threads = k + 1;
        p[k] = make(config);
        ASSERT_TRUE(p[k]);
    }
    ASSERT_GE(p[0]->clusters.cluster_count, 2 * 64u);  // the ranges really split
    for (int f = 0; f < 5; ++f) {
        stipple::AnimationState state;
        state.time = float(f) / 6.0f;
        for (auto& q : p) stipple::pipeline_update(q.get(), state, nullptr);
        const stipple::PointClusters& a = p[0]->clusters;
        for (int k = 1; k < 3; ++k) {
            const stipple::PointClusters& b = p[k]->clusters;
            const std::string what = std::to_string(k + 1) + " threads, frame " + std::to_string(f);
            ASSERT_EQ(a.run_count, b.run_count) << what;
            ASSERT_EQ(a.placed_count, b.placed_count) << what;
            EXPECT_EQ(0, std::memcmp(a.run.get(), b.run.get(), a.run_count * 4)) << what;
            EXPECT_EQ(0, std::memcmp(a.placed.get(), b.placed.get(), a.placed_count * 4)) << what;
            EXPECT_EQ(0, std::memcmp(a.keep.get(), b.keep.get(), a.cluster_count * 4)) << what;
            EXPECT_EQ(a.stats.culled_back, b.stats.culled_back) << what;
            EXPECT_EQ(a.stats.culled_frustum, b.stats.culled_frustum) << what;
            EXPECT_EQ(a.stats.cut, b.stats.cut) << what;
            EXPECT_EQ(a.stats.points_sized, b.stats.points_sized) << what;
            const uint32_t tris = asset_.mesh.triangle_count;
            EXPECT_TRUE(same_floats(a.area_ratio.get(), b.area_ratio.get(), tris)) << what;
            EXPECT_TRUE(same_floats(a.edge_ratio.get(), b.edge_ratio.get(), tris)) << what;
        }
    }
    for (auto& q : p) stipple::pipeline_destroy(q.get());
}

}  // namespace
