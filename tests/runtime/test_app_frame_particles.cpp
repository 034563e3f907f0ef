// Stroke particles (GI'01, runtime/particle_stage.h) drawn into the application's own frame
// (runtime/app_frame.h): with a particle style the pipeline draws its strokes, not dots, into
// the application's framebuffer and viewport, and the picture matches the player's own frame
// of the same state.
#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "runtime/app_frame.h"
#include "runtime/camera.h"
#include "runtime/particle_style.h"
#include "tests/common/fixtures.h"

namespace {

using namespace stipple;
using namespace stipple::test;

constexpr int kW = 320, kH = 240;

// Marked: a stroke's colour (or the style's fill) over the white paper.
bool marked(const uint8_t* p) {
    return p[0] < 215 || p[1] < 215 || p[2] < 215;
}

struct Frames {
    std::vector<uint8_t> app, own;  // RGBA, bottom row first
    uint32_t strokes = 0;
};

// One state drawn into a white application framebuffer of kW x kH at viewport (x0, y0) and
// by the player's own frame; `app` holds the viewport's pixels only.
void draw_both(const char* style_name, int x0, int y0, Frames* out) {
    HeadlessGl gl;
    std::string error;
    ASSERT_TRUE(gl.open(&error)) << error;
    Asset asset;
    ASSERT_TRUE(
        load_baked(baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 20000"), &asset, &error))
        << error;
    const ParticleStyle* style = find_particle_style(style_name);
    ASSERT_NE(style, nullptr) << style_name;
    FrameConfig config;
    config.width = kW;
    config.height = kH;
    config.check_gl_errors = true;
    config.particle_style = style;
    auto p = std::make_unique<Pipeline>();
    ASSERT_TRUE(pipeline_init(p.get(), asset, gl.gl(), config).ok());
    const GlApi& api = gl.gl();
    TestFramebuffer fb;
    ASSERT_TRUE(fb.create(api, kW + x0, kH + y0));
    api.BindFramebuffer(GL_FRAMEBUFFER, fb.fbo());
    api.Viewport(0, 0, kW + x0, kH + y0);
    api.ClearColor(1, 1, 1, 1);
    api.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    const OrbitCamera cam = orbit_camera(asset, p->config, nullptr);
    AppView view;
    view.view = cam.view;
    view.projection = cam.projection;
    view.viewport[0] = x0;
    view.viewport[1] = y0;
    view.viewport[2] = kW;
    view.viewport[3] = kH;
    AnimationState state;
    state.clip = 0;
    state.time = 0.5f;
    pipeline_draw_into(p.get(), state, view, nullptr);
    out->strokes = p->particles.stroke_count;
    out->app.resize(size_t(kW) * kH * 4);
    api.BindFramebuffer(GL_FRAMEBUFFER, fb.fbo());
    api.ReadPixels(x0, y0, kW, kH, GL_RGBA, GL_UNSIGNED_BYTE, out->app.data());
    ASSERT_TRUE(pipeline_set_view(p.get(), p->config).ok());  // back to the orbit camera
    pipeline_frame(p.get(), state, nullptr);
    out->own.resize(out->app.size());
    renderer_read_color(&p->renderer, out->own.data());
    EXPECT_EQ(pipeline_gl_errors(*p).count, 0u) << pipeline_gl_errors(*p).first_pass;
    pipeline_destroy(p.get());
}

TEST(AppFrameParticles, StrokesAreDrawnIntoTheApplicationsFrameLikeThePlayersOwn) {
    for (const char* style : {"ink", "painterly-long"}) {
        for (int offset : {0, 16}) {  // the application's viewport at (0, 0) and at (16, 16)
            SCOPED_TRACE(std::string(style) + " at " + std::to_string(offset));
            Frames f;
            draw_both(style, offset, offset, &f);
            ASSERT_FALSE(f.app.empty());
            size_t ink = 0, differ = 0;
            for (size_t i = 0; i < f.own.size(); i += 4) {
                ink += marked(&f.app[i]);
                bool d = false;
                for (int c = 0; c < 3; ++c)
                    d = d || std::abs(int(f.app[i + c]) - int(f.own[i + c])) > 24;
                differ += d;
            }
            EXPECT_GT(f.strokes, 200u);
            EXPECT_GT(ink, 500u) << "no strokes in the application's frame";
            EXPECT_LT(double(differ), 0.02 * kW * kH) << differ << " pixels differ";
        }
    }
}

}  // namespace
