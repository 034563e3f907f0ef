// The depth pass's simplified occluder (issue 9 item 5; bake/occluder.h, the OCCL section).
// On a dense mesh whose triangles are each below a pixel the depth-only pass is most of the
// frame (docs/measurements-after.md); the occluder, the render mesh decimated by half-edge
// collapses at bake, covers the same screen area with a fraction of the triangles. Its
// vertices are render-mesh vertices, so it is drawn from the mesh pass's own skinned vertex
// buffer. Where the decimated surface cuts in front of the true one (concave places) it
// would hide dots lying on the surface, so each vertex is pushed away from the eye along its
// view ray by the bake's measured deviation (the largest distance the occluder lies in front
// of the surface): the push keeps the occluder's screen outline and puts it behind the true
// surface wherever the surface faces the eye (thesis §3.2: the depth pass lies "slightly
// behind the particles"). Only depth-only passes use it: the picture of a pass that paints
// the paper would show its coarser outline.
#include <cstring>

#include "runtime/asset.h"
#include "runtime/gl_program.h"
#include "runtime/renderer.h"
#include "runtime/renderer_shaders.h"

namespace stipple {

namespace {

// The push as a multiple of the bake's measured deviation (measured over the rest pose and
// sampled poses of every clip, bake/occluder.h: skinning bends the surface between the
// occluder's vertices).
constexpr float kOccluderPushScale = 1.0f;

// The mesh pass's vertex shader (runtime/renderer_shaders.h kMeshVs) with the push along the view
// ray. u_eye: the eye (w = 1), or for a parallel projection the direction away from it (w = 0).
const char* kOccluderVs = R"(#version 300 es
layout(location = 0) in vec3 a_position;
uniform mat4 u_view_projection;
uniform float u_depth_bias;
uniform vec4 u_eye;
uniform float u_push;
void main() {
    vec3 away = u_eye.w != 0.0 ? a_position - u_eye.xyz : u_eye.xyz;
    float len = length(away);
    vec3 p = len > 0.0 ? a_position + away * (u_push / len) : a_position;
    gl_Position = u_view_projection * vec4(p, 1.0);
    gl_Position.z += u_depth_bias * gl_Position.w;
}
)";

// The eye of `vp` in the mesh's space: the point whose clip coordinates are (0, 0, k, 0); for
// a parallel projection that is a direction, returned (unit, away from the eye) with w = 0.
glm::vec4 eye_of(const glm::mat4& vp) {
    const glm::vec4 e = glm::inverse(vp) * glm::vec4(0.0f, 0.0f, 1.0f, 0.0f);
    const float size = glm::length(glm::vec3(e));
    if (std::abs(e.w) > 1e-6f * size) return glm::vec4(glm::vec3(e) / e.w, 1.0f);
    glm::vec3 away = size > 0.0f ? glm::vec3(e) / size : glm::vec3(0.0f);
    if ((vp * glm::vec4(away, 0.0f)).z < 0.0f) away = -away;
    return glm::vec4(away, 0.0f);
}

}  // namespace

void renderer_config_occluder(RendererConfig* rc, const Asset& asset, const FrameConfig& c) {
    if (!c.occluder || !asset.occluder_indices) return;
    rc->occluder_indices = asset.occluder_indices;
    rc->occluder_triangle_count = asset.occluder_triangle_count;
    rc->occluder_push = asset.occluder_deviation * kOccluderPushScale;
}

Status renderer_init_occluder(Renderer* r) {
    const GlApi& gl = r->gl;
    const RendererConfig& c = r->config;
    if (c.occluder_triangle_count == 0 || !c.occluder_indices) return {};
    Status st;
    r->occluder_program = link_gl_program(
        gl, kOccluderVs, c.depth_copy ? shaders::kMeshFs : shaders::kMeshFsNoCopy, "occluder", &st);
    if (!r->occluder_program) return st;
    const GLuint p = r->occluder_program;
    gl_uniform_locations(gl, p,
                         {{&r->occluder_vp, "u_view_projection"},
                          {&r->occluder_bias, "u_depth_bias"},
                          {&r->occluder_paper, "u_paper"},
                          {&r->occluder_eye, "u_eye"},
                          {&r->occluder_push, "u_push"}});
    gl.BindVertexArray(0);  // the index buffer is bound to mesh_vao only while drawing
    gl.GenBuffers(1, &r->occluder_ibo);
    gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, r->occluder_ibo);
    gl.BufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(size_t(c.occluder_triangle_count) * 12),
                  c.occluder_indices, GL_STATIC_DRAW);
    gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
    r->occluder_enabled = true;
    return {};
}

void renderer_destroy_occluder(Renderer* r) {
    const GlApi& gl = r->gl;
    if (r->occluder_ibo) gl.DeleteBuffers(1, &r->occluder_ibo);
    if (r->occluder_program) gl.DeleteProgram(r->occluder_program);
    r->occluder_ibo = 0;
    r->occluder_program = 0;
    r->occluder_enabled = false;
}

bool renderer_draw_occluder(Renderer* r, const glm::mat4& view_projection) {
    const RendererConfig& c = r->config;
    if (!r->occluder_enabled || !r->occluder_program ||
        std::memcmp(c.paper, c.background, sizeof(c.paper)) != 0)
        return false;
    const GlApi& gl = r->gl;
    const float det = glm::determinant(view_projection);
    const glm::vec4 eye = eye_of(view_projection);
    gl.UseProgram(r->occluder_program);
    gl.UniformMatrix4fv(r->occluder_vp, 1, GL_FALSE, &view_projection[0][0]);
    gl.Uniform1f(r->occluder_bias, c.depth_bias);
    gl.Uniform4f(r->occluder_paper, c.paper[0], c.paper[1], c.paper[2], 1.0f);
    gl.Uniform4f(r->occluder_eye, eye.x, eye.y, eye.z, eye.w);
    gl.Uniform1f(r->occluder_push, c.occluder_push);
    // Back faces culled as renderer_draw_triangles does (the occluder keeps the bake's
    // outward winding); a degenerate transform draws every triangle.
    if (det != 0.0f) {
        gl.FrontFace(det < 0.0f ? GL_CCW : GL_CW);
        gl.CullFace(GL_BACK);
        gl.Enable(GL_CULL_FACE);
    }
    gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, r->occluder_ibo);
    gl.DrawElements(GL_TRIANGLES, GLsizei(c.occluder_triangle_count * 3), GL_UNSIGNED_INT, nullptr);
    gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, r->mesh_ibo);  // mesh_vao's own again
    gl.Disable(GL_CULL_FACE);
    // The double-sided triangles (not in the occluder) in full, with the mesh program.
    const uint32_t total = c.triangle_count, single = r->single_sided_count;
    gl.UseProgram(r->mesh_program);
    if (total > single)
        gl.DrawElements(GL_TRIANGLES, GLsizei((total - single) * 3), GL_UNSIGNED_INT,
                        reinterpret_cast<const void*>(size_t(single) * 12));
    return true;
}

}  // namespace stipple
