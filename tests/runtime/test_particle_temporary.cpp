// Unit tests of runtime/particle_temporary.h: GI'01 §5's temporary particles on triangles,
// generated per view into a fixed pool of slots keyed by (triangle, rank).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "runtime/particle_stage.h"
#include "runtime/particle_temporary.h"
#include "tests/common/fixtures.h"

namespace {

using namespace stipple;
using namespace stipple::test;

constexpr int kW = 640, kH = 480;

class TemporaryParticlesTest : public ::testing::Test {
  protected:
    void SetUp() override {
        std::string error;
        ASSERT_TRUE(load_baked(baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 5000"),
                               &asset_, &error))
            << error;
        const MeshView& m = asset_.mesh;
        for (uint32_t v = 0; v < m.vertex_count; ++v)
            for (int k = 0; k < 3; ++k) {
                lo_[k] = std::min(lo_[k], m.positions[v * 3 + k]);
                hi_[k] = std::max(hi_[k], m.positions[v * 3 + k]);
            }
    }
    // The bind pose seen from the front (+z of the bounding box's centre, the whole box in a
    // 40 degree field), zoomed `zoom` times by the focal length.
    ParticleFrame frame(float zoom) const {
        const glm::vec3 c = 0.5f * (lo_ + hi_);
        const float size = glm::length(hi_ - lo_);
        const float fov = 2.0f * std::atan(std::tan(glm::radians(20.0f)) / zoom);
        ParticleFrame f;
        f.points = &asset_.points;
        f.indices = asset_.mesh.indices;
        f.positions = asset_.mesh.positions;
        f.normals = asset_.mesh.normals;
        f.eye = c + glm::vec3(0.0f, 0.0f, 1.5f * size);
        f.view_projection =
            glm::perspective(fov, float(kW) / float(kH), 0.01f * size, 10.0f * size) *
            glm::lookAt(f.eye, c, glm::vec3(0.0f, 1.0f, 0.0f));
        f.width = kW;
        f.height = kH;
        f.focal_px = 0.5f * float(kH) / std::tan(0.5f * fov);
        return f;
    }
    // The live slots as (slot, (triangle, rank)).
    static std::map<uint32_t, std::pair<uint32_t, uint32_t>> live(const TemporaryParticles& t) {
        std::map<uint32_t, std::pair<uint32_t, uint32_t>> m;
        for (uint32_t s = 0; s < t.slots; ++s)
            if (t.triangle[s] != kFreeSlot) m[s] = {t.triangle[s], t.rank[s]};
        return m;
    }
    Asset asset_;
    glm::vec3 lo_ = glm::vec3(INFINITY), hi_ = glm::vec3(-INFINITY);
};

TEST_F(TemporaryParticlesTest, SlotsAreTakenAtInitAndAllFree) {
    TemporaryParticles t;
    ASSERT_TRUE(temporary_particles_build(&t, asset_, 40000).ok());
    const uint32_t baked = asset_.points.point_count;
    EXPECT_EQ(t.baked, baked);
    EXPECT_EQ(t.slots, 40000u - baked);
    EXPECT_EQ(t.count, 40000u);
    EXPECT_EQ(t.free_count, t.slots);
    ASSERT_EQ(t.view.point_count, t.count);
    for (uint32_t i = 0; i < baked; ++i) {  // the baked points are kept as they are
        ASSERT_EQ(t.view.host_triangle[i], asset_.points.host_triangle[i]);
        ASSERT_EQ(t.view.radius[i], asset_.points.radius[i]);
    }
    EXPECT_TRUE(live(t).empty());
}

TEST_F(TemporaryParticlesTest, NoneWhenTheBudgetIsTheBake) {
    TemporaryParticles t;
    ASSERT_TRUE(temporary_particles_build(&t, asset_, 0).ok());
    EXPECT_EQ(t.count, asset_.points.point_count);
    EXPECT_EQ(t.slots, 0u);
    EXPECT_EQ(t.view.host_triangle, asset_.points.host_triangle);
}

// A close-up takes slots only on triangles in view that face the eye; each slot holds one
// (triangle, rank), a triangle's ranks are a prefix, radii shrink with the rank (the A / i law
// continued); the same view twice keeps every slot's key (stable ids); a second stage makes the
// same slots (deterministic); and when the view moves away, every slot fades out and is freed.
TEST_F(TemporaryParticlesTest, GeneratedPerViewKeyedByTriangleAndRank) {
    const ParticleStyle& style = *find_particle_style("painterly-long");
    ParticleStage s, again;
    ASSERT_TRUE(particle_stage_init(&s, asset_, style, kW, kH, 200000).ok());
    ASSERT_TRUE(particle_stage_init(&again, asset_, style, kW, kH, 200000).ok());
    const ParticleFrame close = frame(8.0f);
    for (int f = 0; f < 3; ++f) {
        particle_stage_update(&s, close);
        particle_stage_update(&again, close);
    }
    const TemporaryParticles& t = s.temporary;
    const auto first = live(t);
    std::printf("zoom 8: %zu slots held, %u shown, %u triangles asked of %u\n", first.size(),
                t.stats.shown, t.stats.triangles, asset_.mesh.triangle_count);
    ASSERT_GT(first.size(), 1000u);
    EXPECT_EQ(first, live(again.temporary));
    EXPECT_LT(t.stats.triangles, asset_.mesh.triangle_count / 2);
    std::map<uint32_t, std::vector<std::pair<uint32_t, float>>> ranks;  // (rank, radius)
    uint32_t listed = 0;
    for (const auto& [slot, key] : first) {
        const uint32_t id = t.baked + slot, tri = key.first;
        ASSERT_EQ(t.view.host_triangle[id], tri);
        ranks[tri].push_back({key.second, t.view.radius[id]});
        // In view (with the stroke margin) and facing the eye or near the outline.
        const uint32_t* c = asset_.mesh.indices + size_t(tri) * 3;
        bool in_x = false, in_y = false;
        float most = -1.0f;
        for (int k = 0; k < 3; ++k) {
            const glm::vec3 p = glm::make_vec3(asset_.mesh.positions + size_t(c[k]) * 3);
            const glm::vec4 q = close.view_projection * glm::vec4(p, 1.0f);
            in_x |= std::abs(q.x) < 1.2f * q.w;
            in_y |= std::abs(q.y) < 1.2f * q.w;
            const glm::vec3 n = glm::make_vec3(asset_.mesh.normals + size_t(c[k]) * 3);
            most = std::max(most, glm::dot(glm::normalize(n), glm::normalize(close.eye - p)));
        }
        EXPECT_TRUE(in_x || in_y) << tri;
        EXPECT_GT(most, -0.2f) << tri;
        listed += (s.set.state[id] & kParticleListed) != 0;
    }
    EXPECT_EQ(listed, first.size());
    for (auto& [tri, r] : ranks) {
        std::sort(r.begin(), r.end());
        for (uint32_t k = 0; k < r.size(); ++k) {
            ASSERT_EQ(r[k].first, k) << "triangle " << tri;
            ASSERT_GT(r[k].second, 0.0f);
            if (k > 0) {
                ASSERT_LT(r[k].second, r[k - 1].second) << "triangle " << tri;
            }
        }
        EXPECT_EQ(t.linked[tri], r.size());
    }
    particle_stage_update(&s, close);
    EXPECT_EQ(live(t), first) << "the same view keeps every slot's (triangle, rank)";
    // Far away: nothing needed, every slot fades out (4 frames) and is freed.
    const ParticleFrame far = frame(0.5f);
    for (int f = 0; f < 6; ++f) particle_stage_update(&s, far);
    EXPECT_EQ(t.free_count, t.slots);
    EXPECT_TRUE(live(t).empty());
    uint32_t temporary_listed = 0;
    for (uint32_t k = 0; k < s.set.count; ++k) temporary_listed += s.set.list[k] >= t.baked;
    EXPECT_EQ(temporary_listed, 0u);
    particle_stage_destroy(&s);
    particle_stage_destroy(&again);
}

// Zooming in by steps, a slot keeps its (triangle, rank) from frame to frame while it lives:
// one cannot vanish from above one fade step of opacity (it fades out first and is freed only
// then), and none that joins shows at full opacity. Most stay: the ranks a zoom in adds
// are new slots, and only the triangles that leave the narrowing view let theirs go.
TEST_F(TemporaryParticlesTest, KeepTheirIdsAndFadeWhileTheViewChanges) {
    ParticleStage s;
    ASSERT_TRUE(
        particle_stage_init(&s, asset_, *find_particle_style("painterly-long"), kW, kH, 200000)
            .ok());
    particle_stage_update(&s, frame(3.0f));
    uint32_t kept = 0, before = 0;
    for (int f = 1; f <= 10; ++f) {
        const auto a = live(s.temporary);
        std::map<uint32_t, float> alpha;
        for (const auto& [slot, key] : a) alpha[slot] = s.set.alpha[s.temporary.baked + slot];
        particle_stage_update(&s, frame(3.0f * std::pow(1.05f, float(f))));
        const auto b = live(s.temporary);
        for (const auto& [slot, key] : a) {
            ++before;
            const auto it = b.find(slot);
            if (it == b.end()) {
                EXPECT_LE(alpha[slot], 0.26f) << "slot " << slot << " vanished while shown";
                continue;
            }
            ASSERT_EQ(it->second, key) << "slot " << slot << " changed its key while alive";
            ++kept;
        }
        for (const auto& [slot, key] : b) {
            if (!a.count(slot)) {
                EXPECT_LE(s.set.alpha[s.temporary.baked + slot], 0.26f);
            }
        }
    }
    std::printf("zooming in 5%% a frame: %u of %u slots kept their key\n", kept, before);
    EXPECT_GE(kept, before - before / 20);
    particle_stage_destroy(&s);
}

// particle_stage_init's list_points bounds what a frame lists: stage 1's list, stage 3's
// samples and stage 4's strokes are sized by it, the ids' per-particle arrays by the tree.
TEST_F(TemporaryParticlesTest, AListBudgetSizesTheListedBuffersOnly) {
    const ParticleStyle* style = find_particle_style("painterly-long");
    ASSERT_NE(style, nullptr);
    auto bytes = [&](uint32_t tree, uint32_t list) {
        CountingArena arena;
        AllocatorScope scope(counting_allocator(&arena));
        ParticleStage s;
        EXPECT_TRUE(particle_stage_init(&s, asset_, *style, 640, 480, tree, list).ok());
        EXPECT_EQ(s.set.capacity, tree);
        EXPECT_EQ(s.set.list_capacity, list == 0 ? tree : list);
        particle_stage_destroy(&s);
        return arena.bytes;
    };
    const size_t whole = bytes(65536, 0), bounded = bytes(65536, 8192);
    const size_t big_tree = bytes(262144, 8192);
    const double per_unlisted = double(whole - bounded) / double(65536 - 8192);
    const double per_id = double(big_tree - bounded) / double(262144 - 65536);
    std::printf(
        "65,536 particles: %zu bytes listed whole, %zu with 8,192 listed (%.1f bytes per "
        "particle not listed); 262,144 with 8,192 listed: %zu (%.1f bytes per id)\n",
        whole, bounded, per_unlisted, big_tree, per_id);
    // Samples 41, strokes and their ids 44, the list and stage 1's scratch 20, an answer 1.
    EXPECT_GT(per_unlisted, 100.0);
    // A slot's id: its point (16), key and link (12), free list (4), set state (6), fades (8).
    EXPECT_LT(per_id, 60.0);
}

}  // namespace
