// The level of detail (runtime/point_clusters.h) on random cases, and its selection over the
// thread pool (runtime/point_clusters_select.cpp):
//  - on random views, zooms, tones, lights and poses the drawn dots are the bytes of the full
//    stages, and the clusters' back-face test and slope bound do their share of the work;
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
#include "runtime/point_simd.h"
#include "runtime/point_stages.h"
#include "tests/common/fixtures.h"

namespace {

using stipple::Pipeline;

bool same_floats(const float* a, const float* b, size_t n) {
    return n == 0 || std::memcmp(a, b, n * 4) == 0;  // (empty vectors' data() may be null)
}

class LodRandom : public ::testing::Test {
  protected:
    void SetUp() override {
        std::string error;
        ASSERT_TRUE(stipple::test::load_baked(
            stipple::test::baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 60000"), &asset_,
            &error))
            << error;
        ASSERT_TRUE(gl_.open(&error)) << error;
    }
    void TearDown() override { stipple::point_simd_force(stipple::point_simd_detected()); }

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

// The level of detail draws the dots of the full stages, which run every point through
// relevance and size: the same points at the same places with the same sizes bit for bit.
// Random views include grazing ones, where the slope bound cuts hardest.
TEST_F(LodRandom, DrawsTheDotsOfTheFullStages) {
    std::mt19937 rng(1234);
    uint64_t run_total = 0, drawn_total = 0, back_total = 0, clusters_total = 0;
    for (int trial = 0; trial < 16; ++trial) {
        const stipple::FrameConfig config = random_config(&rng);
        stipple::FrameConfig every = config;
        every.lod = false;
        std::unique_ptr<Pipeline> p = make(config), full = make(every);
        ASSERT_TRUE(p && full);
        for (int f = 0; f < 3; ++f) {
            stipple::AnimationState state;
            state.time = std::uniform_real_distribution<float>(0.0f, 2.0f)(rng);
            stipple::pipeline_update(full.get(), state, nullptr);
            stipple::pipeline_update(p.get(), state, nullptr);
            const std::vector<float> dots = drawable_dots(*full), lod = drawable_dots(*p);
            const std::string what =
                "trial " + std::to_string(trial) + ", frame " + std::to_string(f);
            ASSERT_EQ(lod.size(), dots.size()) << what;
            EXPECT_TRUE(same_floats(lod.data(), dots.data(), dots.size())) << what;
            run_total += p->clusters.run_count;
            drawn_total += dots.size() / 4;
            back_total += p->clusters.stats.culled_back;
            clusters_total += p->clusters.stats.clusters;
        }
        stipple::pipeline_destroy(p.get());
        stipple::pipeline_destroy(full.get());
    }
    EXPECT_GT(drawn_total, 1000u);
    // Clusters face one way (the bind normal's axis splits them), so about a third of them lie
    // on the far side; and the cut runs a few points per dot, not the whole hierarchy (60k).
    EXPECT_GT(back_total * 5, clusters_total) << back_total << " of " << clusters_total;
    EXPECT_LT(run_total, drawn_total * 12) << run_total << " run for " << drawn_total;
}

// The clusters' tests and the stretches over 2 and 3 threads: the same selection as on one.
TEST_F(LodRandom, SelectionIsTheSameOnAnyThreadCount) {
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
            const uint32_t tris = asset_.mesh.triangle_count;
            EXPECT_TRUE(same_floats(a.area_ratio.get(), b.area_ratio.get(), tris)) << what;
            EXPECT_TRUE(same_floats(a.edge_ratio.get(), b.edge_ratio.get(), tris)) << what;
        }
    }
    for (auto& q : p) stipple::pipeline_destroy(q.get());
}

}  // namespace
