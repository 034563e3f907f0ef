// Instances over one shared asset through the C API (issue 8): the memory a player takes is
// reported before it is created and taken from the application's allocator or block; three
// instances cost three times that plus one asset; each instance draws in a shared frame what
// it draws alone.
#include <gtest/gtest.h>

#include <cstring>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <string>
#include <vector>

#include "platform/headless_context.h"
#include "runtime/stipple.h"
#include "tests/common/fixtures.h"

namespace {

using namespace stipple::test;

struct Hook {
    size_t allocations = 0, releases = 0, bytes = 0;
};

void* hook_allocate(size_t bytes, void* user) {
    Hook* h = static_cast<Hook*>(user);
    ++h->allocations;
    h->bytes += bytes;
    return ::operator new(bytes, std::nothrow);
}
void hook_release(void* p, void* user) {
    ++static_cast<Hook*>(user)->releases;
    ::operator delete(p);
}

class Instances : public ::testing::Test {
  protected:
    void SetUp() override {
        std::string error;
        ASSERT_TRUE(gl_.open(&error)) << error;
        const std::string path = baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 5000");
        ASSERT_EQ(stipple_asset_load_file(path.c_str(), &asset_), STIPPLE_OK);
        desc_.width = 240;
        desc_.height = 160;
        desc_.get_proc_address = stipple::platform::proc_loader(gl_.context());
    }
    void TearDown() override { stipple_asset_destroy(asset_); }
    HeadlessGl gl_;
    stipple_asset* asset_ = nullptr;
    stipple_player_desc desc_ = {};
};

TEST_F(Instances, MemoryComesFromTheHookAndMatchesTheQuery) {
    const size_t bytes = stipple_player_memory_bytes(asset_, &desc_);
    ASSERT_GT(bytes, 100000u);
    Hook hook;
    stipple_player_desc d = desc_;
    d.allocate = hook_allocate;
    d.release = hook_release;
    d.allocator_user = &hook;
    stipple_player* players[3] = {};
    for (auto& p : players) ASSERT_EQ(stipple_player_create(asset_, &d, &p), STIPPLE_OK);
    EXPECT_EQ(hook.bytes, 3 * bytes) << "three instances take three times the query";
    const size_t taken = hook.allocations;
    for (auto& p : players) stipple_player_draw(p, 0, 0.3f);
    EXPECT_EQ(hook.allocations, taken) << "drawing took memory";
    for (auto& p : players) stipple_player_destroy(p);
    EXPECT_EQ(hook.releases, hook.allocations);
}

TEST_F(Instances, ABlockOfTheQueriedSizeIsEnoughAndOneByteLessIsNot) {
    const size_t bytes = stipple_player_memory_bytes(asset_, &desc_);
    std::vector<uint8_t> storage(bytes + 16);
    uint8_t* block = storage.data() + (16 - reinterpret_cast<uintptr_t>(storage.data()) % 16) % 16;
    stipple_player_desc d = desc_;
    d.memory = block;
    d.memory_size = bytes - 1;
    stipple_player* p = nullptr;
    EXPECT_EQ(stipple_player_create(asset_, &d, &p), STIPPLE_ERROR_OUT_OF_MEMORY);
    EXPECT_EQ(p, nullptr);
    d.memory_size = bytes;
    ASSERT_EQ(stipple_player_create(asset_, &d, &p), STIPPLE_OK) << stipple_last_error();
    std::vector<uint8_t> rgba(240 * 160 * 4);
    stipple_player_draw(p, 0, 0.3f);
    stipple_player_read_rgba(p, rgba.data());
    size_t ink = 0;
    for (size_t i = 0; i < rgba.size(); i += 4) ink += rgba[i] < 100;
    EXPECT_GT(ink, 100u) << "a player living in the caller's block draws";
    stipple_player_destroy(p);
}

// Three instances side by side in one application frame: each region is what that instance
// draws alone (pixel-exact), so instances share nothing but the asset.
TEST_F(Instances, EachInstanceDrawsInTheSharedFrameWhatItDrawsAlone) {
    const stipple::GlApi& g = gl_.gl();
    constexpr int kW = 480, kH = 160;
    TestFramebuffer framebuffer;
    ASSERT_TRUE(framebuffer.create(g, kW, kH));
    stipple_player_desc d = desc_;
    d.width = kW;
    d.height = kH;
    stipple_player* players[3] = {};
    for (auto& p : players) ASSERT_EQ(stipple_player_create(asset_, &d, &p), STIPPLE_OK);
    stipple_app_view view = {};
    const glm::mat4 v =
        glm::lookAt(glm::vec3(0, 0.8f, 4.2f), glm::vec3(0, 0.75f, 0), glm::vec3(0, 1, 0));
    const glm::mat4 proj = glm::perspective(glm::radians(30.0f), float(kW) / kH, 0.1f, 20.0f);
    std::memcpy(view.view, glm::value_ptr(v), sizeof(view.view));
    std::memcpy(view.projection, glm::value_ptr(proj), sizeof(view.projection));
    view.viewport[2] = kW;
    view.viewport[3] = kH;
    auto draw = [&](int only) {  // only: one instance, or -1 for all three
        g.BindFramebuffer(GL_FRAMEBUFFER, framebuffer.fbo());
        g.Viewport(0, 0, kW, kH);
        g.DepthMask(GL_TRUE);
        g.ClearColor(1, 1, 1, 1);
        g.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        for (int i = 0; i < 3; ++i) {
            if (only >= 0 && i != only) continue;
            const glm::mat4 m = glm::translate(glm::mat4(1.0f), glm::vec3(1.3f * (i - 1), 0, 0));
            std::memcpy(view.model, glm::value_ptr(m), sizeof(view.model));
            stipple_player_draw_into(players[i], &view, 0, 0.2f + 0.5f * i, -1, 0.0f, 0.0f);
        }
        std::vector<uint8_t> rgba(size_t(kW) * kH * 4);
        g.BindFramebuffer(GL_FRAMEBUFFER, framebuffer.fbo());
        g.ReadPixels(0, 0, kW, kH, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
        return rgba;
    };
    const std::vector<uint8_t> all = draw(-1);
    std::vector<uint8_t> alone[3] = {draw(0), draw(1), draw(2)};
    auto covers = [](const std::vector<uint8_t>& img, size_t k) {
        return img[k] != 255 || img[k + 1] != 255 || img[k + 2] != 255;
    };
    size_t compared[3] = {}, differ[3] = {}, overlap = 0;
    for (size_t k = 0; k < all.size(); k += 4) {
        int owner = -1, count = 0;
        for (int i = 0; i < 3; ++i)
            if (covers(alone[i], k)) owner = i, ++count;
        if (count > 1) {
            ++overlap;
            continue;
        }
        if (owner < 0) {
            EXPECT_FALSE(covers(all, k)) << "ink where no instance draws alone";
            continue;
        }
        ++compared[owner];
        differ[owner] += std::memcmp(&all[k], &alone[owner][k], 4) != 0;
    }
    for (int i = 0; i < 3; ++i) {
        EXPECT_GT(compared[i], 1000u) << "instance " << i << " drew too little";
        EXPECT_EQ(differ[i], 0u) << "instance " << i;
    }
    EXPECT_LT(overlap, compared[1] / 10) << "the instances should barely overlap";
    for (auto& p : players) stipple_player_destroy(p);
}

}  // namespace
