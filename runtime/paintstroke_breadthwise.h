// GI'98 §4.3-§5: breadthwise subdivision of a lengthwise segment: the view-dependent out
// vectors, the ring of vertices at each segment end, hidden back side suppression, normals
// (eq. 2, nudge) and the per-vertex effects (eqs. 3-6).
#pragma once
#include <cstdint>
#include <glm/glm.hpp>

#include "runtime/paintstroke.h"
#include "runtime/paintstroke_curve.h"

namespace stipple {

// §5.3: vertex.shade = exp(-kGlobalShadingK p). With k = 2 a point on the lit global surface
// (p = 0) keeps full light and one at the far side of the unit sphere (p = 1) keeps e^-2, 14%.
constexpr float kGlobalShadingK = 2.0f;

// GI'98 eq. 6: light penetration p in [0, 1] of a point at (1 - d_gl) N_gl in the unit sphere
// toward the light L (both normalised here).
float global_penetration(const glm::vec3& n_gl, float d_gl, const glm::vec3& light);
// exp(-k p); 1 (no global shading) for a zero global normal.
float global_shade(const glm::vec3& n_gl, float d_gl, const glm::vec3& light);

// GI'98 eq. 3 exactly as printed: op_len = alpha op_max + (1 - alpha) op_min with
// alpha = |view . pos' / |pos'||. `view` and `tangent` need not be normalised.
float lengthwise_opacity(float op_min, float op_max, const glm::vec3& view,
                         const glm::vec3& tangent);

// The view-dependent frame of the tube at one parameter t (GI'98 §4.3.2).
struct RingFrame {
    glm::vec3 pos{0.0f};
    glm::vec3 tangent{0.0f};  // pos'(t), not normalised
    glm::vec3 view{0.0f};     // unit, eye -> pos (GI'98 §3)
    glm::vec3 edge{0.0f};     // unit direction of out_edge: perpendicular to pos' and view
    glm::vec3 centre{0.0f};   // unit direction of out_centre: perpendicular to pos', toward
                              // the viewer
    glm::vec3 adj{0.0f};      // GI'98 eq. 2: -rad'(t) / |pos'(t)|^2 pos'(t)
    float rad = 0.0f;         // max(rad(t), 0)
    bool tangent_defined = false;
};
RingFrame ring_frame(const SectionCurve& s, float t);

// Hidden back side test of §4.3 at one segment end: the far half of a truncated cone shows
// past its silhouette only when (dr/ds) (unit tangent . view) > rad / |pos| (derived from
// (out + adj) . (eye - vertex) > 0 for the out directions behind the axis). A straight tube
// (dr/ds = 0) never shows its back; a tube widening away from the viewer seen along its axis
// does.
bool back_side_visible(const RingFrame& f);

// Ring layout (GI'98 §4.3.1): the viewer's side first, from +edge over the centre to -edge
// (2, 3 or 5 vertices for quality 0, 1, 2), then the far side (1 or 3 vertices) when drawn.
int ring_front_count(int quality);
int ring_size(int quality, bool back);
// Unit out directions of the ring, in ring order; returns the count.
int ring_directions(const RingFrame& f, int quality, bool back, glm::vec3* dirs);

// Linear attributes at one ring (interpolated between control points, GI'98 §3).
struct RingAttributes {
    glm::vec3 colour{0.0f};
    float op_min = 1.0f, op_max = 1.0f;
    float reflectance = 0.0f;
    float shade = 1.0f;  // exp(-k p), interpolated from the control points' values
};

// Writes the ring's vertices: position pos + rad * dir, normal dir + adj (eq. 2; quality 0
// edge normals nudged toward the centre's, §4.4), alpha = op_len (eq. 3) * o_i (eqs. 4-5).
// Returns the count (ring_size).
int build_ring(const RingFrame& f, int quality, bool back, const RingAttributes& attr,
               const StrokeStyle& style, float nudge, StrokeVertex* out);

// Triangles of the quads between ring A (vertices base..) and ring B (base + size..):
// writes 6 indices per quad and returns the count.
int ring_indices(int quality, bool back, uint32_t base, uint32_t* out);

}  // namespace stipple
