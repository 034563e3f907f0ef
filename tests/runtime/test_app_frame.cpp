// Drawing into the application's own frame (runtime/app_frame.h, issue 8): the test is the
// application. It owns a framebuffer (colour + depth), draws its own quad with its own
// program, leaves its GL state set, then has a pipeline draw CesiumMan into the same frame.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>
#include <memory>
#include <string>
#include <vector>

#include "runtime/app_frame.h"
#include "runtime/camera.h"
#include "tests/common/fixtures.h"

namespace {

using namespace stipple;
using namespace stipple::test;

constexpr int kW = 320, kH = 240;

const char* kQuadVs = R"(#version 300 es
layout(location = 0) in vec2 a_xy;
uniform float u_z;
void main() { gl_Position = vec4(a_xy, u_z, 1.0); }
)";
const char* kQuadFs = R"(#version 300 es
precision mediump float;
layout(location = 0) out vec4 o;
void main() { o = vec4(1.0, 0.0, 0.0, 1.0); }
)";

// The application's GL state, queried independently of runtime/gl_state.h.
struct AppState {
    GLint program, vao, array_buffer, fbo, viewport[4], depth_func, src, dst, cull_mode, front_face;
    GLboolean blend, depth_test, depth_mask;
    bool operator==(const AppState& o) const {
        return program == o.program && vao == o.vao && array_buffer == o.array_buffer &&
               fbo == o.fbo && depth_func == o.depth_func && src == o.src && dst == o.dst &&
               cull_mode == o.cull_mode && front_face == o.front_face && blend == o.blend &&
               depth_test == o.depth_test && depth_mask == o.depth_mask &&
               viewport[0] == o.viewport[0] && viewport[1] == o.viewport[1] &&
               viewport[2] == o.viewport[2] && viewport[3] == o.viewport[3];
    }
};

AppState query(const GlApi& gl) {
    AppState s;
    gl.GetIntegerv(GL_CURRENT_PROGRAM, &s.program);
    gl.GetIntegerv(GL_VERTEX_ARRAY_BINDING, &s.vao);
    gl.GetIntegerv(GL_ARRAY_BUFFER_BINDING, &s.array_buffer);
    gl.GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &s.fbo);
    gl.GetIntegerv(GL_VIEWPORT, s.viewport);
    gl.GetIntegerv(GL_DEPTH_FUNC, &s.depth_func);
    gl.GetIntegerv(GL_BLEND_SRC_RGB, &s.src);
    gl.GetIntegerv(GL_BLEND_DST_RGB, &s.dst);
    gl.GetIntegerv(GL_CULL_FACE_MODE, &s.cull_mode);
    gl.GetIntegerv(GL_FRONT_FACE, &s.front_face);
    s.blend = gl.IsEnabled(GL_BLEND);
    s.depth_test = gl.IsEnabled(GL_DEPTH_TEST);
    gl.GetBooleanv(GL_DEPTH_WRITEMASK, &s.depth_mask);
    return s;
}

GLuint shader(const GlApi& gl, GLenum type, const char* src) {
    GLuint s = gl.CreateShader(type);
    gl.ShaderSource(s, 1, &src, nullptr);
    gl.CompileShader(s);
    return s;
}

class AppFrame : public ::testing::Test {
  protected:
    void SetUp() override {
        std::string error;
        ASSERT_TRUE(gl_.open(&error)) << error;
        ASSERT_TRUE(load_baked(baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 20000"),
                               &asset_, &error))
            << error;
        const GlApi& gl = gl_.gl();
        ASSERT_TRUE(framebuffer_.create(gl, kW, kH));
        program_ = gl.CreateProgram();
        gl.AttachShader(program_, shader(gl, GL_VERTEX_SHADER, kQuadVs));
        gl.AttachShader(program_, shader(gl, GL_FRAGMENT_SHADER, kQuadFs));
        gl.LinkProgram(program_);
        const float left_half[12] = {-1, -1, 0, -1, 0, 1, -1, -1, 0, 1, -1, 1};
        gl.GenVertexArrays(1, &vao_);
        gl.BindVertexArray(vao_);
        gl.GenBuffers(1, &vbo_);
        gl.BindBuffer(GL_ARRAY_BUFFER, vbo_);
        gl.BufferData(GL_ARRAY_BUFFER, sizeof(left_half), left_half, GL_STATIC_DRAW);
        gl.EnableVertexAttribArray(0);
        gl.VertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, nullptr);
        FrameConfig config;
        config.width = kW;
        config.height = kH;
        config.check_gl_errors = true;
        ASSERT_TRUE(pipeline_init(pipeline_.get(), asset_, gl, config).ok());
        const OrbitCamera cam = orbit_camera(asset_, pipeline_->config, nullptr);
        view_.view = cam.view;
        view_.projection = cam.projection;
        view_.viewport[2] = kW;
        view_.viewport[3] = kH;
    }
    void TearDown() override { pipeline_destroy(pipeline_.get()); }

    // Clears to `clear`, draws the red quad over the left half at NDC depth quad_z (none if
    // quad_z > 1), sets the application's own state, has the pipeline draw into the frame,
    // and returns the frame. `before`/`after`: the application's state around the call.
    std::vector<uint8_t> frame(float quad_z, float clear, AppState* before, AppState* after) {
        const GlApi& gl = gl_.gl();
        gl.BindFramebuffer(GL_FRAMEBUFFER, framebuffer_.fbo());
        gl.Viewport(0, 0, kW, kH);
        gl.DepthMask(GL_TRUE);
        gl.ClearColor(clear, clear, clear, 1.0f);
        gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        gl.UseProgram(program_);
        gl.BindVertexArray(vao_);
        gl.Enable(GL_DEPTH_TEST);
        gl.DepthFunc(GL_LESS);
        gl.Disable(GL_BLEND);
        if (quad_z <= 1.0f) {
            gl.Uniform1f(gl.GetUniformLocation(program_, "u_z"), quad_z);
            gl.DrawArrays(GL_TRIANGLES, 0, 6);
        }
        // The application's state at the call: odd on purpose.
        gl.Enable(GL_BLEND);
        gl.BlendFunc(GL_ONE, GL_ONE);
        gl.DepthFunc(GL_GREATER);
        gl.DepthMask(GL_FALSE);
        gl.CullFace(GL_FRONT);  // culling itself off: these only have to survive
        gl.FrontFace(GL_CW);
        gl.Viewport(3, 5, 100, 50);
        *before = query(gl);
        AnimationState state;
        state.clip = 0;
        state.time = 0.5f;
        AppView v = view_;
        v.model = model_;
        pipeline_draw_into(pipeline_.get(), state, v, nullptr);
        *after = query(gl);
        std::vector<uint8_t> rgba(size_t(kW) * kH * 4);
        gl.ReadPixels(0, 0, kW, kH, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
        return rgba;
    }

    HeadlessGl gl_;
    Asset asset_;
    std::unique_ptr<Pipeline> pipeline_ = std::make_unique<Pipeline>();
    TestFramebuffer framebuffer_;
    GLuint program_ = 0, vao_ = 0, vbo_ = 0;
    AppView view_;
    glm::mat4 model_ = glm::mat4(1.0f);
};

bool red(const uint8_t* p) {
    return p[0] == 255 && p[1] == 0 && p[2] == 0;
}
bool inky(const uint8_t* p) {
    return p[0] < 100 && p[1] < 100 && p[2] < 100;
}

TEST_F(AppFrame, NearerApplicationGeometryHidesDotsAndLinesExactly) {
    AppState before, after;
    const std::vector<uint8_t> none = frame(2.0f, 0.5f, &before, &after);
    EXPECT_TRUE(before == after) << "the application's GL state changed";
    const std::vector<uint8_t> front = frame(-0.999f, 0.5f, &before, &after);
    EXPECT_TRUE(before == after);
    const std::vector<uint8_t> back = frame(0.9999f, 0.5f, &before, &after);
    size_t ink_left = 0, ink_right = 0, ink_left_back = 0, right_differs = 0, left_not_red = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const size_t i = (size_t(y) * kW + size_t(x)) * 4;
            const bool left = x < kW / 2;
            if (left) {
                ink_left += inky(&none[i]);
                ink_left_back += inky(&back[i]);
                left_not_red += !red(&front[i]);
            } else {
                ink_right += inky(&none[i]);
                for (int c = 0; c < 4; ++c) right_differs += none[i + c] != front[i + c];
            }
        }
    EXPECT_GT(ink_left, 200u) << "the character should straddle the middle";
    EXPECT_GT(ink_right, 200u);
    EXPECT_EQ(left_not_red, 0u) << "ink or body drawn over the nearer quad";
    EXPECT_EQ(right_differs, 0u) << "the quad changed the half it does not cover";
    EXPECT_GT(ink_left_back, ink_left / 2) << "a farther quad must not hide the character";
    EXPECT_EQ(pipeline_gl_errors(*pipeline_).count, 0u)
        << pipeline_gl_errors(*pipeline_).first_pass;
}

// With the application's clear matching the player's white paper, the frame drawn into the
// application's framebuffer looks like the player's own frame of the same state.
TEST_F(AppFrame, MatchesThePlayersFrame) {
    AppState before, after;
    const std::vector<uint8_t> app = frame(2.0f, 1.0f, &before, &after);
    AnimationState state;
    state.clip = 0;
    state.time = 0.5f;
    pipeline_set_view(pipeline_.get(), pipeline_->config).ok();  // back to the orbit camera
    pipeline_frame(pipeline_.get(), state, nullptr);
    std::vector<uint8_t> own(size_t(kW) * kH * 4);
    renderer_read_color(&pipeline_->renderer, own.data());
    size_t differ = 0, ink = 0;
    for (size_t i = 0; i < own.size(); i += 4) {
        ink += inky(&own[i]);
        bool d = false;
        for (int c = 0; c < 3; ++c) d = d || std::abs(int(app[i + c]) - int(own[i + c])) > 8;
        differ += d;
    }
    EXPECT_GT(ink, 400u);
    EXPECT_LT(double(differ), 0.005 * kW * kH) << differ << " pixels differ";
}

// The model matrix places the instance in the world: moved right by a quarter of the view,
// its ink moves right.
TEST_F(AppFrame, ModelMatrixPlacesTheCharacter) {
    AppState before, after;
    auto centroid = [](const std::vector<uint8_t>& rgba) {
        double sx = 0, n = 0;
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x)
                if (inky(&rgba[(size_t(y) * kW + size_t(x)) * 4])) sx += x, n += 1;
        return n > 0 ? sx / n : -1.0;
    };
    const double centred = centroid(frame(2.0f, 1.0f, &before, &after));
    // A shift of d world units at the target's distance moves the image by d * focal / depth;
    // use the camera's own axes: the view's x axis in world space.
    const glm::vec3 right(view_.view[0][0], view_.view[1][0], view_.view[2][0]);
    model_ = glm::translate(glm::mat4(1.0f), 0.3f * right);
    const double moved = centroid(frame(2.0f, 1.0f, &before, &after));
    EXPECT_GT(moved, centred + 10.0);
}

// A framebuffer named in the view is drawn into even when another one is bound, and the
// bound one stays bound.
TEST_F(AppFrame, DrawsIntoANamedFramebuffer) {
    const GlApi& gl = gl_.gl();
    gl.BindFramebuffer(GL_FRAMEBUFFER, framebuffer_.fbo());
    gl.DepthMask(GL_TRUE);
    gl.ClearColor(1, 1, 1, 1);
    gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    GLuint other = 0, other_rb = 0;  // bound at the call; must stay untouched
    gl.GenFramebuffers(1, &other);
    gl.BindFramebuffer(GL_FRAMEBUFFER, other);
    gl.GenRenderbuffers(1, &other_rb);
    gl.BindRenderbuffer(GL_RENDERBUFFER, other_rb);
    gl.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, kW, kH);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, other_rb);
    gl.ClearColor(0, 1, 0, 1);
    gl.Clear(GL_COLOR_BUFFER_BIT);
    AppView v = view_;
    v.framebuffer = framebuffer_.fbo();
    AnimationState state;
    state.clip = 0;
    state.time = 0.5f;
    pipeline_draw_into(pipeline_.get(), state, v, nullptr);
    GLint bound = 0;
    gl.GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &bound);
    EXPECT_EQ(GLuint(bound), other);
    std::vector<uint8_t> mine(size_t(kW) * kH * 4), theirs(mine.size());
    gl.ReadPixels(0, 0, kW, kH, GL_RGBA, GL_UNSIGNED_BYTE, theirs.data());
    gl.BindFramebuffer(GL_FRAMEBUFFER, framebuffer_.fbo());
    gl.ReadPixels(0, 0, kW, kH, GL_RGBA, GL_UNSIGNED_BYTE, mine.data());
    size_t ink = 0, green = 0;
    for (size_t i = 0; i < mine.size(); i += 4) {
        ink += inky(&mine[i]);
        green += theirs[i] == 0 && theirs[i + 1] == 255 && theirs[i + 2] == 0;
    }
    EXPECT_GT(ink, 200u);
    EXPECT_EQ(green, size_t(kW) * kH) << "the bound framebuffer was drawn into";
    gl.DeleteFramebuffers(1, &other);
    gl.DeleteRenderbuffers(1, &other_rb);
}

}  // namespace
