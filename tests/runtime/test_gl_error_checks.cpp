// FrameConfig::check_gl_errors: glGetError after each pass and readback, the first error's
// pass and code and a count in the renderer (pipeline_gl_errors). GL errors are provoked on
// purpose here, through the GL table and through a renderer object broken by hand.
#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "runtime/frame_pipeline.h"
#include "tests/common/fixtures.h"

namespace {

using namespace stipple;
using namespace stipple::test;

class GlErrorChecks : public ::testing::Test {
  protected:
    void SetUp() override {
        const std::string path = baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 5000");
        ASSERT_FALSE(path.empty());
        std::string error;
        ASSERT_TRUE(load_baked(path, &asset_, &error)) << error;
        ASSERT_TRUE(gl_.open(&error)) << error;
        while (gl_.gl().GetError() != GL_NO_ERROR) {
        }
    }
    void TearDown() override {
        if (pipeline_) pipeline_destroy(pipeline_.get());
    }
    // A 64x64 pipeline with the checks on or off.
    void init(bool check) {
        FrameConfig config;
        config.width = config.height = 64;
        config.check_gl_errors = check;
        pipeline_.reset(new Pipeline());
        const Status st = pipeline_init(pipeline_.get(), asset_, gl_.gl(), config);
        ASSERT_TRUE(st.ok()) << st.message;
    }
    // Draws `frames` frames of clip 0 and reads each back.
    void draw(int frames) {
        std::vector<uint8_t> rgba(64 * 64 * 4);
        for (int f = 0; f < frames; ++f) {
            pipeline_frame(pipeline_.get(), 0, float(f) / 30.0f, nullptr);
            renderer_read_color(&pipeline_->renderer, rgba.data());
        }
    }

    Asset asset_;
    HeadlessGl gl_;
    std::unique_ptr<Pipeline> pipeline_;
};

TEST_F(GlErrorChecks, CleanFramesReportNone) {
    init(true);
    draw(5);
    const GlErrorLog& e = pipeline_gl_errors(*pipeline_);
    EXPECT_EQ(e.count, 0u) << "first: " << gl_error_name(e.first_error) << " after "
                           << (e.first_pass ? e.first_pass : "?");
    EXPECT_EQ(e.first_pass, nullptr);
}

// An error raised before a frame (an invalid enum through the GL table) is caught by the
// first check of that frame: the depth pass.
TEST_F(GlErrorChecks, AnErrorBeforeTheFrameIsReportedAfterTheDepthPass) {
    init(true);
    gl_.gl().Enable(0xDEAD);  // not a capability: GL_INVALID_ENUM
    draw(1);
    const GlErrorLog& e = pipeline_gl_errors(*pipeline_);
    EXPECT_EQ(e.count, 1u);
    ASSERT_NE(e.first_pass, nullptr);
    EXPECT_STREQ(e.first_pass, "depth");
    EXPECT_STREQ(gl_error_name(e.first_error), "GL_INVALID_ENUM");
}

// A broken dots program (a name GL never made) fails inside the dots pass, and the report
// names that pass, not the depth or lines passes drawn before it.
TEST_F(GlErrorChecks, AnErrorInsideAPassNamesThatPass) {
    init(true);
    const GLuint program = pipeline_->renderer.point_program;
    pipeline_->renderer.point_program = 0xBAD0BAD;  // glUseProgram: GL_INVALID_VALUE
    draw(2);
    pipeline_->renderer.point_program = program;
    const GlErrorLog& e = pipeline_gl_errors(*pipeline_);
    EXPECT_GE(e.count, 2u);  // once per frame at least
    ASSERT_NE(e.first_pass, nullptr);
    EXPECT_STREQ(e.first_pass, "dots");
    EXPECT_STREQ(gl_error_name(e.first_error), "GL_INVALID_VALUE");
}

TEST_F(GlErrorChecks, OffByDefault) {
    EXPECT_FALSE(FrameConfig().check_gl_errors);
    init(false);
    gl_.gl().Enable(0xDEAD);
    draw(1);
    EXPECT_EQ(pipeline_gl_errors(*pipeline_).count, 0u);
    while (gl_.gl().GetError() != GL_NO_ERROR) {
    }
}

TEST(GlErrorNames, NameEveryCode) {
    EXPECT_STREQ(gl_error_name(GL_INVALID_OPERATION), "GL_INVALID_OPERATION");
    EXPECT_STREQ(gl_error_name(GL_OUT_OF_MEMORY), "GL_OUT_OF_MEMORY");
    EXPECT_STREQ(gl_error_name(GL_INVALID_FRAMEBUFFER_OPERATION),
                 "GL_INVALID_FRAMEBUFFER_OPERATION");
    EXPECT_STREQ(gl_error_name(0x1234), "GL_UNKNOWN_ERROR");
}

}  // namespace
