// The frame against its raster floor (issue 9, "What it must show"; thesis §9.1.1): at
// 1280x720 through headless EGL, for CesiumMan (100k points, its walk) and the horse animated
// through a generated skeleton (tools/bend_rig.h, 96,966 points, relevance recompute on), in
// one run with interleaved rounds:
//   frame  - pipeline_frame: every CPU stage, then the renderer's passes and glFinish;
//   floor  - a bare GL program drawing exactly the dots the frame drew (positions and sizes
//            copied once from the pipeline's draw buffers) over one depth-only pass of the full
//            mesh in the same pose (back faces culled), no CPU stage;
//   replay - the pipeline's own renderer on the same copied frames (mesh pass, silhouette
//            lines, dots): the draw side without the CPU stages.
// "GPU culls": the frame and the replay again with every triangle handed to the GPU, which
// culls the back faces (the mesh pass before runtime/renderer_front.cpp), for the A/B.
// "occluder": the frame with the depth pass drawing the bake's simplified occluder (OCCL,
// bake/occluder.h, 10% of the triangles; runtime/renderer_occluder.cpp) instead of the full
// mesh; the other variants draw the full mesh (the assets carry the section; it is turned off).
// "2 threads": the frame and the occluder frame again with a two-thread pool, which runs the
// point part on its worker beside the mesh pass (pipeline_frame); the other variants use the
// default, one thread.
// "before": the frame drawn the way pipeline_frame drew it before the mesh pass went ahead of
// the point stages and the clear was narrowed (bench/frame_floor_before.h).
// Each round runs kFrames frames of each, replaying frame k of the clip in all of them.
// Reports ms per frame (min and median over rounds), frame / floor, fps, process CPU time
// and the stage times.
// Own main (not benchmark_main): the rounds are interleaved by hand. `--rounds N`;
// `--raster-threads N`: llvmpipe's rasterizer threads (bench/raster_threads.sh compares).
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "bake/asset_writer.h"
#include "bake/occluder.h"
#include "bake/point_hierarchy.h"
#include "bake/scene_import.h"
#include "bench/frame_floor_before.h"
#include "platform/headless_context.h"
#include "runtime/frame_pipeline.h"
#include "runtime/gl_program.h"
#include "tools/bend_rig.h"

namespace {

using stipple::GlApi;
constexpr int kWidth = 1280, kHeight = 720;
constexpr int kFrames = 30;  // frames per round and variant: one second of the clip at 30 fps

// One frame of the clip as the pipeline drew it.
struct Captured {
    std::vector<float> vertices, dot_positions, dot_sizes, lines;
    std::vector<uint8_t> front;  // the triangles' facing (the mesh pass's front faces)
    uint32_t dots = 0, line_count = 0;
};

struct Case {
    const char* name = "";
    stipple::Asset asset;
    std::unique_ptr<stipple::Pipeline> pipeline;
    int clip = 0;
    std::vector<Captured> frames;
    std::vector<double> frame_ms, floor_ms, replay_ms, depth_ms;  // per round, wall clock
    std::vector<double> frame_cpu, floor_cpu, replay_cpu;         // per round, process CPU
    std::vector<double> bin_ms;  // per round: the floor's mesh pass inside glDrawElements
    std::vector<double> replay_all_ms, replay_all_cpu;  // replay, every triangle to the GPU
    std::vector<double> frame_all_ms;                   // frame, every triangle to the GPU
    std::vector<double> occluder_ms;                    // frame, the occluder's depth pass
    std::vector<double> two_ms, two_occluder_ms;        // the same two with 2 threads
    stipple::ThreadPool two;                            // swapped into the pipeline for those
    std::vector<stipple::StageTimes> stages;            // per round, per frame
    frame_floor::Before before;  // the frame drawn the previous way (frame_floor_before.h)
};

bool bake_file(const std::string& path, uint32_t points, stipple::Asset* out) {
    stipple::bake::RawScene scene;
    if (!stipple::bake::import_scene(path, &scene).ok()) return false;
    stipple::bake::HierarchyConfig config;
    config.point_count = points;
    stipple::bake::PointHierarchy hierarchy;
    if (!stipple::bake::build_point_hierarchy(scene, config, &hierarchy, nullptr).ok())
        return false;
    constexpr double kOccluderRatio = 0.1;
    const std::vector<uint8_t> bytes = stipple::bake::encode_asset(
        scene, hierarchy, {}, {}, {}, {}, stipple::bake::bake_occluder(scene, kOccluderRatio));
    return stipple::load_asset_memory(bytes.data(), bytes.size(), out).ok();
}

// The horse with the generated skeleton of stipple-make-bend-rig (defaults, --up z).
bool bake_bent_horse(stipple::Asset* out) {
    namespace fs = std::filesystem;
    const fs::path gltf = fs::temp_directory_path() /
                          ("stipple_bench_horse_bend_" + std::to_string(::getpid()) + ".gltf");
    stipple::tools::BendRigOptions o;
    o.up_axis = 2;  // format::kUpZ
    stipple::tools::BendRigSummary summary;
    std::string error;
    const bool ok =
        stipple::tools::write_bend_rig(std::string(STIPPLE_SOURCE_DIR) + "/assets/Horse/horse.ply",
                                       gltf.string(), o, &summary, &error) &&
        bake_file(gltf.string(), 96966, out);
    if (!error.empty()) std::fprintf(stderr, "bench_frame_floor: %s\n", error.c_str());
    std::error_code ignored;
    fs::remove(gltf, ignored);
    return ok;
}

// Runs the clip's first kFrames frames at 30 fps once and keeps what each drew.
void capture(Case* c) {
    stipple::Pipeline& p = *c->pipeline;
    const uint32_t verts = c->asset.mesh.vertex_count;
    for (int k = 0; k < kFrames; ++k) {
        stipple::pipeline_frame(&p, c->clip, float(k) / 30.0f, nullptr);
        Captured f;
        f.vertices.assign(p.vertex_positions.get(), p.vertex_positions.get() + size_t(verts) * 3);
        f.dots = p.points_drawn;
        f.dot_positions.assign(p.draw_positions.get(), p.draw_positions.get() + size_t(f.dots) * 3);
        f.dot_sizes.assign(p.draw_sizes.get(), p.draw_sizes.get() + f.dots);
        f.line_count = p.lines_drawn;
        f.lines.assign(p.lines.get(), p.lines.get() + size_t(f.line_count) * 6);
        f.front.assign(p.triangle_front.get(),
                       p.triangle_front.get() + c->asset.mesh.triangle_count);
        c->frames.push_back(std::move(f));
    }
}

bool make_case(Case* c, const GlApi& gl, const char* clip_name) {
    stipple::FrameConfig config;
    config.width = kWidth;
    config.height = kHeight;
    config.relevance_update = true;
    c->pipeline = std::make_unique<stipple::Pipeline>();
    if (!stipple::pipeline_init(c->pipeline.get(), c->asset, gl, config).ok() ||
        !stipple::thread_pool_init(&c->two, 2).ok())
        return false;
    c->pipeline->renderer.occluder_enabled = false;  // on only in run_occluder
    c->clip = std::max(0, stipple::find_clip(c->asset, clip_name));
    capture(c);
    return true;
}

// ---- The bare program: a depth-only pass and round dots, nothing else. ----

const char* kDepthVs = R"(#version 300 es
layout(location = 0) in vec3 a_position;
uniform mat4 u_vp;
void main() {
    gl_Position = u_vp * vec4(a_position, 1.0);
    gl_Position.z += 0.002 * gl_Position.w;
}
)";
const char* kDepthFs = R"(#version 300 es
precision mediump float;
layout(location = 0) out vec4 o_color;
void main() { o_color = vec4(1.0); }
)";
const char* kDotVs = R"(#version 300 es
layout(location = 0) in vec3 a_position;
layout(location = 1) in float a_size;
uniform mat4 u_vp;
out float v_radius;
void main() {
    gl_Position = u_vp * vec4(a_position, 1.0);
    v_radius = 0.5 * a_size;
    gl_PointSize = a_size + 1.0;
}
)";
const char* kDotFs = R"(#version 300 es
precision mediump float;
in float v_radius;
layout(location = 0) out vec4 o_color;
void main() {
    float d = length(gl_PointCoord - vec2(0.5)) * (2.0 * v_radius + 1.0);
    float coverage = clamp(v_radius + 0.5 - d, 0.0, 1.0);
    if (coverage <= 0.0) discard;
    o_color = vec4(0.0, 0.0, 0.0, coverage);
}
)";

struct Bare {
    GLuint fbo = 0, colour = 0, depth = 0, depth_program = 0, dot_program = 0;
    GLint depth_vp = -1, dot_vp = -1;
    GLuint mesh_vao = 0, mesh_vbo = 0, mesh_ibo = 0, dot_vao = 0, dot_pos = 0, dot_size = 0;
    uint32_t index_count = 0;
};

GLuint array_buffer(const GlApi& gl, GLuint location, GLint components, size_t bytes) {
    GLuint b = 0;
    gl.GenBuffers(1, &b);
    gl.BindBuffer(GL_ARRAY_BUFFER, b);
    gl.BufferData(GL_ARRAY_BUFFER, GLsizeiptr(bytes), nullptr, GL_DYNAMIC_DRAW);
    gl.EnableVertexAttribArray(location);
    gl.VertexAttribPointer(location, components, GL_FLOAT, GL_FALSE, 0, nullptr);
    return b;
}

bool bare_init(Bare* b, const GlApi& gl, const stipple::Asset& a, uint32_t max_dots) {
    stipple::Status st;
    b->depth_program = stipple::link_gl_program(gl, kDepthVs, kDepthFs, "floor depth", &st);
    b->dot_program = stipple::link_gl_program(gl, kDotVs, kDotFs, "floor dots", &st);
    if (!b->depth_program || !b->dot_program) return false;
    b->depth_vp = gl.GetUniformLocation(b->depth_program, "u_vp");
    b->dot_vp = gl.GetUniformLocation(b->dot_program, "u_vp");
    gl.GenFramebuffers(1, &b->fbo);
    gl.BindFramebuffer(GL_FRAMEBUFFER, b->fbo);
    const GLenum formats[2] = {GL_RGBA8, GL_DEPTH_COMPONENT24};
    const GLenum attachments[2] = {GL_COLOR_ATTACHMENT0, GL_DEPTH_ATTACHMENT};
    GLuint* rbs[2] = {&b->colour, &b->depth};
    for (int i = 0; i < 2; ++i) {
        gl.GenRenderbuffers(1, rbs[i]);
        gl.BindRenderbuffer(GL_RENDERBUFFER, *rbs[i]);
        gl.RenderbufferStorage(GL_RENDERBUFFER, formats[i], kWidth, kHeight);
        gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, attachments[i], GL_RENDERBUFFER, *rbs[i]);
    }
    gl.GenVertexArrays(1, &b->mesh_vao);
    gl.BindVertexArray(b->mesh_vao);
    b->mesh_vbo = array_buffer(gl, 0, 3, size_t(a.mesh.vertex_count) * 12);
    gl.GenBuffers(1, &b->mesh_ibo);
    gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, b->mesh_ibo);
    b->index_count = a.mesh.triangle_count * 3;
    gl.BufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(size_t(b->index_count) * 4), a.mesh.indices,
                  GL_STATIC_DRAW);
    gl.GenVertexArrays(1, &b->dot_vao);
    gl.BindVertexArray(b->dot_vao);
    b->dot_pos = array_buffer(gl, 0, 3, size_t(max_dots) * 12);
    b->dot_size = array_buffer(gl, 1, 1, size_t(max_dots) * 4);
    gl.BindVertexArray(0);
    return gl.CheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE &&
           gl.GetError() == GL_NO_ERROR;
}

// The floor's frame; with `depth_only` the dots are left out. Returns the ms spent inside the
// mesh pass's glDrawElements (llvmpipe shades, sets up and bins the triangles in the caller's
// thread; its rasterizer threads fill the bins at the flush).
double bare_draw(const Bare& b, const GlApi& gl, const glm::mat4& vp, const Captured& f,
                 bool depth_only) {
    gl.BindFramebuffer(GL_FRAMEBUFFER, b.fbo);
    gl.Viewport(0, 0, kWidth, kHeight);
    gl.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl.DepthMask(GL_TRUE);
    gl.ClearColor(1.0f, 1.0f, 1.0f, 1.0f);
    gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    gl.ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);  // depth only
    gl.Enable(GL_DEPTH_TEST);
    gl.DepthFunc(GL_LESS);
    gl.Disable(GL_BLEND);
    gl.Enable(GL_CULL_FACE);
    gl.CullFace(GL_BACK);
    gl.FrontFace(GL_CCW);
    gl.UseProgram(b.depth_program);
    gl.UniformMatrix4fv(b.depth_vp, 1, GL_FALSE, &vp[0][0]);
    gl.BindVertexArray(b.mesh_vao);
    gl.BindBuffer(GL_ARRAY_BUFFER, b.mesh_vbo);
    gl.BufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(f.vertices.size() * 4), f.vertices.data());
    const auto start = std::chrono::steady_clock::now();
    gl.DrawElements(GL_TRIANGLES, GLsizei(b.index_count), GL_UNSIGNED_INT, nullptr);
    const double bin_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    gl.Disable(GL_CULL_FACE);
    if (depth_only) {
        gl.Finish();
        return bin_ms;
    }
    gl.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl.DepthMask(GL_FALSE);
    gl.DepthFunc(GL_LEQUAL);
    gl.Enable(GL_BLEND);
    gl.BlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    gl.UseProgram(b.dot_program);
    gl.UniformMatrix4fv(b.dot_vp, 1, GL_FALSE, &vp[0][0]);
    gl.BindVertexArray(b.dot_vao);
    gl.BindBuffer(GL_ARRAY_BUFFER, b.dot_pos);
    gl.BufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(size_t(f.dots) * 12), f.dot_positions.data());
    gl.BindBuffer(GL_ARRAY_BUFFER, b.dot_size);
    gl.BufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(size_t(f.dots) * 4), f.dot_sizes.data());
    gl.DrawArrays(GL_POINTS, 0, GLsizei(f.dots));
    gl.BindVertexArray(0);
    gl.Finish();
    return bin_ms;
}

// ---- Rounds ----

using Clock = std::chrono::steady_clock;

double ms_between(Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
}

// Process CPU time (every thread, llvmpipe's rasterizer threads included), in ms: the work a
// variant does, less sensitive than wall time to other processes on a busy machine.
double cpu_ms() {
    timespec ts{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return double(ts.tv_sec) * 1e3 + double(ts.tv_nsec) * 1e-6;
}

// pipeline_frame's classic draw after pipeline_update, with every triangle handed to the GPU
// (its back faces culled there, as before runtime/renderer_front.cpp).
void frame_all_triangles(stipple::Pipeline* p, int clip, float time) {
    stipple::AnimationState state;
    state.clip = clip;
    state.time = time;
    stipple::pipeline_update(p, state, nullptr);
    stipple::renderer_set_front_faces(&p->renderer, nullptr, p->view_projection);
    stipple::renderer_draw_fill(&p->renderer, p->view_projection, p->vertex_positions.get(),
                                p->vertex_normals.get(), p->asset->mesh.vertex_count);
    stipple::renderer_draw_line_sets(&p->renderer, p->view_projection, p->lines.get(),
                                     p->lines_drawn, nullptr, 0);
    stipple::renderer_draw_dots(&p->renderer, p->view_projection, p->draw_positions.get(),
                                p->draw_sizes.get(), nullptr, p->points_drawn);
    p->renderer.gl.Finish();
}

void run_frames(Case* c, bool all_triangles) {
    stipple::StageTimes t;
    const double cpu = cpu_ms();
    const Clock::time_point start = Clock::now();
    for (int k = 0; k < kFrames; ++k) {
        if (all_triangles)
            frame_all_triangles(c->pipeline.get(), c->clip, float(k) / 30.0f);
        else
            stipple::pipeline_frame(c->pipeline.get(), c->clip, float(k) / 30.0f, &t);
    }
    const double ms = ms_between(start, Clock::now()) / kFrames;
    if (all_triangles) {
        c->frame_all_ms.push_back(ms);
        return;
    }
    c->frame_ms.push_back(ms);
    c->frame_cpu.push_back((cpu_ms() - cpu) / kFrames);
    c->stages.push_back(t);
}

void run_before(Case* c) {
    const double cpu = cpu_ms();
    const Clock::time_point start = Clock::now();
    double draw = 0;
    for (int k = 0; k < kFrames; ++k)
        draw += frame_floor::frame_before(c->pipeline.get(), c->clip, float(k) / 30.0f);
    c->before.frame_ms.push_back(ms_between(start, Clock::now()) / kFrames);
    c->before.frame_cpu.push_back((cpu_ms() - cpu) / kFrames);
    c->before.draw_ms.push_back(draw / kFrames);
}

void run_occluder(Case* c, std::vector<double>* ms) {
    c->pipeline->renderer.occluder_enabled = true;
    const Clock::time_point start = Clock::now();
    for (int k = 0; k < kFrames; ++k)
        stipple::pipeline_frame(c->pipeline.get(), c->clip, float(k) / 30.0f, nullptr);
    ms->push_back(ms_between(start, Clock::now()) / kFrames);
    c->pipeline->renderer.occluder_enabled = false;
}

// The frame (or the occluder frame) with the two-thread pool in the pipeline.
void run_two_threads(Case* c, bool occluder) {
    std::swap(c->pipeline->pool, c->two);
    if (occluder) {
        run_occluder(c, &c->two_occluder_ms);
    } else {
        const Clock::time_point start = Clock::now();
        for (int k = 0; k < kFrames; ++k)
            stipple::pipeline_frame(c->pipeline.get(), c->clip, float(k) / 30.0f, nullptr);
        c->two_ms.push_back(ms_between(start, Clock::now()) / kFrames);
    }
    std::swap(c->pipeline->pool, c->two);
}

void run_floor(Case* c, const Bare& b) {
    const GlApi& gl = c->pipeline->renderer.gl;
    const double cpu = cpu_ms();
    const Clock::time_point start = Clock::now();
    double bin = 0;
    for (const Captured& f : c->frames)
        bin += bare_draw(b, gl, c->pipeline->view_projection, f, false);
    c->floor_ms.push_back(ms_between(start, Clock::now()) / kFrames);
    c->floor_cpu.push_back((cpu_ms() - cpu) / kFrames);
    c->bin_ms.push_back(bin / kFrames);
    const Clock::time_point depth_start = Clock::now();
    for (const Captured& f : c->frames) bare_draw(b, gl, c->pipeline->view_projection, f, true);
    c->depth_ms.push_back(ms_between(depth_start, Clock::now()) / kFrames);
}

// With `all_triangles` the mesh pass is handed every triangle and the GPU culls the back faces
// (as before runtime/renderer_front.cpp).
void run_replay(Case* c, bool all_triangles) {
    stipple::Pipeline& p = *c->pipeline;
    const double cpu = cpu_ms();
    const Clock::time_point start = Clock::now();
    for (const Captured& f : c->frames) {
        stipple::renderer_set_front_faces(&p.renderer, all_triangles ? nullptr : f.front.data(),
                                          p.view_projection);
        stipple::renderer_draw_fill(&p.renderer, p.view_projection, f.vertices.data(),
                                    p.vertex_normals.get(), c->asset.mesh.vertex_count);
        stipple::renderer_draw_line_sets(&p.renderer, p.view_projection, f.lines.data(),
                                         f.line_count, nullptr, 0);
        stipple::renderer_draw_dots(&p.renderer, p.view_projection, f.dot_positions.data(),
                                    f.dot_sizes.data(), nullptr, f.dots);
        p.renderer.gl.Finish();
    }
    (all_triangles ? c->replay_all_ms : c->replay_ms)
        .push_back(ms_between(start, Clock::now()) / kFrames);
    (all_triangles ? c->replay_all_cpu : c->replay_cpu).push_back((cpu_ms() - cpu) / kFrames);
}

double minimum(std::vector<double> v) {
    return *std::min_element(v.begin(), v.end());
}
double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

// Median over rounds of one stage's ms per frame.
double stage_median(const Case& c, double stipple::StageTimes::*field) {
    std::vector<double> v;
    for (const stipple::StageTimes& t : c.stages) v.push_back(t.*field / kFrames);
    return median(v);
}

std::string min_median(const std::vector<double>& v) {
    char text[64];
    std::snprintf(text, sizeof(text), "%.2f / %.2f", minimum(v), median(v));
    return text;
}

void report(const Case& c) {
    double dots = 0;
    for (const Captured& f : c.frames) dots += f.dots;
    const double fm = median(c.frame_ms), lm = median(c.floor_ms);
    std::printf("| %s | %u | %u | %.0f | %s | %s | %s | %s | %s | %.2f / %.2f | %.0f |\n", c.name,
                c.asset.points.point_count, c.asset.mesh.triangle_count, dots / kFrames,
                min_median(c.frame_ms).c_str(), min_median(c.frame_all_ms).c_str(),
                min_median(c.floor_ms).c_str(), min_median(c.replay_ms).c_str(),
                min_median(c.replay_all_ms).c_str(), minimum(c.frame_ms) / minimum(c.floor_ms),
                fm / lm, 1000.0 / fm);
}

void report_cpu(const Case& c) {
    std::printf("| %s | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f |\n", c.name,
                minimum(c.frame_cpu), minimum(c.floor_cpu), minimum(c.replay_cpu),
                minimum(c.replay_all_cpu), minimum(c.frame_cpu) / minimum(c.floor_cpu),
                minimum(c.depth_ms), minimum(c.bin_ms));
}

void report_stages(const Case& c) {
    using T = stipple::StageTimes;
    std::printf("| %s | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f |\n", c.name,
                stage_median(c, &T::sample), stage_median(c, &T::skin), stage_median(c, &T::select),
                stage_median(c, &T::place), stage_median(c, &T::relevance),
                stage_median(c, &T::refine), stage_median(c, &T::size),
                stage_median(c, &T::silhouette), stage_median(c, &T::draw));
}

void report_occluder(const Case& c) {
    std::printf("| %s | %u of %u | %.4g | %s | %s | %s | %.2f / %.2f | %.2f / %.2f | %.0f |\n",
                c.name, c.asset.occluder_triangle_count, c.asset.mesh.triangle_count,
                double(c.asset.occluder_deviation), min_median(c.frame_ms).c_str(),
                min_median(c.occluder_ms).c_str(), min_median(c.floor_ms).c_str(),
                minimum(c.occluder_ms) / minimum(c.frame_ms),
                median(c.occluder_ms) / median(c.frame_ms),
                minimum(c.occluder_ms) / minimum(c.floor_ms),
                median(c.occluder_ms) / median(c.floor_ms), 1000.0 / median(c.occluder_ms));
}

void report_threads(const Case& c) {
    std::printf("| %s | %s | %s | %s | %s | %.2f / %.2f | %.0f | %.0f |\n", c.name,
                min_median(c.frame_ms).c_str(), min_median(c.two_ms).c_str(),
                min_median(c.two_occluder_ms).c_str(), min_median(c.floor_ms).c_str(),
                minimum(c.two_ms) / minimum(c.floor_ms), median(c.two_ms) / median(c.floor_ms),
                1000.0 / median(c.two_ms), 1000.0 / median(c.two_occluder_ms));
}

// a[r] / b[r] per round: a variant over the floor measured in the same round (the floor moves
// by a third between rounds on this machine; a ratio of two minima can pair different rounds).
std::vector<double> per_round(const std::vector<double>& a, const std::vector<double>& b) {
    std::vector<double> r;
    for (size_t k = 0; k < a.size() && k < b.size(); ++k) r.push_back(a[k] / b[k]);
    return r;
}

void report_rounds(const Case& c) {
    std::printf("| %s | %s | %s | %s | %s |\n", c.name,
                min_median(per_round(c.frame_ms, c.floor_ms)).c_str(),
                min_median(per_round(c.occluder_ms, c.floor_ms)).c_str(),
                min_median(per_round(c.two_ms, c.floor_ms)).c_str(),
                min_median(per_round(c.two_occluder_ms, c.floor_ms)).c_str());
}

void print_tables(const Case (&cases)[2], int rounds) {
    std::printf(
        "1280x720, %d rounds of %d frames each, ms per frame (min / median over rounds)\n\n",
        rounds, kFrames);
    std::printf(
        "| asset | points | triangles | dots drawn | frame | frame, GPU culls | floor | "
        "renderer replay | replay, GPU culls | frame / floor (min, median) | fps (median) |\n");
    std::printf("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    for (const Case& c : cases) report(c);
    std::printf(
        "\nProcess CPU time (all threads), ms per frame, min over rounds; and the floor's\n"
        "depth pass alone (wall) and the part of it inside glDrawElements (wall):\n\n");
    std::printf(
        "| asset | frame | floor | renderer replay | replay, GPU culls | frame / floor | "
        "floor depth pass | in glDrawElements |\n"
        "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    for (const Case& c : cases) report_cpu(c);
    std::printf("\nStage times, ms per frame (median over rounds):\n\n");
    std::printf(
        "| asset | sample | skin | select | place | relevance | refine | size | silhouette | "
        "draw |\n| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    for (const Case& c : cases) report_stages(c);
    std::printf("\nThe occluder's depth pass (ms per frame, min / median over rounds):\n\n");
    std::printf(
        "| asset | occluder triangles | deviation | frame | frame, occluder | floor | "
        "occluder / frame (min, median) | occluder / floor (min, median) | fps, occluder |\n"
        "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    for (const Case& c : cases) report_occluder(c);
    std::printf(
        "\nTwo threads: the point part on the pool's worker beside the mesh pass (ms per frame,"
        "\nmin / median over rounds):\n\n"
        "| asset | frame, 1 thread | frame, 2 threads | occluder, 2 threads | floor | "
        "2 threads / floor (min, median) | fps, 2 threads | fps, occluder, 2 threads |\n"
        "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    for (const Case& c : cases) report_threads(c);
    std::printf(
        "\nOver the floor round by round (each variant / the floor of the same round; min / "
        "median\nover rounds):\n\n"
        "| asset | frame | occluder | 2 threads | occluder, 2 threads |\n"
        "| --- | ---: | ---: | ---: | ---: |\n");
    for (const Case& c : cases) report_rounds(c);
}

// `--rounds N` (at least 1), `--raster-threads N` (platform/headless_context.h; -1: Mesa's).
int option(int argc, char** argv, const char* name, int fallback) {
    for (int i = 1; i + 1 < argc; ++i)
        if (std::strcmp(argv[i], name) == 0) return std::atoi(argv[i + 1]);
    return fallback;
}

}  // namespace

int main(int argc, char** argv) {
    const int rounds = std::max(1, option(argc, argv, "--rounds", 5));
    stipple::platform::HeadlessConfig hc;
    hc.width = kWidth;
    hc.height = kHeight;
    hc.raster_threads = option(argc, argv, "--raster-threads", -1);
    stipple::platform::HeadlessContext context;
    GlApi gl;
    if (!stipple::platform::create_headless_context(hc, &context).ok() ||
        !stipple::load_gl_api(stipple::platform::proc_loader(context), &gl).ok()) {
        std::fprintf(stderr, "bench_frame_floor: no headless GL context\n");
        return 1;
    }
    Case cases[2];
    cases[0].name = "CesiumMan (walk)";
    cases[1].name = "horse (bend)";
    if (!bake_file(std::string(STIPPLE_SOURCE_DIR) + "/assets/CesiumMan/CesiumMan.glb", 100000,
                   &cases[0].asset) ||
        !bake_bent_horse(&cases[1].asset) || !make_case(&cases[0], gl, "") ||
        !make_case(&cases[1], gl, "bend")) {
        std::fprintf(stderr, "bench_frame_floor: cannot bake or set up the assets\n");
        return 1;
    }
    Bare bare[2];
    for (int i = 0; i < 2; ++i)
        if (!bare_init(&bare[i], gl, cases[i].asset, cases[i].pipeline->point_capacity)) {
            std::fprintf(stderr, "bench_frame_floor: cannot create the bare program\n");
            return 1;
        }
    for (int r = 0; r < rounds; ++r)
        for (int i = 0; i < 2; ++i) {  // the order of the nine turns every round
            for (int v = 0; v < 9; ++v) {
                const int which = (v + r) % 9;
                if (which <= 1) run_frames(&cases[i], which == 1);
                if (which == 2) run_floor(&cases[i], bare[i]);
                if (which == 3 || which == 4) run_replay(&cases[i], which == 4);
                if (which == 5) run_occluder(&cases[i], &cases[i].occluder_ms);
                if (which == 6) run_before(&cases[i]);
                if (which == 7 || which == 8) run_two_threads(&cases[i], which == 8);
            }
        }
    print_tables(cases, rounds);
    frame_floor::report_before_header();
    for (const Case& c : cases)
        frame_floor::report_before(c.name, c.before, c.frame_ms, c.frame_cpu, c.floor_ms,
                                   stage_median(c, &stipple::StageTimes::draw));
    for (Case& c : cases) {
        stipple::pipeline_destroy(c.pipeline.get());
        stipple::thread_pool_destroy(&c.two);
    }
    return 0;
}
