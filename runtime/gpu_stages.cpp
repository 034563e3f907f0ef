#include "runtime/gpu_stages.h"

#include <cstring>

#include "runtime/frame_pipeline.h"
#include "runtime/frame_pose.h"
#include "runtime/gl_program.h"
#include "runtime/silhouette.h"
#include "runtime/stage_clock.h"

namespace stipple {

namespace {

constexpr uint32_t kRowTexels = 1u << kGpuRowShift;

const char* kFeedbackVs =
#include "runtime/gpu_stages_shader.inc"
    ;

// Rasterisation is off during the pass; GLES 3.0 still wants a fragment shader to link.
const char* kFeedbackFs = R"(#version 300 es
precision mediump float;
out vec4 o_color;
void main() { o_color = vec4(0.0); }
)";

uint32_t rows_for(uint32_t texels) {
    return texels == 0 ? 1 : (texels + kRowTexels - 1) / kRowTexels;
}

GLuint compile(const GlApi& gl, GLenum type, const char* source, Status* error) {
    GLuint s = gl.CreateShader(type);
    gl.ShaderSource(s, 1, &source, nullptr);
    gl.CompileShader(s);
    GLint ok = 0;
    gl.GetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (ok) return s;
    char log[512] = {};
    gl.GetShaderInfoLog(s, sizeof(log), nullptr, log);
    *error = make_status(StatusCode::gl_error, "gpu stages shader compile failed: %s", log);
    gl.DeleteShader(s);
    return 0;
}

// gl_program.h's link, with the transform feedback output declared before linking.
GLuint link_feedback_program(const GlApi& gl, Status* error) {
    const GLuint v = compile(gl, GL_VERTEX_SHADER, kFeedbackVs, error);
    const GLuint f = v ? compile(gl, GL_FRAGMENT_SHADER, kFeedbackFs, error) : 0;
    if (!f) {
        if (v) gl.DeleteShader(v);
        return 0;
    }
    const GLuint p = gl.CreateProgram();
    gl.AttachShader(p, v);
    gl.AttachShader(p, f);
    const char* varyings[1] = {"v_dot"};
    gl.TransformFeedbackVaryings(p, 1, varyings, GL_INTERLEAVED_ATTRIBS);
    gl.LinkProgram(p);
    gl.DeleteShader(v);
    gl.DeleteShader(f);
    GLint ok = 0;
    gl.GetProgramiv(p, GL_LINK_STATUS, &ok);
    if (ok) return p;
    char log[512] = {};
    gl.GetProgramInfoLog(p, sizeof(log), nullptr, log);
    *error = make_status(StatusCode::gl_error, "gpu stages program link failed: %s", log);
    gl.DeleteProgram(p);
    return 0;
}

// A kRowTexels-wide texture of `texels` texels (storage only), nearest, no mipmaps.
GLuint data_texture(const GlApi& gl, GLenum internal, GLenum format, GLenum type, uint32_t texels) {
    GLuint t = 0;
    gl.GenTextures(1, &t);
    gl.BindTexture(GL_TEXTURE_2D, t);
    gl.TexImage2D(GL_TEXTURE_2D, 0, GLint(internal), GLsizei(kRowTexels), GLsizei(rows_for(texels)),
                  0, format, type, nullptr);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return t;
}

// Uploads `texels` texels (texel_bytes each, tightly packed) into the bound texture from its
// first texel on: the full rows in one call, the last partial row in another.
void upload_texels(const GlApi& gl, GLenum format, GLenum type, const void* data, uint32_t texels,
                   size_t texel_bytes) {
    const uint32_t full = texels / kRowTexels, rest = texels % kRowTexels;
    const uint8_t* bytes = static_cast<const uint8_t*>(data);
    if (full > 0)
        gl.TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, GLsizei(kRowTexels), GLsizei(full), format, type,
                         bytes);
    if (rest > 0)
        gl.TexSubImage2D(GL_TEXTURE_2D, 0, 0, GLint(full), GLsizei(rest), 1, format, type,
                         bytes + size_t(full) * kRowTexels * texel_bytes);
}

// The point texel (thesis Alg. 6.3's inputs): host vertices a, b, c packed 21 bits each into
// two words, then the bits of u and v.
void pack_point(const Asset& asset, uint32_t i, uint32_t* t) {
    const PointsView& pts = asset.points;
    const uint32_t* tri = asset.mesh.indices + size_t(pts.host_triangle[i]) * 3;
    t[0] = tri[0] | (tri[1] << 21);
    t[1] = (tri[1] >> 11) | (tri[2] << 10);
    std::memcpy(&t[2], &pts.bary_u[i], 4);
    std::memcpy(&t[3], &pts.bary_v[i], 4);
}

// Fills the bound RGBA32UI texture with `count` point texels, one row at a time through a
// block on the stack: texel k is point k, or with `list` point list[k] (the neighbour lists).
void upload_point_texels(const GlApi& gl, const Asset& asset, uint32_t count,
                         const uint32_t* list) {
    uint32_t row[kRowTexels * 4];
    for (uint32_t first = 0; first < count; first += kRowTexels) {
        const uint32_t n = count - first < kRowTexels ? count - first : kRowTexels;
        for (uint32_t k = 0; k < n; ++k)
            pack_point(asset, list ? list[first + k] : first + k, row + size_t(k) * 4);
        gl.TexSubImage2D(GL_TEXTURE_2D, 0, 0, GLint(first / kRowTexels), GLsizei(n), 1,
                         GL_RGBA_INTEGER, GL_UNSIGNED_INT, row);
    }
}

GLuint static_buffer(const GlApi& gl, const void* data, size_t bytes) {
    GLuint b = 0;
    gl.GenBuffers(1, &b);
    gl.BindBuffer(GL_ARRAY_BUFFER, b);
    gl.BufferData(GL_ARRAY_BUFFER, GLsizeiptr(bytes), data, GL_STATIC_DRAW);
    return b;
}

// The transform feedback pass's per-point attributes (gpu_stages_shader.inc's locations).
void create_attributes(GpuStages* g, const Asset& asset, const float* radius_scale,
                       const float* rest_radius, const uint8_t* double_sided) {
    const GlApi& gl = g->gl;
    const size_t n = g->point_count;
    gl.GenVertexArrays(1, &g->feedback_vao);
    gl.BindVertexArray(g->feedback_vao);
    g->scale_vbo = static_buffer(gl, radius_scale, n * 4);
    gl.EnableVertexAttribArray(0);
    gl.VertexAttribPointer(0, 1, GL_FLOAT, GL_FALSE, 0, nullptr);
    g->rest_vbo = static_buffer(gl, rest_radius, n * 4);
    gl.EnableVertexAttribArray(1);
    gl.VertexAttribPointer(1, 1, GL_FLOAT, GL_FALSE, 0, nullptr);
    // Point i's list is [offsets[i], offsets[i + 1]): one buffer read at two offsets.
    g->offsets_vbo = static_buffer(gl, asset.points.neighbour_offsets, (n + 1) * 4);
    gl.EnableVertexAttribArray(2);
    gl.VertexAttribIPointer(2, 1, GL_UNSIGNED_INT, 0, nullptr);
    gl.EnableVertexAttribArray(3);
    gl.VertexAttribIPointer(3, 1, GL_UNSIGNED_INT, 0, reinterpret_cast<const void*>(size_t(4)));
    if (double_sided) {  // else the attribute's default value, 0: single-sided
        g->sides_vbo = static_buffer(gl, double_sided, n);
        gl.EnableVertexAttribArray(4);
        gl.VertexAttribPointer(4, 1, GL_UNSIGNED_BYTE, GL_FALSE, 0, nullptr);
    }
    gl.BindVertexArray(0);
}

// The output buffer, and the vertex array the dots pass reads it through.
void create_dots(GpuStages* g) {
    const GlApi& gl = g->gl;
    gl.GenBuffers(1, &g->dots);
    gl.BindBuffer(GL_ARRAY_BUFFER, g->dots);
    gl.BufferData(GL_ARRAY_BUFFER, GLsizeiptr(size_t(g->point_count) * 16), nullptr,
                  GL_DYNAMIC_COPY);
    gl.GenVertexArrays(1, &g->draw_vao);
    gl.BindVertexArray(g->draw_vao);
    gl.EnableVertexAttribArray(0);
    gl.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 16, nullptr);
    gl.EnableVertexAttribArray(1);
    gl.VertexAttribPointer(1, 1, GL_FLOAT, GL_FALSE, 16, reinterpret_cast<const void*>(size_t(12)));
    gl.BindVertexArray(0);
    gl.BindBuffer(GL_ARRAY_BUFFER, 0);
}

void find_uniforms(GpuStages* g) {
    const GlApi& gl = g->gl;
    const GLuint p = g->program;
    gl_uniform_locations(gl, p,
                         {{&g->u_view_projection, "u_view_projection"},
                          {&g->u_eye_focal, "u_eye_focal"},
                          {&g->u_size, "u_size"},
                          {&g->u_lights, "u_lights"},
                          {&g->u_light_count, "u_light_count"},
                          {&g->u_ambient, "u_ambient"},
                          {&g->u_ink, "u_ink"}});
    gl.UseProgram(p);
    const char* samplers[4] = {"u_vertex_positions", "u_vertex_normals", "u_points",
                               "u_neighbours"};
    for (int unit = 0; unit < 4; ++unit)
        gl.Uniform1i(gl.GetUniformLocation(p, samplers[unit]), unit);
    gl.UseProgram(0);
}

Status check_counts(const GlApi& gl, const Asset& asset) {
    GLint max_size = 0;
    gl.GetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    const uint32_t most = asset.points.neighbour_count > asset.points.point_count
                              ? asset.points.neighbour_count
                              : asset.points.point_count;
    if (asset.mesh.vertex_count > kGpuMaxVertices)
        return make_status(StatusCode::invalid_argument,
                           "gpu path: %u vertices, at most %u (packed host vertex indices)",
                           asset.mesh.vertex_count, kGpuMaxVertices);
    if (rows_for(most) > uint32_t(max_size) ||
        rows_for(asset.mesh.vertex_count) > uint32_t(max_size))
        return make_status(StatusCode::invalid_argument,
                           "gpu path: %u points or neighbours need %u texture rows, GL has %d",
                           most, rows_for(most), max_size);
    return {};
}

}  // namespace

Status gpu_stages_init(GpuStages* g, const GlApi& gl, const Asset& asset, const float* radius_scale,
                       const float* rest_radius, const uint8_t* double_sided) {
    *g = GpuStages();
    g->gl = gl;
    g->point_count = asset.points.point_count;
    g->vertex_count = asset.mesh.vertex_count;
    Status st = check_counts(gl, asset);
    if (!st.ok()) return st;
    g->program = link_feedback_program(gl, &st);
    if (!g->program) return st;
    find_uniforms(g);
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    g->vertex_positions = data_texture(gl, GL_RGB32F, GL_RGB, GL_FLOAT, g->vertex_count);
    g->vertex_normals = data_texture(gl, GL_RGB32F, GL_RGB, GL_FLOAT, g->vertex_count);
    g->points = data_texture(gl, GL_RGBA32UI, GL_RGBA_INTEGER, GL_UNSIGNED_INT, g->point_count);
    upload_point_texels(gl, asset, g->point_count, nullptr);
    g->neighbours = data_texture(gl, GL_RGBA32UI, GL_RGBA_INTEGER, GL_UNSIGNED_INT,
                                 asset.points.neighbour_count);
    upload_point_texels(gl, asset, asset.points.neighbour_count, asset.points.neighbours);
    gl.BindTexture(GL_TEXTURE_2D, 0);
    create_attributes(g, asset, radius_scale, rest_radius, double_sided);
    create_dots(g);
    if (gl.GetError() != GL_NO_ERROR) {
        gpu_stages_destroy(g);
        return make_status(StatusCode::gl_error, "GL error while creating the gpu stages");
    }
    return {};
}

namespace {

// The frame's settings as the shader's uniforms (SizeParams, the ink table of this frame).
void set_uniforms(const GpuStages& g, const SizeParams& params, bool relevance_update) {
    const GlApi& gl = g.gl;
    gl.UniformMatrix4fv(g.u_view_projection, 1, GL_FALSE, &params.view_projection[0][0]);
    gl.Uniform4f(g.u_eye_focal, params.eye.x, params.eye.y, params.eye.z, focal_pixels(params));
    gl.Uniform4f(g.u_size, params.max_point_size, params.smooth_slope,
                 relevance_update ? 1.0f : 0.0f, kRegionPerRadiusSquared);
    float lights[4 * kMaxLights] = {};
    const int count = params.light_count < kMaxLights ? params.light_count : kMaxLights;
    for (int k = 0; k < count; ++k) {
        lights[k * 4] = params.light_direction[k].x;
        lights[k * 4 + 1] = params.light_direction[k].y;
        lights[k * 4 + 2] = params.light_direction[k].z;
        lights[k * 4 + 3] = params.light_intensity[k];
    }
    gl.Uniform4fv(g.u_lights, kMaxLights, lights);
    gl.Uniform1i(g.u_light_count, count);
    gl.Uniform1f(g.u_ambient, params.ambient);
    const InkTable table(params);
    gl.Uniform1fv(g.u_ink, InkTable::kSteps + 1, table.ink);
}

void bind_texture(const GlApi& gl, int unit, GLuint texture) {
    gl.ActiveTexture(GLenum(GL_TEXTURE0 + unit));
    gl.BindTexture(GL_TEXTURE_2D, texture);
}

}  // namespace

void gpu_stages_run(GpuStages* g, const float* vertex_positions, const float* vertex_normals,
                    const SizeParams& params, bool relevance_update) {
    const GlApi& gl = g->gl;
    if (g->point_count == 0) return;
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    bind_texture(gl, 0, g->vertex_positions);
    upload_texels(gl, GL_RGB, GL_FLOAT, vertex_positions, g->vertex_count, 12);
    bind_texture(gl, 1, g->vertex_normals);
    upload_texels(gl, GL_RGB, GL_FLOAT, vertex_normals, g->vertex_count, 12);
    bind_texture(gl, 2, g->points);
    bind_texture(gl, 3, g->neighbours);
    gl.UseProgram(g->program);
    set_uniforms(*g, params, relevance_update);
    gl.BindVertexArray(g->feedback_vao);
    gl.Enable(GL_RASTERIZER_DISCARD);
    gl.BindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, g->dots);
    gl.BeginTransformFeedback(GL_POINTS);
    gl.DrawArrays(GL_POINTS, 0, GLsizei(g->point_count));
    gl.EndTransformFeedback();
    gl.BindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, 0);
    gl.Disable(GL_RASTERIZER_DISCARD);
    gl.BindVertexArray(0);
    for (int unit = 3; unit >= 0; --unit) bind_texture(gl, unit, 0);  // leaves unit 0 active
}

bool gpu_stages_read_dots(const GpuStages& g, float* out) {
    const GlApi& gl = g.gl;
    const size_t bytes = size_t(g.point_count) * 16;
    if (bytes == 0) return true;
    gl.BindBuffer(GL_ARRAY_BUFFER, g.dots);
    const void* mapped = gl.MapBufferRange(GL_ARRAY_BUFFER, 0, GLsizeiptr(bytes), GL_MAP_READ_BIT);
    if (mapped) std::memcpy(out, mapped, bytes);
    const bool ok = mapped && gl.UnmapBuffer(GL_ARRAY_BUFFER) == GL_TRUE;
    gl.BindBuffer(GL_ARRAY_BUFFER, 0);
    return ok;
}

void gpu_stages_destroy(GpuStages* g) {
    const GlApi& gl = g->gl;
    if (!gl.DeleteBuffers) return;
    const GLuint buffers[5] = {g->scale_vbo, g->rest_vbo, g->offsets_vbo, g->sides_vbo, g->dots};
    gl.DeleteBuffers(5, buffers);
    const GLuint vaos[2] = {g->feedback_vao, g->draw_vao};
    gl.DeleteVertexArrays(2, vaos);
    const GLuint textures[4] = {g->vertex_positions, g->vertex_normals, g->points, g->neighbours};
    gl.DeleteTextures(4, textures);
    if (g->program) gl.DeleteProgram(g->program);
    *g = GpuStages();
}

Status gpu_path_init(Pipeline* p) {
    const Asset& a = *p->asset;
    // Strokes read the points' radii (their LOD cut): the rest-pose ones on this path.
    std::memcpy(p->radius.get(), p->rest_radius.get(), size_t(a.points.point_count) * 4);
    return gpu_stages_init(&p->gpu, p->renderer.gl, a, p->radius_scale.get(), p->rest_radius.get(),
                           p->point_double_sided.get());
}

void gpu_path_update(Pipeline* p, StageTimes* t) {
    const Asset& a = *p->asset;
    StageClock::time_point clock = StageClock::now();
    p->refined_count = 0;  // the refinement needs the points on the CPU: not on this path
    p->refinement_stats = RefinementStats();
    p->points_drawn = a.points.point_count;  // submitted; the dots shader culls size 0
    p->dots_coloured = false;                // dots take the ink colour on this path
    pipeline_line_and_stroke_stages(p, t, &clock);
}

void gpu_path_draw_points(Pipeline* p) {
    gpu_stages_run(&p->gpu, p->vertex_positions.get(), p->vertex_normals.get(), p->size_params,
                   p->config.relevance_update);
    renderer_draw_points_from(&p->renderer, p->view_projection, p->gpu.draw_vao,
                              p->gpu.point_count);
}

}  // namespace stipple
