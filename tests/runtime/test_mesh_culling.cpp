// The mesh pass culls the back faces of single-sided triangles (CCW front) and draws
// double-sided triangles (RendererConfig::triangle_double_sided) from both sides; with the
// paper the colour of the background it writes depth only, and the dots still find the body.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "runtime/renderer.h"
#include "tests/common/fixtures.h"

namespace {

using namespace stipple;
using namespace stipple::test;

constexpr int kSize = 32;

// Two quads side by side at z = 0, seen from +z by an orthographic camera looking down -z
// (view-projection diag(1, 1, -1, 1), determinant < 0 like every camera's): the left one
// (x < 0) counter-clockwise as seen (front-facing), the right one clockwise (back-facing).
const float kPositions[] = {
    -0.9f, -0.5f, 0.0f, -0.1f, -0.5f, 0.0f, -0.1f, 0.5f, 0.0f, -0.9f, 0.5f, 0.0f,  // left
    0.1f,  -0.5f, 0.0f, 0.9f,  -0.5f, 0.0f, 0.9f,  0.5f, 0.0f, 0.1f,  0.5f, 0.0f,  // right
};
const uint32_t kIndices[] = {0, 1, 2, 0, 2, 3,   // left: CCW
                             4, 6, 5, 4, 7, 6};  // right: CW

class MeshCulling : public ::testing::Test {
  protected:
    void SetUp() override {
        std::string error;
        ASSERT_TRUE(gl_.open(&error)) << error;
    }
    void TearDown() override { renderer_destroy(&renderer_); }
    void init(const uint8_t* double_sided, bool paper_is_background) {
        RendererConfig c;
        c.width = c.height = kSize;
        c.max_points = 2;
        c.vertex_count = 8;
        c.indices = kIndices;
        c.triangle_count = 4;
        c.triangle_double_sided = double_sided;
        const float background[3] = {0.0f, 0.0f, 1.0f}, paper[3] = {1.0f, 1.0f, 1.0f};
        std::memcpy(c.background, paper_is_background ? paper : background, 12);
        std::memcpy(c.paper, paper, 12);
        const Status st = renderer_init(&renderer_, gl_.gl(), c);
        ASSERT_TRUE(st.ok()) << st.message;
    }
    // Draws the mesh pass, then a dot in front of each quad's centre; reads the colour.
    void draw(const glm::mat4& view_projection = camera()) {
        renderer_draw_mesh(&renderer_, view_projection, kPositions, 8);
        if (with_dots_) {
            const float dots[6] = {-0.5f, 0.0f, 0.01f, 0.5f, 0.0f, 0.01f};
            const float sizes[2] = {6.0f, 6.0f};
            renderer_draw_points(&renderer_, view_projection, dots, sizes, 2);
        }
        rgba_.assign(size_t(kSize) * kSize * 4, 0);
        renderer_read_color(&renderer_, rgba_.data());
    }
    // The pixel at the centre of the left (0) or right (1) quad.
    const uint8_t* centre(int quad) const {
        const int x = quad == 0 ? kSize / 4 : 3 * kSize / 4;
        return rgba_.data() + (size_t(kSize / 2) * kSize + size_t(x)) * 4;
    }
    static glm::mat4 camera() {
        glm::mat4 m(1.0f);
        m[2][2] = -1.0f;
        return m;
    }
    static bool is(const uint8_t* p, uint8_t r, uint8_t g, uint8_t b) {
        return p[0] == r && p[1] == g && p[2] == b;
    }

    HeadlessGl gl_;
    Renderer renderer_;
    bool with_dots_ = false;
    std::vector<uint8_t> rgba_;
};

TEST_F(MeshCulling, SingleSidedBackFacesShowTheBackground) {
    init(nullptr, false);
    EXPECT_EQ(renderer_.single_sided_count, 4u);
    draw();
    EXPECT_TRUE(is(centre(0), 255, 255, 255));  // paper
    EXPECT_TRUE(is(centre(1), 0, 0, 255));      // background
}

TEST_F(MeshCulling, DoubleSidedTrianglesDrawFromBothSides) {
    const uint8_t right_double[4] = {0, 0, 1, 1};
    init(right_double, false);
    EXPECT_EQ(renderer_.single_sided_count, 2u);
    draw();
    EXPECT_TRUE(is(centre(0), 255, 255, 255));
    EXPECT_TRUE(is(centre(1), 255, 255, 255));
}

// Flags in any order: the index buffer is regrouped, every triangle still drawn once.
TEST_F(MeshCulling, InterleavedFlagsKeepEveryTriangle) {
    const uint8_t interleaved[4] = {1, 0, 1, 0};
    init(interleaved, false);
    EXPECT_EQ(renderer_.single_sided_count, 2u);
    draw();
    // Left quad: both halves drawn (one front-facing single-sided, one double-sided).
    EXPECT_TRUE(is(centre(0), 255, 255, 255));
    int left_paper = 0, right_paper = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const uint8_t* p = rgba_.data() + (size_t(y) * kSize + size_t(x)) * 4;
            if (is(p, 255, 255, 255)) ++(x < kSize / 2 ? left_paper : right_paper);
        }
    // The right quad keeps only its double-sided half: about half the left's pixels.
    EXPECT_GT(left_paper, 0);
    EXPECT_GT(right_paper, left_paper / 4);
    EXPECT_LT(right_paper, 3 * left_paper / 4);
}

// An application's GL_CULL_FACE left on does not cull double-sided triangles, and the
// renderer leaves culling off after its pass.
TEST_F(MeshCulling, DoubleSidedIgnoresCullingLeftOn) {
    const uint8_t all_double[4] = {1, 1, 1, 1};
    init(all_double, false);
    EXPECT_EQ(renderer_.single_sided_count, 0u);
    gl_.gl().Enable(GL_CULL_FACE);
    draw();
    EXPECT_TRUE(is(centre(1), 255, 255, 255));
    EXPECT_FALSE(gl_.gl().IsEnabled(GL_CULL_FACE));
}

// A context whose glFrontFace is clockwise: the renderer sets the winding itself, so the
// front quad is drawn and the back one culled all the same.
TEST_F(MeshCulling, ClockwiseFrontFaceOfTheContextDoesNotMatter) {
    init(nullptr, false);
    using FrontFace = void (*)(GLenum);
    auto front_face =
        reinterpret_cast<FrontFace>(platform::proc_loader(gl_.context())("glFrontFace"));
    ASSERT_NE(front_face, nullptr);
    front_face(GL_CW);
    draw();
    front_face(GL_CCW);
    EXPECT_TRUE(is(centre(0), 255, 255, 255));  // paper
    EXPECT_TRUE(is(centre(1), 0, 0, 255));      // background
}

// A mirrored view-projection (x flipped: determinant > 0) shows the front quad on the right,
// clockwise on screen: it is still drawn, and the back quad (now on the left) still culled.
TEST_F(MeshCulling, MirroredViewKeepsTheFrontFaces) {
    init(nullptr, false);
    glm::mat4 mirrored = camera();
    mirrored[0][0] = -1.0f;
    draw(mirrored);
    EXPECT_TRUE(is(centre(1), 255, 255, 255));
    EXPECT_TRUE(is(centre(0), 0, 0, 255));
}

// Paper = background: the pass writes depth only. The dot over the front quad is drawn (the
// body's depth is there), the one over the culled quad is not (nothing there), and the
// colour writes are back on for the dots.
TEST_F(MeshCulling, DepthOnlyPassStillHoldsTheDots) {
    init(nullptr, true);
    with_dots_ = true;
    draw();
    EXPECT_TRUE(is(centre(0), 0, 0, 0));        // ink over the body
    EXPECT_TRUE(is(centre(1), 255, 255, 255));  // no body, no dot: paper-white background
    GLboolean mask[4] = {};
    gl_.gl().GetBooleanv(GL_COLOR_WRITEMASK, mask);
    EXPECT_TRUE(mask[0] && mask[1] && mask[2] && mask[3]);
}

}  // namespace
