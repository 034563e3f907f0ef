// Fur (GI'98 §5.3, the SIGGRAPH'97 sketch's animal and torus): one hair per point of the
// hierarchy's coarse-to-fine prefix, so drawing the first k strokes is a level of detail just
// as drawing the first k points is. Each hair is a surface-anchored paintstroke on its point's
// host triangle and barycentrics, its control points in the tangent frame of
// runtime/stroke_anchor.h (surface_frame), the same frame the runtime rebuilds every frame.
#pragma once
#include <cstdint>

#include "bake/bake_error.h"
#include "bake/point_hierarchy.h"
#include "bake/raw_scene.h"
#include "bake/stroke_data.h"

namespace stipple::bake {

constexpr uint32_t kFurControlPoints = 5;

struct FurConfig {
    uint32_t count = 0;   // hairs wanted (more than the points: one per point)
    float length = 0.0f;  // hair length, object units; 0: default_fur_length(scene)
    float radius = 0.0f;  // root radius, object units; 0: length / 25
    // Object-space comb: the hair bends toward its projection onto the tangent plane; the tip
    // turns by that projection's length in radians (at most kMaxFurBend). Gravity by default.
    float comb[3] = {0.0f, -1.0f, 0.0f};
    float curl = 0.0f;  // twist of the bend around the normal, radians per object unit
};

constexpr float kMaxFurBend = 1.5f;  // radians

// 3% of the rest pose's bounding-box diagonal (0 for an empty mesh).
float default_fur_length(const RawScene& scene);

// Appends min(count, points) hairs to `out`, stroke i rooted at point i (root_point = i).
// Errors: invalid_option (length or radius, once defaulted, not finite or not in
// (0, 2.5e5], so no control point passes limits::kMaxStrokeCoordinate; a non-finite comb or
// curl; count over limits::kMaxStrokes), malformed_input (a point's host triangle outside
// the mesh). Nothing is appended on error.
[[nodiscard]] BakeError bake_fur(const RawScene& scene, const PointHierarchy& points,
                                 const FurConfig& config, BakedStrokes* out);

}  // namespace stipple::bake
