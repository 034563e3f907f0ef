// The mesh pass's front faces (issue 9, item 5: take the milliseconds out of the frame's draw).
// On llvmpipe the depth pass of a dense mesh costs what the driver does per triangle in the
// calling thread: fetch, shade, clip, cull, set up and bin; back faces are culled only after
// most of that. The silhouette stage (runtime/silhouette.h, thesis §3.2) already knows every
// triangle's facing for this frame's eye, so the pass hands the GPU only the single-sided
// triangles that may face it (front ones and back ones within ~0.9 degrees of edge-on, which the
// GPU's snapped vertices could still turn to the front) and the GPU culls what is left exactly
// as before: the depth and the picture are the same.
#include <cstring>

#include "runtime/renderer.h"
#include "runtime/silhouette.h"

namespace stipple {

void renderer_set_front_faces(Renderer* r, const uint8_t* front, const glm::mat4& view_projection) {
    r->front_faces = front;
    r->front_vp = view_projection;
    r->front_count = Renderer::kFrontNotBuilt;
}

void renderer_init_front(Renderer* r) {
    const RendererConfig& c = r->config;
    if (c.triangle_count == 0 || !c.indices) return;
    const GlApi& gl = r->gl;
    gl.GenBuffers(1, &r->front_ibo);
    gl.BindBuffer(GL_ARRAY_BUFFER, r->front_ibo);  // filled as indices, bound as such to draw
    gl.BufferData(GL_ARRAY_BUFFER, GLsizeiptr(size_t(c.triangle_count) * 12), nullptr,
                  GL_STREAM_DRAW);
    gl.BindBuffer(GL_ARRAY_BUFFER, 0);
}

void renderer_destroy_front(Renderer* r) {
    if (r->front_ibo) r->gl.DeleteBuffers(1, &r->front_ibo);
    r->front_ibo = 0;
}

namespace {

// The flags were made for the eye of `vp`'s camera: only a perspective projection has that
// eye as its centre (an affine one has w constant and the flags say nothing about it).
bool flags_apply(const Renderer& r, const glm::mat4& vp) {
    if (!r.front_faces || !r.front_ibo) return false;
    if (vp[0][3] == 0.0f && vp[1][3] == 0.0f && vp[2][3] == 0.0f) return false;
    return std::memcmp(&vp[0][0], &r.front_vp[0][0], sizeof(float) * 16) == 0;
}

// Writes the single-sided triangles not flagged kFacingBack into `out`, in the index buffer's
// order (the single-sided ones, runtime/renderer.cpp upload_indices); returns their number.
uint32_t compact_front(const RendererConfig& c, const uint8_t* front, uint32_t* out) {
    const uint32_t* in = c.indices;
    const uint8_t* sides = c.triangle_double_sided;
    uint32_t n = 0;
    // Every triangle is copied to the next free slot and counted only when kept (no branch:
    // facing is not predictable triangle to triangle); `out` holds triangle_count triangles.
    for (uint32_t t = 0; t < c.triangle_count; ++t) {
        std::memcpy(out + size_t(n) * 3, in + size_t(t) * 3, 12);
        n += uint32_t(front[t] != kFacingBack) & uint32_t(!sides || sides[t] == 0);
    }
    return n;
}

}  // namespace

bool renderer_front_triangles(Renderer* r, const glm::mat4& view_projection, uint32_t* count) {
    if (!flags_apply(*r, view_projection)) return false;
    if (r->front_count == Renderer::kFrontNotBuilt) {
        const GlApi& gl = r->gl;
        const GLsizeiptr bytes = GLsizeiptr(size_t(r->config.triangle_count) * 12);
        gl.BindBuffer(GL_ARRAY_BUFFER, r->front_ibo);
        void* mapped = gl.MapBufferRange(GL_ARRAY_BUFFER, 0, bytes,
                                         GL_MAP_WRITE_BIT | GL_MAP_INVALIDATE_BUFFER_BIT);
        if (!mapped) {
            gl.BindBuffer(GL_ARRAY_BUFFER, 0);
            r->front_faces = nullptr;  // no mapping: every triangle, as without the flags
            return false;
        }
        const uint32_t n = compact_front(r->config, r->front_faces, static_cast<uint32_t*>(mapped));
        const bool unmapped = gl.UnmapBuffer(GL_ARRAY_BUFFER) == GL_TRUE;
        gl.BindBuffer(GL_ARRAY_BUFFER, 0);
        if (!unmapped) {  // the contents were lost (GLES 3.0 §2.10.3): draw them all
            r->front_faces = nullptr;
            return false;
        }
        r->front_count = n;
    }
    *count = r->front_count;
    return true;
}

}  // namespace stipple
