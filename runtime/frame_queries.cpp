// What a caller can ask of the last frame: point ids, projections, visible dots, stroke roots
// (runtime/frame_pipeline.h declares them).
#include <algorithm>
#include <cmath>

#include "runtime/frame_pipeline.h"
#include "runtime/stroke_anchor.h"

namespace stipple {

uint64_t pipeline_point_id(const Pipeline& p, uint32_t i) {
    const uint32_t baked = p.asset->points.point_count;
    if (i < baked) return i;
    const uint32_t j = i - baked;
    return (uint64_t(p.refined_triangle[j]) + 1) << 32 | p.refined_index[j];
}

namespace {

// Clip space to pixels (origin top-left) and window depth.
glm::vec3 to_pixels(const Pipeline& p, const glm::vec4& clip) {
    const glm::vec3 ndc = glm::vec3(clip) / clip.w;
    return glm::vec3((ndc.x * 0.5f + 0.5f) * float(p.config.width),
                     (0.5f - ndc.y * 0.5f) * float(p.config.height), ndc.z * 0.5f + 0.5f);
}

}  // namespace

glm::vec3 pipeline_project(const Pipeline& p, uint32_t i) {
    return to_pixels(
        p, p.view_projection * glm::vec4(p.point_positions[i * 3], p.point_positions[i * 3 + 1],
                                         p.point_positions[i * 3 + 2], 1.0f));
}

uint32_t pipeline_stroke_roots(const Pipeline& p, StrokeRootSample* out, uint32_t capacity) {
    if (!p.strokes.enabled) return 0;
    const Asset& a = *p.asset;
    const StrokesView& v = a.strokes;
    const glm::mat4* joints = a.skinned ? p.skin_matrices.get() : nullptr;
    uint32_t n = 0;
    for (uint32_t i = 0; i < v.stroke_count && n < capacity; ++i) {
        const format::StrokeRecord& r = v.strokes[i];
        const glm::vec3 drawn =
            to_pixels(p, p.projection * glm::vec4(p.strokes.points[r.first_point].position, 1.0f));
        const glm::vec3 surface =
            r.root_point != format::kNoRootPoint
                ? pipeline_project(p, r.root_point)
                : to_pixels(p, p.view_projection *
                                   glm::vec4(stroke_root(v, i, a.mesh, p.vertex_positions.get(),
                                                         p.vertex_normals.get(), joints),
                                             1.0f));
        out[n++] = StrokeRootSample{i, drawn.x, drawn.y, surface.x, surface.y};
    }
    return n;
}

namespace {

// Whether the point shader (runtime/renderer_shaders.h kPointVs) draws a dot at window depth z
// whose centre is (x, y) in GL window coordinates (rows bottom first) in pixel `centre_texel`:
// the mesh's depth there is not in front of it, or the depth interpolated from the 2x2 texels
// around its centre (texels off the object read 1) is not, one of them on the object.
bool dot_seen(const float* depth, int w, int h, size_t centre_texel, float x, float y, float z) {
    const float centre = depth[centre_texel];
    if (centre < 1.0f && z <= centre + 1e-5f) return true;
    const float ax = x - 0.5f, ay = y - 0.5f;
    const int cx = int(std::floor(ax)), cy = int(std::floor(ay));
    const float fx = ax - float(cx), fy = ay - float(cy);
    float d[4], nearest = 1.0f;
    for (int k = 0; k < 4; ++k) {
        const int tx = std::min(std::max(cx + (k & 1), 0), w - 1);
        const int ty = std::min(std::max(cy + (k >> 1), 0), h - 1);
        d[k] = depth[size_t(ty) * size_t(w) + size_t(tx)];
        nearest = std::min(nearest, d[k]);
    }
    const float between =
        (d[0] + (d[1] - d[0]) * fx) * (1.0f - fy) + (d[2] + (d[3] - d[2]) * fx) * fy;
    return nearest < 1.0f && z <= between + 1e-5f;
}

// The dots with a size whose centre lies inside the image and near the mesh's coverage (one of
// the 2x2 texels around it on the object), split by dot_seen: `hidden` false lists the ones
// drawn, true the ones the mesh in front hides.
uint32_t sized_dots(const Pipeline& p, const float* depth, bool hidden, VisibleDot* out,
                    uint32_t capacity) {
    const int w = p.config.width, h = p.config.height;
    const uint32_t count = pipeline_point_count(p);
    uint32_t n = 0;
    for (uint32_t i = 0; i < count && n < capacity; ++i) {
        if (p.size[i] <= 0.0f) continue;
        const glm::vec3 s = pipeline_project(p, i);
        const int px = int(std::floor(s.x)), py = int(std::floor(s.y));
        if (px < 0 || py < 0 || px >= w || py >= h) continue;
        const float gx = s.x, gy = float(h) - s.y;  // GL window coordinates
        const size_t centre = size_t(h - 1 - py) * size_t(w) + size_t(px);
        const int cx = int(std::floor(gx - 0.5f)), cy = int(std::floor(gy - 0.5f));
        bool on_object = false;
        for (int k = 0; k < 4; ++k) {
            const int tx = std::min(std::max(cx + (k & 1), 0), w - 1);
            const int ty = std::min(std::max(cy + (k >> 1), 0), h - 1);
            on_object = on_object || depth[size_t(ty) * size_t(w) + size_t(tx)] < 1.0f;
        }
        if (!on_object || dot_seen(depth, w, h, centre, gx, gy, s.z) == hidden) continue;
        out[n++] = VisibleDot{pipeline_point_id(p, i), s.x, s.y, p.size[i]};
    }
    return n;
}

}  // namespace

uint32_t pipeline_visible_dots(const Pipeline& p, const float* depth, VisibleDot* out,
                               uint32_t capacity) {
    return sized_dots(p, depth, false, out, capacity);
}

uint32_t pipeline_hidden_dots(const Pipeline& p, const float* depth, VisibleDot* out,
                              uint32_t capacity) {
    return sized_dots(p, depth, true, out, capacity);
}

}  // namespace stipple
