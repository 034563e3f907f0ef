#include "runtime/stroke_anchor.h"

namespace stipple {
namespace {

glm::vec3 vec3_at(const float* a, uint32_t i) {
    return glm::vec3(a[i * 3], a[i * 3 + 1], a[i * 3 + 2]);
}

float unorm8(uint8_t v) {
    return float(v) * (1.0f / 255.0f);
}

glm::vec3 snorm8(const int8_t* v) {
    return glm::vec3(float(v[0]), float(v[1]), float(v[2])) * (1.0f / 127.0f);
}

// The host triangle's tangent frame at the stroke's barycentrics, as posed this frame.
SurfaceFrame host_frame(const format::StrokeRecord& s, const MeshView& mesh, const float* positions,
                        const float* normals) {
    const uint32_t* t = mesh.indices + size_t(s.host) * 3;
    return surface_frame(vec3_at(positions, t[0]), vec3_at(positions, t[1]),
                         vec3_at(positions, t[2]), vec3_at(normals, t[0]), vec3_at(normals, t[1]),
                         vec3_at(normals, t[2]), s.bary_u, s.bary_v);
}

// Object-space position and global normal of a stored point under a rigid-ish transform.
void place_with_matrix(const format::StrokePointRecord& r, const glm::mat4& m, glm::vec3* pos,
                       glm::vec3* normal) {
    const glm::vec3 p(r.position[0], r.position[1], r.position[2]);
    *pos = glm::vec3(m * glm::vec4(p, 1.0f));
    *normal = glm::vec3(m * glm::vec4(snorm8(r.global_normal), 0.0f));
}

}  // namespace

StrokePoint decode_stroke_point(const format::StrokePointRecord& r, const glm::vec3& position,
                                const glm::vec3& global_normal) {
    StrokePoint p;
    p.position = position;
    p.radius = r.radius;
    p.colour = glm::vec3(unorm8(r.colour[0]), unorm8(r.colour[1]), unorm8(r.colour[2]));
    p.reflectance = unorm8(r.reflectance);
    p.op_min = unorm8(r.op_min);
    p.op_max = unorm8(r.op_max);
    const float len = glm::length(global_normal);
    p.global_normal = len > 1e-6f ? global_normal / len : glm::vec3(0.0f);  // §5.3 N_gl, unit
    p.global_depth = unorm8(r.global_depth);
    return p;
}

void anchor_strokes(const StrokesView& strokes, const MeshView& mesh, const float* positions,
                    const float* normals, const glm::mat4* skin_matrices, const glm::mat4& view,
                    StrokePoint* out_points) {
    const glm::mat3 view_rotation(view);
    for (uint32_t s = 0; s < strokes.stroke_count; ++s) {
        const format::StrokeRecord& rec = strokes.strokes[s];
        const format::StrokePointRecord* in = strokes.points + rec.first_point;
        StrokePoint* out = out_points + rec.first_point;
        if (rec.anchor == format::kAnchorSurface) {
            const SurfaceFrame f = host_frame(rec, mesh, positions, normals);
            for (uint32_t i = 0; i < rec.point_count; ++i) {
                const glm::vec3 p = frame_point(
                    f, glm::vec3(in[i].position[0], in[i].position[1], in[i].position[2]));
                const glm::vec3 n = frame_direction(f, snorm8(in[i].global_normal));
                out[i] = decode_stroke_point(in[i], glm::vec3(view * glm::vec4(p, 1.0f)),
                                             view_rotation * n);
            }
            continue;
        }
        const bool joint = rec.anchor == format::kAnchorJoint && skin_matrices;
        const glm::mat4 m = joint ? view * skin_matrices[rec.host] : view;
        for (uint32_t i = 0; i < rec.point_count; ++i) {
            glm::vec3 p, n;
            place_with_matrix(in[i], m, &p, &n);
            out[i] = decode_stroke_point(in[i], p, n);
        }
    }
}

glm::vec3 stroke_root(const StrokesView& strokes, uint32_t stroke, const MeshView& mesh,
                      const float* positions, const float* normals,
                      const glm::mat4* skin_matrices) {
    const format::StrokeRecord& rec = strokes.strokes[stroke];
    if (rec.anchor == format::kAnchorSurface)
        return host_frame(rec, mesh, positions, normals).origin;
    const float* p = strokes.points[rec.first_point].position;
    const glm::vec4 bind(p[0], p[1], p[2], 1.0f);
    if (rec.anchor == format::kAnchorJoint && skin_matrices)
        return glm::vec3(skin_matrices[rec.host] * bind);
    return glm::vec3(bind);
}

}  // namespace stipple
