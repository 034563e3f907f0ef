#include "tools/paintstroke_oit.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>

#include "runtime/gl_program.h"

namespace stipple::bench {

namespace {

constexpr int kMaxLayers = 64;

// runtime/stroke_renderer.cpp's shaders, with the peel test added: a fragment at or in front
// of the previous layer's depth at its pixel is discarded.
const char* kPeelVs = R"(#version 300 es
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec4 a_colour;
layout(location = 3) in vec2 a_reflectance_shade;
uniform mat4 u_projection;
out vec3 v_position;
out vec3 v_normal;
out vec4 v_colour;
out vec2 v_reflectance_shade;
void main() {
    v_position = a_position;
    v_normal = a_normal;
    v_colour = a_colour;
    v_reflectance_shade = a_reflectance_shade;
    gl_Position = u_projection * vec4(a_position, 1.0);
}
)";

const char* kPeelFs = R"(#version 300 es
precision highp float;
in vec3 v_position;
in vec3 v_normal;
in vec4 v_colour;
in vec2 v_reflectance_shade;
uniform vec4 u_light;
uniform float u_ambient;
uniform float u_diffuse;
uniform float u_shininess;
uniform highp sampler2D u_prev;
layout(location = 0) out vec4 o_color;
void main() {
    if (gl_FragCoord.z <= texelFetch(u_prev, ivec2(gl_FragCoord.xy), 0).r) discard;
    float len = length(v_normal);
    vec3 n = len > 0.0 ? v_normal / len : vec3(0.0, 0.0, 1.0);
    vec3 l = u_light.xyz;
    float plen = length(v_position);
    vec3 v = plen > 0.0 ? -v_position / plen : vec3(0.0, 0.0, 1.0);
    vec3 h = normalize(l + v + vec3(0.0, 0.0, 1e-6));
    float lambert = max(dot(n, l), 0.0);
    float spec = lambert > 0.0 ? pow(max(dot(n, h), 0.0), u_shininess) : 0.0;
    vec3 rgb = v_colour.rgb * (u_ambient + u_diffuse * v_reflectance_shade.y * lambert) +
               vec3(v_reflectance_shade.x * spec);
    o_color = vec4(rgb, v_colour.a);
}
)";

struct Peeler {
    GLuint program = 0, fbo = 0, colour = 0, depth[2] = {};
    GLint u_projection = -1, u_light = -1, u_ambient = -1, u_diffuse = -1, u_shininess = -1;
    GLint u_prev = -1;
};

bool peeler_init(const GlApi& gl, int w, int h, Peeler* p) {
    Status error;
    p->program = link_gl_program(gl, kPeelVs, kPeelFs, "peel", &error);
    if (!p->program) {
        std::fprintf(stderr, "%s\n", error.message);
        return false;
    }
    const char* names[6] = {"u_projection", "u_light",     "u_ambient",
                            "u_diffuse",    "u_shininess", "u_prev"};
    GLint* locations[6] = {&p->u_projection, &p->u_light,     &p->u_ambient,
                           &p->u_diffuse,    &p->u_shininess, &p->u_prev};
    for (int i = 0; i < 6; ++i) *locations[i] = gl.GetUniformLocation(p->program, names[i]);
    gl.GenFramebuffers(1, &p->fbo);
    gl.BindFramebuffer(GL_FRAMEBUFFER, p->fbo);
    gl.GenRenderbuffers(1, &p->colour);
    gl.BindRenderbuffer(GL_RENDERBUFFER, p->colour);
    gl.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, w, h);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, p->colour);
    gl.GenTextures(2, p->depth);
    for (GLuint t : p->depth) {
        gl.BindTexture(GL_TEXTURE_2D, t);
        gl.TexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT32F, w, h, 0, GL_DEPTH_COMPONENT,
                      GL_FLOAT, nullptr);
        gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_NONE);
    }
    gl.BindTexture(GL_TEXTURE_2D, 0);
    gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, p->depth[0], 0);
    return gl.CheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
}

void peeler_destroy(const GlApi& gl, Peeler* p) {
    gl.DeleteProgram(p->program);
    gl.DeleteFramebuffers(1, &p->fbo);
    gl.DeleteRenderbuffers(1, &p->colour);
    gl.DeleteTextures(2, p->depth);
}

// Uploads the mesh into the renderer's buffers (clamped to their capacities).
uint32_t upload(const GlApi& gl, const StrokeRenderer& r, const StrokeMesh& m) {
    const uint32_t nv = std::min(m.vertex_count, r.config.max_vertices);
    uint32_t ni = std::min(m.index_count, r.config.max_indices);
    ni -= ni % 3;
    gl.BindVertexArray(r.vao);
    gl.BindBuffer(GL_ARRAY_BUFFER, r.vbo);
    gl.BufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(nv * sizeof(StrokeVertex)), m.vertices);
    gl.BufferSubData(GL_ELEMENT_ARRAY_BUFFER, 0, GLsizeiptr(ni * sizeof(uint32_t)), m.indices);
    return ni;
}

// Sets the peeling program's uniforms for `view` (the light and the stroke defaults).
void use_program(const GlApi& gl, const Peeler& p, const View& view) {
    gl.UseProgram(p.program);
    gl.UniformMatrix4fv(p.u_projection, 1, GL_FALSE, &view.projection[0][0]);
    gl.Uniform4f(p.u_light, view.light_eye.x, view.light_eye.y, view.light_eye.z, 0.0f);
    const StrokeLighting lighting;
    gl.Uniform1f(p.u_ambient, lighting.ambient);
    gl.Uniform1f(p.u_diffuse, lighting.diffuse);
    gl.Uniform1f(p.u_shininess, lighting.specular_exponent);
    gl.Uniform1i(p.u_prev, 0);
    gl.ActiveTexture(GL_TEXTURE0);
}

// The back-to-front order without depth test or writes: every fragment blended in segment
// order (the peeling program, with a previous-layer depth of 0 everywhere, discards nothing).
void draw_without_depth(const GlApi& gl, const Peeler& p, const StrokeRenderer& r, const View& view,
                        const StrokeMesh& m, const uint32_t* sorted, const Target& t,
                        std::vector<uint8_t>* out) {
    gl.BindFramebuffer(GL_FRAMEBUFFER, p.fbo);
    gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, p.depth[1], 0);
    const float zero = 0.0f;
    gl.DepthMask(GL_TRUE);
    gl.ClearBufferfv(GL_DEPTH, 0, &zero);
    gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, p.depth[0], 0);
    target_clear(gl, t);
    StrokeMesh ordered = m;
    ordered.indices = const_cast<uint32_t*>(sorted);
    const uint32_t ni = upload(gl, r, ordered);
    use_program(gl, p, view);
    gl.BindTexture(GL_TEXTURE_2D, p.depth[1]);
    gl.Disable(GL_DEPTH_TEST);
    gl.DepthMask(GL_FALSE);
    gl.Enable(GL_BLEND);
    gl.BlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    gl.DrawElements(GL_TRIANGLES, GLsizei(ni), GL_UNSIGNED_INT, nullptr);
    gl.BindTexture(GL_TEXTURE_2D, 0);
    gl.BindVertexArray(0);
    gl.DepthMask(GL_TRUE);
    target_read(gl, t, out->data());
}

// Peels every layer of the uploaded mesh and composites them front to back ("under") into
// `out` (bottom-up RGBA8, black background). Returns the number of non-empty layers.
int peel(const GlApi& gl, const Peeler& p, const View& view, uint32_t index_count, int w, int h,
         std::vector<uint8_t>* out) {
    const size_t n = size_t(w) * size_t(h);
    std::vector<float> acc(n * 4, 0.0f);
    std::vector<uint8_t> layer(n * 4);
    gl.BindFramebuffer(GL_FRAMEBUFFER, p.fbo);
    gl.Viewport(0, 0, w, h);
    gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, p.depth[1], 0);
    const float zero = 0.0f, one = 1.0f, clear[4] = {0, 0, 0, 0};
    gl.DepthMask(GL_TRUE);
    gl.ClearBufferfv(GL_DEPTH, 0, &zero);  // nothing is in front of the first layer
    use_program(gl, p, view);
    gl.Enable(GL_DEPTH_TEST);
    gl.DepthFunc(GL_LESS);
    gl.Disable(GL_BLEND);
    int layers = 0;
    for (; layers < kMaxLayers; ++layers) {
        const int cur = layers % 2;
        gl.BindTexture(GL_TEXTURE_2D, 0);
        gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, p.depth[cur],
                                0);
        gl.ClearBufferfv(GL_COLOR, 0, clear);
        gl.ClearBufferfv(GL_DEPTH, 0, &one);
        gl.BindTexture(GL_TEXTURE_2D, p.depth[1 - cur]);
        gl.DrawElements(GL_TRIANGLES, GLsizei(index_count), GL_UNSIGNED_INT, nullptr);
        gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
        gl.ReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, layer.data());
        size_t written = 0;
        for (size_t i = 0; i < n; ++i) {
            const float a = float(layer[i * 4 + 3]) / 255.0f;
            if (a <= 0.0f) continue;
            ++written;
            const float t = (1.0f - acc[i * 4 + 3]) * a;
            for (int c = 0; c < 3; ++c)
                acc[i * 4 + size_t(c)] += t * float(layer[i * 4 + size_t(c)]);
            acc[i * 4 + 3] += t;
        }
        if (written == 0) break;
    }
    gl.BindTexture(GL_TEXTURE_2D, 0);
    out->resize(n * 4);
    for (size_t i = 0; i < n; ++i) {
        for (int c = 0; c < 3; ++c)
            (*out)[i * 4 + size_t(c)] = uint8_t(std::min(acc[i * 4 + size_t(c)] + 0.5f, 255.0f));
        (*out)[i * 4 + 3] = 255;
    }
    return layers;
}

void compare(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b, OitResult* r) {
    for (size_t i = 0; i < a.size(); i += 4) {
        if (!(a[i] | a[i + 1] | a[i + 2] | b[i] | b[i + 1] | b[i + 2])) continue;
        r->covered_px += 1;
        int worst = 0;
        for (size_t c = 0; c < 3; ++c) {
            const int d = std::abs(int(a[i + c]) - int(b[i + c]));
            r->abs_sum += d;
            worst = std::max(worst, d);
        }
        r->max_diff = std::max(r->max_diff, worst);
        r->bad_px += worst > 8;
    }
}

}  // namespace

bool measure_oit(const GlApi& gl, StrokeRenderer* renderer, int width, int height, int scale,
                 int frames, int quality, float opacity, OitResult* out,
                 std::vector<uint8_t>* sorted_image, std::vector<uint8_t>* peeled_image) {
    Peeler p;
    Target target;
    if (!peeler_init(gl, width, height, &p) || !target_init(gl, width, height, &target))
        return false;
    const Scene scene = make_gi98_scene(opacity);
    TessellationParams params;
    params.quality = quality;
    auto f = std::make_unique<StrokeFrame>();
    stroke_frame_init(f.get(), params);
    std::vector<uint8_t> sorted(size_t(width) * size_t(height) * 4), peeled, blended(sorted.size());
    *out = OitResult();
    for (int i = 0; i < frames; ++i) {
        const View view = scene_view(scale, i * (kFrames / frames), width, height);
        tessellate_scene(scene, view, f.get());
        const auto t0 = std::chrono::steady_clock::now();
        target_clear(gl, target);
        StrokeLighting lighting;
        lighting.light_eye = view.light_eye;
        stroke_renderer_draw(renderer, view.projection, lighting, f->mesh.vertices,
                             f->mesh.vertex_count, f->sorted_indices.get(), f->mesh.index_count);
        gl.Finish();
        const auto t1 = std::chrono::steady_clock::now();
        target_read(gl, target, sorted.data());
        const auto t2 = std::chrono::steady_clock::now();
        const uint32_t ni = upload(gl, *renderer, f->mesh);
        const int layers = peel(gl, p, view, ni, width, height, &peeled);
        gl.BindVertexArray(0);
        const auto t3 = std::chrono::steady_clock::now();
        out->sorted_ms += std::chrono::duration<double, std::milli>(t1 - t0).count();
        out->peeled_ms += std::chrono::duration<double, std::milli>(t3 - t2).count();
        out->max_layers = std::max(out->max_layers, layers);
        out->mean_layers += layers;
        compare(sorted, peeled, out);
        draw_without_depth(gl, p, *renderer, view, f->mesh, f->sorted_indices.get(), target,
                           &blended);
        OitResult all;
        compare(blended, peeled, &all);
        out->nowrite_abs_sum += all.abs_sum;
        out->nowrite_covered_px += all.covered_px;
        out->nowrite_bad_px += all.bad_px;
        out->frames += 1;
        if (i == 0 && sorted_image) *sorted_image = sorted;
        if (i == 0 && peeled_image) *peeled_image = peeled;
    }
    out->mean_layers /= std::max(out->frames, 1.0);
    out->sorted_ms /= std::max(out->frames, 1.0);
    out->peeled_ms /= std::max(out->frames, 1.0);
    peeler_destroy(gl, &p);
    target_destroy(gl, &target);
    return true;
}

}  // namespace stipple::bench
