// Particle memory is accounted (docs/particles.md): pipeline_memory_bytes covers what a
// pipeline with a particle style takes from its allocator (the particle tree at
// FrameConfig::particle_budget, visibility fades), so a block of that size suffices, and it
// grows with the budget by what the per-particle buffers cost.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "runtime/frame_pipeline.h"
#include "runtime/particle_style.h"
#include "tests/common/fixtures.h"

namespace {

using namespace stipple;

// An allocator hook that sums what it hands out (as a block rounds it) and the peak in use.
struct Tally {
    size_t total = 0, live = 0, peak = 0;
};
void* tally_allocate(size_t bytes, void* user) {
    Tally* t = static_cast<Tally*>(user);
    const size_t n = rounded_allocation(bytes);
    void* raw = std::aligned_alloc(kAllocationAlign, n + kAllocationAlign);
    if (!raw) return nullptr;
    *static_cast<size_t*>(raw) = n;
    t->total += n;
    t->live += n;
    t->peak = std::max(t->peak, t->live);
    return static_cast<uint8_t*>(raw) + kAllocationAlign;
}
void tally_release(void* p, void* user) {
    if (!p) return;
    void* raw = static_cast<uint8_t*>(p) - kAllocationAlign;
    static_cast<Tally*>(user)->live -= *static_cast<size_t*>(raw);
    std::free(raw);
}

FrameConfig particle_config(uint32_t budget, bool fades) {
    FrameConfig c;
    c.particle_style = find_particle_style("ink");
    c.particle_budget = budget;
    c.particle_fades = fades;
    return c;
}

class ParticleMemory : public ::testing::Test {
  protected:
    void SetUp() override {
        std::string error;
        ASSERT_TRUE(test::load_baked(
            test::baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 10000"), &asset_, &error))
            << error;
        ASSERT_TRUE(gl_.open(&error)) << error;
    }
    Asset asset_;
    test::HeadlessGl gl_;
};

TEST_F(ParticleMemory, PipelineMemoryBytesCoversTheParticleStage) {
    const FrameConfig c = particle_config(kDefaultParticleTreePoints, true);
    const size_t bytes = pipeline_memory_bytes(asset_, c);
    ASSERT_GT(bytes, 0u);
    Tally tally;
    Allocator hook;
    hook.allocate = tally_allocate;
    hook.release = tally_release;
    hook.user = &tally;
    auto p = std::make_unique<Pipeline>();
    ASSERT_TRUE(pipeline_init(p.get(), asset_, gl_.gl(), c, hook).ok());
    EXPECT_TRUE(p->particles.visibility.enabled);
    EXPECT_EQ(p->particles.set.capacity, kDefaultParticleTreePoints);
    const size_t in_use = tally.live;
    pipeline_destroy(p.get());
    std::printf("pipeline_memory_bytes %zu; allocated %zu in all, %zu at the peak, %zu kept\n",
                bytes, tally.total, tally.peak, in_use);
    EXPECT_LE(tally.total, bytes);
    EXPECT_EQ(tally.live, 0u);
    // A block of exactly that size holds the pipeline.
    std::vector<uint8_t> block(bytes + kAllocationAlign);
    BlockArena arena;
    arena.base = block.data();
    arena.size = block.size();
    auto q = std::make_unique<Pipeline>();
    ASSERT_TRUE(pipeline_init(q.get(), asset_, gl_.gl(), c, block_allocator(&arena)).ok());
    EXPECT_LE(arena.used, bytes + kAllocationAlign);
    pipeline_destroy(q.get());
}

// The budget's cost per particle of the tree, and the fades' per pixel (640x480).
TEST_F(ParticleMemory, BudgetAndFadesAreCounted) {
    const uint32_t baked = asset_.points.point_count;
    const size_t none = pipeline_memory_bytes(asset_, particle_config(0, false));
    const size_t small = pipeline_memory_bytes(asset_, particle_config(65536, false));
    const size_t full = pipeline_memory_bytes(asset_, particle_config(262144, false));
    const size_t faded = pipeline_memory_bytes(asset_, particle_config(262144, true));
    ASSERT_GT(none, 0u);
    const double per_particle = double(full - small) / double(262144 - 65536);
    std::printf(
        "bake alone %zu bytes; 65,536 particles %zu; 262,144: %zu (%.1f bytes per "
        "particle), with fades %zu\n",
        none, small, full, per_particle, faded);
    EXPECT_GT(small, none + size_t(100) * (65536 - baked));
    // About 160 bytes per particle kept by the stage, and 60 more taken and released during
    // init (the ranked candidates, bind positions, the tree's grids), which a block must hold
    // too: 222 when measured. Stage 1's scratch holds a chunk, not the tree (41 bytes more
    // per particle when it did).
    EXPECT_GT(per_particle, 150.0);
    EXPECT_LT(per_particle, 240.0);
    EXPECT_GE(faded - full, size_t(640) * 480 * 20 + size_t(262144) * 8);
    // Out of range: a named error.
    FrameConfig bad = particle_config((1u << 22) + 1, false);
    FrameConfig out;
    const Status st = resolve_frame_config(bad, &out);
    EXPECT_EQ(st.code, StatusCode::invalid_argument);
    EXPECT_NE(std::string(st.message).find("particle_budget"), std::string::npos) << st.message;
}

}  // namespace
