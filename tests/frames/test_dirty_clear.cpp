// Clearing only what the last frame drew (runtime/renderer_dirty.cpp; issue 9, the draw at its
// raster floor): pipeline_frame narrows the next clear to the posed mesh's picture grown by the
// dots' and lines' half width. Over a walk with camera moves (close-ups past the image's edge,
// the character moving away, turning, seen from above) and a background change, every frame's
// picture and depth copy must hold only the background and the far depth outside the
// rectangle it reports: then clearing that rectangle before the next frame leaves the whole
// image as a full clear would (a clear that missed part of the last frame shows here as
// stale dots outside the next rectangle). And the narrowed clear must really be narrower.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "runtime/frame_pipeline.h"
#include "tests/common/pipeline_view.h"

namespace {

using namespace stipple::test;

constexpr int kWidth = 320, kHeight = 240;

struct Step {
    CameraView camera;
    float time;
    bool grey_background;
};

TEST(DirtyClear, NothingDrawnOutsideTheNextClear) {
    PipelineView view;
    std::string error;
    ASSERT_TRUE(view.open(baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 10000"), kWidth,
                          kHeight, &error))
        << error;
    stipple::Pipeline* p = view.pipeline();
    const Step steps[] = {
        {{1.0f, 0.0f, 0.0f}, 0.0f, false},   {{1.0f, 0.0f, 0.0f}, 0.3f, false},
        {{4.0f, 20.0f, 0.0f}, 0.5f, false},  {{0.5f, 20.0f, 0.0f}, 0.6f, false},
        {{0.5f, 90.0f, 10.0f}, 0.7f, false}, {{2.0f, 180.0f, -20.0f}, 0.9f, false},
        {{0.7f, 0.0f, 0.0f}, 1.1f, true},    {{0.7f, 40.0f, 60.0f}, 1.3f, true},
        {{1.2f, 40.0f, 60.0f}, 1.5f, false}, {{1.2f, 40.0f, 60.0f}, 1.6f, false},
        {{0.4f, -30.0f, 0.0f}, 1.8f, false}, {{1.0f, 0.0f, 0.0f}, 2.0f, false}};
    int narrowed = 0;
    for (const Step& s : steps) {
        stipple::FrameConfig c = p->config;
        c.zoom = s.camera.zoom;
        c.yaw_degrees = s.camera.yaw_degrees;
        c.pitch_degrees = s.camera.pitch_degrees;
        const float grey = s.grey_background ? 0.5f : 1.0f;
        for (float& b : c.background) b = grey;
        for (float& b : c.paper) b = grey;
        ASSERT_TRUE(stipple::pipeline_set_view(p, c).ok());
        const int* d = p->renderer.dirty;
        if (d[2] >= 0 && d[2] * d[3] < kWidth * kHeight) ++narrowed;
        stipple::pipeline_frame(p, 0, s.time, nullptr);
        SCOPED_TRACE(s.time);
        const std::vector<uint8_t> colour = view.read_colour();
        const std::vector<float> depth = view.read_depth();
        const uint8_t bg = s.grey_background ? 128 : 255;
        uint32_t outside = 0, inside = 0;
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x) {
                const bool in =
                    d[2] < 0 || (x >= d[0] && x < d[0] + d[2] && y >= d[1] && y < d[1] + d[3]);
                const size_t i = size_t(y) * kWidth + size_t(x);
                const bool drawn = colour[i * 4] != bg || colour[i * 4 + 1] != bg ||
                                   colour[i * 4 + 2] != bg || depth[i] != 1.0f;
                (in ? inside : outside) += drawn ? 1u : 0u;
            }
        EXPECT_EQ(outside, 0u) << "pixels drawn outside the reported rectangle " << d[0] << ","
                               << d[1] << " " << d[2] << "x" << d[3];
        EXPECT_GT(inside, 100u);
    }
    // Most frames' clears were narrower than the image (not the first, not after a close-up
    // that fills it).
    EXPECT_GE(narrowed, 6);
}

}  // namespace
