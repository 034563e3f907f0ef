// Clearing only what the last frame drew (issue 9 item 5: the draw at its raster floor).
// llvmpipe's rasterizer threads clear every tile of the colour and depth buffers at the start
// of a frame, one memset per tile row: at 1280x720 that was about a quarter of their time on
// CesiumMan (perf, `rep stos` in swrast_dri.so), although the character covers a small part of
// the image. Everything outside what the previous frame drew still holds the background and
// the far depth, so renderer_clear_frame clears only that rectangle (a scissored clear) when
// pipeline_frame has said where it drew (the posed mesh's bounding box on screen, grown by the
// dots' and lines' half width; runtime/frame_pipeline.cpp). Any other draw into the image,
// a background change, or a box reaching behind the eye brings back the full clear. The picture
// is the same pixel for pixel.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "runtime/renderer.h"

namespace stipple {

void renderer_mark_dirty(Renderer* r) {
    r->dirty[0] = r->dirty[1] = 0;
    r->dirty[2] = r->dirty[3] = -1;
}

void renderer_set_drawn_box(Renderer* r, const glm::mat4& view_projection, const glm::vec3& lo,
                            const glm::vec3& hi, float margin_px) {
    const RendererConfig& c = r->config;
    float x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
    for (int k = 0; k < 8; ++k) {
        const glm::vec4 q = view_projection * glm::vec4(k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y,
                                                        k & 4 ? hi.z : lo.z, 1.0f);
        // Every corner in front of the eye: the box is, and its picture lies inside the
        // corners' pictures. Else (or NaN) the whole image.
        if (!(q.w > 1e-6f)) return renderer_mark_dirty(r);
        const float x = (q.x / q.w * 0.5f + 0.5f) * float(c.width);
        const float y = (q.y / q.w * 0.5f + 0.5f) * float(c.height);
        x0 = std::fmin(x0, x), x1 = std::fmax(x1, x);
        y0 = std::fmin(y0, y), y1 = std::fmax(y1, y);
    }
    const float m = margin_px + 2.0f;  // and a pixel or two for rounding
    x0 = std::floor(x0 - m), y0 = std::floor(y0 - m);
    x1 = std::ceil(x1 + m), y1 = std::ceil(y1 + m);
    if (!(x0 < x1 && y0 < y1)) return renderer_mark_dirty(r);  // NaN
    const float w = float(c.width), h = float(c.height);
    x0 = std::fmin(std::fmax(x0, 0.0f), w), x1 = std::fmin(std::fmax(x1, 0.0f), w);
    y0 = std::fmin(std::fmax(y0, 0.0f), h), y1 = std::fmin(std::fmax(y1, 0.0f), h);
    r->dirty[0] = int(x0);
    r->dirty[1] = int(y0);
    r->dirty[2] = int(x1) - int(x0);
    r->dirty[3] = int(y1) - int(y0);
}

bool renderer_scissor_dirty(Renderer* r) {
    const RendererConfig& c = r->config;
    const int* d = r->dirty;
    const bool same_background =
        std::memcmp(c.background, r->cleared_background, sizeof(c.background)) == 0;
    const bool part =
        same_background && d[2] >= 0 && d[3] >= 0 && (d[2] < c.width || d[3] < c.height);
    std::memcpy(r->cleared_background, c.background, sizeof(c.background));
    if (part) {
        r->gl.Enable(GL_SCISSOR_TEST);
        r->gl.Scissor(d[0], d[1], d[2], d[3]);
    }
    renderer_mark_dirty(r);
    return part;
}

void renderer_set_drawn_mesh(Renderer* r, const glm::mat4& view_projection, const float* positions,
                             uint32_t vertex_count, const float* sizes, uint32_t size_count,
                             float max_point_size) {
    if (vertex_count == 0) return renderer_mark_dirty(r);
    glm::vec3 lo(positions[0], positions[1], positions[2]), hi = lo;
    for (uint32_t i = 1; i < vertex_count; ++i) {
        const glm::vec3 q(positions[size_t(i) * 3], positions[size_t(i) * 3 + 1],
                          positions[size_t(i) * 3 + 2]);
        lo = glm::min(lo, q);
        hi = glm::max(hi, q);
    }
    float dot = max_point_size;
    for (uint32_t i = 0; i < size_count; ++i) dot = std::max(dot, sizes[i]);
    // A dot's sprite reaches d/2 + 1/2 from its centre (at least 1 px; renderer_shaders.h), a
    // line half its width (at least 1 px, the GL's narrowest) from its axis.
    const float line = std::max(r->config.line_width, 1.0f);
    const float margin = std::max(0.5f * std::max(dot, 1.0f) + 0.5f, 0.5f * line + 0.5f);
    renderer_set_drawn_box(r, view_projection, lo, hi, margin);
}

}  // namespace stipple
