// libFuzzer target: load a .stip asset and, when it loads, run frames of the pipeline over
// it (runtime/frame_pipeline.cpp: clip sampling, blending, skinning, morphs, placement,
// relevance, sizing, refinement, silhouettes) against a GL table of stubs, so every CPU stage
// runs without a context. docs/fuzzing.md.
#include <cstddef>
#include <cstdint>

#include "runtime/frame_pipeline.h"
#include "tests/fuzz/fuzz_common.h"

namespace {

// A GL entry point that does nothing and returns zero.
template <typename F>
struct Stub;
template <typename R, typename... A>
struct Stub<R (*)(A...)> {
    static R call(A...) { return R(); }
};

void gen_names(GLsizei n, GLuint* names) {
    for (GLsizei i = 0; i < n; ++i) names[i] = GLuint(i + 1);
}
void get_true(GLuint, GLenum, GLint* value) {
    *value = GL_TRUE;
}
void get_floats(GLenum, GLfloat* value) {
    value[0] = value[1] = 1.0f;
}  // line width range
GLuint create_shader(GLenum) {
    return 1;
}
GLuint create_program() {
    return 1;
}
GLenum framebuffer_complete(GLenum) {
    return GL_FRAMEBUFFER_COMPLETE;
}
const GLubyte* get_string(GLenum) {
    return reinterpret_cast<const GLubyte*>("stub");
}

stipple::GlApi stub_gl() {
    stipple::GlApi gl;
#define STIPPLE_GL_STUB(type, name) gl.name = &Stub<type>::call;
    STIPPLE_GL_FUNCTIONS(STIPPLE_GL_STUB)
#undef STIPPLE_GL_STUB
    gl.GenBuffers = gl.GenVertexArrays = gl.GenFramebuffers = gl.GenRenderbuffers = gl.GenTextures =
        &gen_names;
    gl.GetShaderiv = gl.GetProgramiv = &get_true;
    gl.GetFloatv = &get_floats;
    gl.CreateShader = &create_shader;
    gl.CreateProgram = &create_program;
    gl.CheckFramebufferStatus = &framebuffer_complete;
    gl.GetString = &get_string;
    return gl;
}

void run_frames(const stipple::Asset& asset, const stipple::FrameConfig& config) {
    static const stipple::GlApi gl = stub_gl();
    stipple::Pipeline p;
    if (!stipple::pipeline_init(&p, asset, gl, config).ok()) {
        stipple::pipeline_destroy(&p);
        return;
    }
    stipple::AnimationState state;
    if (asset.clip_count > 0) {
        state.clip = 0;
        state.time = 0.37f;
        stipple::pipeline_frame(&p, state, nullptr);
        state.blend_clip = int(asset.clip_count - 1);
        state.blend_time = 1.9f;
        state.blend_weight = 0.4f;
        state.time = 1e4f;  // clips loop
    }
    stipple::pipeline_frame(&p, state, nullptr);
    stipple::pipeline_destroy(&p);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::vector<uint8_t> bytes = stipple::fuzz::asset_bytes(data, size);
    stipple::Asset asset;
    if (!stipple::load_asset_memory(bytes.data(), bytes.size(), &asset).ok()) return 0;
    stipple::FrameConfig config;
    config.width = 96;
    config.height = 72;
    // A small refinement budget: the same code paths (the budget binds more often, so the
    // rescaled pass and the count limit run too) at a fraction of the 2^18 default's cost.
    // A frame's refinement work is bounded by 64 budgets (docs/fuzzing.md), which dominated
    // the run time at 2,048 (~130 inputs/s under ASan); 256 keeps every path.
    config.refinement_budget = 256;
    run_frames(asset, config);
    // A close-up with dual quaternions, framed on the clips: refinement past the hierarchy.
    config.zoom = 8.0f;
    config.yaw_degrees = 70.0f;
    config.skinning = stipple::anim::Skinning::dqs;
    config.frame_clip = asset.clip_count > 0 ? 0 : -1;
    config.frame_blend_clip = int(asset.clip_count) - 1;
    run_frames(asset, config);
    return 0;
}
