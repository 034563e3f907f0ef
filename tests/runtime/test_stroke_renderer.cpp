// runtime/stroke_renderer.h on a headless context, into the test's own 64x64 framebuffer
// (colour + depth): hand-made eye-space StrokeVertex quads facing the viewer.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>
#include <string>
#include <vector>

#include "runtime/stroke_renderer.h"
#include "tests/common/fixtures.h"

namespace {

using namespace stipple;
using namespace stipple::test;

constexpr int kSize = 64;

// A square quad at eye depth z (negative), half-size h, facing the viewer (+z normals).
void add_quad(std::vector<StrokeVertex>* v, std::vector<uint32_t>* idx, float h, float z,
              glm::vec4 rgba) {
    const uint32_t base = uint32_t(v->size());
    const float xy[4][2] = {{-h, -h}, {h, -h}, {h, h}, {-h, h}};
    for (const auto& p : xy) {
        StrokeVertex s = {{p[0], p[1], z}, {0, 0, 1}, {rgba.r, rgba.g, rgba.b, rgba.a}, 0, 1};
        v->push_back(s);
    }
    const uint32_t tri[6] = {0, 1, 2, 0, 2, 3};
    for (uint32_t i : tri) idx->push_back(base + i);
}

class StrokeRendererTest : public ::testing::Test {
  protected:
    void SetUp() override {
        std::string error;
        ASSERT_TRUE(gl_.open(&error)) << error;
        const GlApi& gl = gl_.gl();
        ASSERT_TRUE(framebuffer_.create(gl, kSize, kSize));
        gl.Viewport(0, 0, kSize, kSize);
        while (gl.GetError() != GL_NO_ERROR) {
        }
    }
    void TearDown() override {
        if (renderer_.program) stroke_renderer_destroy(&renderer_);
    }
    void init(uint32_t max_vertices, uint32_t max_indices) {
        StrokeRendererConfig config;
        config.max_vertices = max_vertices;
        config.max_indices = max_indices;
        config.check_errors = true;
        const Status st = stroke_renderer_init(&renderer_, gl_.gl(), config);
        ASSERT_TRUE(st.ok()) << st.message;
    }
    void clear(float r, float g, float b) {
        const GlApi& gl = gl_.gl();
        gl.DepthMask(GL_TRUE);
        gl.ClearColor(r, g, b, 1.0f);
        gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    }
    void draw(const std::vector<StrokeVertex>& v, const std::vector<uint32_t>& idx,
              uint32_t vertex_count, uint32_t index_count) {
        // 90 degrees: at eye depth z the view spans x, y in [z, -z].
        const glm::mat4 projection = glm::perspective(glm::radians(90.0f), 1.0f, 0.1f, 10.0f);
        StrokeLighting lighting;  // light at the viewer: a +z normal gets ambient + diffuse = 1
        stroke_renderer_draw(&renderer_, projection, lighting, v.data(), vertex_count, idx.data(),
                             index_count);
    }
    std::vector<uint8_t> read() {
        std::vector<uint8_t> rgba(kSize * kSize * 4);
        gl_.gl().ReadPixels(0, 0, kSize, kSize, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
        return rgba;
    }
    static const uint8_t* at(const std::vector<uint8_t>& rgba, int x, int y) {
        return &rgba[size_t(y * kSize + x) * 4];
    }

    HeadlessGl gl_;
    TestFramebuffer framebuffer_;
    StrokeRenderer renderer_;
};

void expect_rgb(const uint8_t* p, int r, int g, int b, int tolerance = 2) {
    EXPECT_NEAR(p[0], r, tolerance);
    EXPECT_NEAR(p[1], g, tolerance);
    EXPECT_NEAR(p[2], b, tolerance);
}

TEST_F(StrokeRendererTest, QuadAppearsWhereProjectedInItsColour) {
    init(64, 64);
    std::vector<StrokeVertex> v;
    std::vector<uint32_t> idx;
    add_quad(&v, &idx, 0.5f, -2.0f, {0.8f, 0.4f, 0.2f, 1.0f});  // pixels 24..39
    clear(0, 0, 0);
    draw(v, idx, uint32_t(v.size()), uint32_t(idx.size()));
    const std::vector<uint8_t> rgba = read();
    expect_rgb(at(rgba, 32, 32), 204, 102, 51);
    expect_rgb(at(rgba, 25, 25), 204, 102, 51);
    expect_rgb(at(rgba, 38, 38), 204, 102, 51);
    expect_rgb(at(rgba, 22, 32), 0, 0, 0, 0);
    expect_rgb(at(rgba, 41, 32), 0, 0, 0, 0);
    expect_rgb(at(rgba, 32, 22), 0, 0, 0, 0);
    EXPECT_EQ(renderer_.gl_error_count, 0u);
}

TEST_F(StrokeRendererTest, SpecularIsWhiteAndWeightedByReflectance) {
    init(64, 64);
    std::vector<StrokeVertex> v;
    std::vector<uint32_t> idx;
    add_quad(&v, &idx, 0.5f, -2.0f, {0.2f, 0.2f, 0.2f, 1.0f});
    for (StrokeVertex& s : v) s.reflectance = 0.5f;
    clear(0, 0, 0);
    draw(v, idx, uint32_t(v.size()), uint32_t(idx.size()));
    // At the centre N = V = L: 0.2 * 1 + 0.5 * 1.
    expect_rgb(at(read(), 32, 32), 178, 178, 178, 3);
}

TEST_F(StrokeRendererTest, DepthTestHidesAStrokeBehindEarlierDepth) {
    init(64, 64);
    std::vector<StrokeVertex> v;
    std::vector<uint32_t> idx;
    add_quad(&v, &idx, 0.25f, -1.0f, {0.0f, 1.0f, 0.0f, 1.0f});  // near, pixels 24..39
    clear(0, 0, 0);
    draw(v, idx, uint32_t(v.size()), uint32_t(idx.size()));
    v.clear();
    idx.clear();
    add_quad(&v, &idx, 2.0f, -4.0f, {1.0f, 0.0f, 0.0f, 1.0f});  // far, pixels 16..47
    draw(v, idx, uint32_t(v.size()), uint32_t(idx.size()));
    const std::vector<uint8_t> rgba = read();
    expect_rgb(at(rgba, 32, 32), 0, 255, 0);  // the far stroke is hidden here
    expect_rgb(at(rgba, 18, 32), 255, 0, 0);  // and shows around the near one
    EXPECT_EQ(renderer_.gl_error_count, 0u);
}

TEST_F(StrokeRendererTest, HalfAlphaBlendsHalfway) {
    init(64, 64);
    std::vector<StrokeVertex> v;
    std::vector<uint32_t> idx;
    add_quad(&v, &idx, 0.5f, -2.0f, {1.0f, 0.0f, 0.0f, 0.5f});
    clear(0, 0, 1);
    draw(v, idx, uint32_t(v.size()), uint32_t(idx.size()));
    const std::vector<uint8_t> rgba = read();
    expect_rgb(at(rgba, 32, 32), 128, 0, 128);
    expect_rgb(at(rgba, 10, 10), 0, 0, 255, 0);
}

TEST_F(StrokeRendererTest, CountsOverCapacityAreClampedWithoutGlErrors) {
    init(4, 6);  // room for one quad
    std::vector<StrokeVertex> v;
    std::vector<uint32_t> idx;
    add_quad(&v, &idx, 0.5f, -2.0f, {0.0f, 0.0f, 1.0f, 1.0f});  // centre
    add_quad(&v, &idx, 3.0f, -2.5f, {1.0f, 1.0f, 0.0f, 1.0f});  // would cover everything
    clear(0, 0, 0);
    draw(v, idx, uint32_t(v.size()), uint32_t(idx.size()));
    draw(v, idx, 1000, 1000);
    draw(v, idx, 4, 7);  // not a multiple of 3: the partial triangle is dropped
    const std::vector<uint8_t> rgba = read();
    EXPECT_EQ(renderer_.gl_error_count, 0u) << renderer_.first_gl_error;
    EXPECT_EQ(gl_.gl().GetError(), GLenum(GL_NO_ERROR));
    expect_rgb(at(rgba, 32, 32), 0, 0, 255);
    expect_rgb(at(rgba, 5, 5), 0, 0, 0, 0);  // the second quad was clamped away
}

TEST_F(StrokeRendererTest, LeavesTheDocumentedState) {
    init(16, 16);
    const GlApi& gl = gl_.gl();
    gl.Disable(GL_DEPTH_TEST);
    gl.Disable(GL_BLEND);
    std::vector<StrokeVertex> v;
    std::vector<uint32_t> idx;
    add_quad(&v, &idx, 0.5f, -2.0f, {1.0f, 1.0f, 1.0f, 1.0f});
    draw(v, idx, 4, 6);
    GLfloat depth_test = 0, blend = 0, cull = 1, depth_writes = 0;
    gl.GetFloatv(GL_DEPTH_TEST, &depth_test);
    gl.GetFloatv(GL_BLEND, &blend);
    gl.GetFloatv(GL_CULL_FACE, &cull);
    gl.GetFloatv(GL_DEPTH_WRITEMASK, &depth_writes);
    EXPECT_EQ(depth_test, 1.0f);
    EXPECT_EQ(blend, 1.0f);
    EXPECT_EQ(cull, 0.0f);
    EXPECT_EQ(depth_writes, 1.0f);
}

}  // namespace
