// Stroke anchoring: where a paintstroke's control points are this frame. A surface-anchored
// stroke rides on its host triangle like a stipple point (thesis Alg. 6.3): its root is the
// barycentric point of the skinned triangle and its control points are stored in the
// triangle's tangent frame there, so they turn with the surface; lengths stay in object units,
// so a stroke keeps its shape when the surface stretches. Joint-anchored strokes move rigidly
// with their joint; object-anchored ones stay put. The bake writes control points with the same
// frame (surface_frame), so bake and runtime agree to the last bit on the rest pose.
#pragma once
#include <cstdint>
#include <glm/glm.hpp>

#include "runtime/asset.h"
#include "runtime/paintstroke.h"

namespace stipple {

// The tangent frame at barycentric (u, v) of triangle (p0, p1, p2) with vertex normals
// (n0, n1, n2): origin = u p0 + v p1 + (1-u-v) p2; z = the normalised blend of the vertex
// normals (the face normal when that blend vanishes); x = the first edge p1 - p0 made
// orthogonal to z (any perpendicular when the edge is parallel to z); y = z × x.
struct SurfaceFrame {
    glm::vec3 origin, x, y, z;
};
inline SurfaceFrame surface_frame(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2,
                                  const glm::vec3& n0, const glm::vec3& n1, const glm::vec3& n2,
                                  float u, float v) {
    const float w = 1.0f - u - v;
    SurfaceFrame f;
    f.origin = u * p0 + v * p1 + w * p2;
    glm::vec3 z = u * n0 + v * n1 + w * n2;
    float len = glm::length(z);
    if (!(len > 1e-12f)) {
        z = glm::cross(p1 - p0, p2 - p0);
        len = glm::length(z);
    }
    z = len > 1e-30f ? z / len : glm::vec3(0.0f, 0.0f, 1.0f);
    glm::vec3 x = (p1 - p0) - glm::dot(p1 - p0, z) * z;
    len = glm::length(x);
    if (!(len > 1e-12f)) {
        x = glm::abs(z.x) < 0.9f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
        x = x - glm::dot(x, z) * z;
        len = glm::length(x);
    }
    f.x = x / len;
    f.y = glm::cross(f.z = z, f.x);
    return f;
}

// A frame point: origin + a.x * x + a.y * y + a.z * z (and without the origin for directions).
inline glm::vec3 frame_point(const SurfaceFrame& f, const glm::vec3& a) {
    return f.origin + a.x * f.x + a.y * f.y + a.z * f.z;
}
inline glm::vec3 frame_direction(const SurfaceFrame& f, const glm::vec3& a) {
    return a.x * f.x + a.y * f.y + a.z * f.z;
}

// Decodes one stored control point (quantised colour and opacities) with its position and
// global normal already placed; the helpers below call it.
StrokePoint decode_stroke_point(const format::StrokePointRecord& r, const glm::vec3& position,
                                const glm::vec3& global_normal);

// This frame's control points of every stroke, in eye space, indexed like strokes.points.
// `positions`/`normals` are the posed mesh's vertices (3 floats each, the space `view` takes
// to eye space); `skin_matrices` the posed joints (joint anchors; may be null without any).
// Surface anchors use surface_frame on the posed host triangle.
void anchor_strokes(const StrokesView& strokes, const MeshView& mesh, const float* positions,
                    const float* normals, const glm::mat4* skin_matrices, const glm::mat4& view,
                    StrokePoint* out_points);

// The point a stroke is anchored at this frame in the posed mesh's space: a surface stroke's
// frame origin, the first control point otherwise (before the view transform).
glm::vec3 stroke_root(const StrokesView& strokes, uint32_t stroke, const MeshView& mesh,
                      const float* positions, const float* normals, const glm::mat4* skin_matrices);

}  // namespace stipple
