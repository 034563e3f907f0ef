// Paintstrokes (Neulander & van de Panne, "Rendering Generalized Cylinders with Paintstrokes",
// GI'98): a generalized cylinder given by control points, tessellated every frame in eye space
// into the few polygons that tile its screen projection.
//   §3   representation: StrokePoint (pos and rad by Catmull-Rom, the rest linear)
//   §4.2 lengthwise subdivision: Position Constraints I and II, radius constraint, inflections
//   §4.3 breadthwise subdivision: quality 0 / 1 / 2, out vectors, hidden back side, end caps
//   §4.4 normals: out + adj (eq. 2), nudge for quality 0
//   §5   lengthwise opacity (eq. 3), breadthwise opacity (eqs. 4-5), global shading (eq. 6)
// Plain structs and free functions; output goes to caller-owned fixed-capacity buffers, so a
// frame allocates nothing. The GL side is runtime/stroke_renderer.h.
#pragma once
#include <cstdint>
#include <glm/glm.hpp>

namespace stipple {

// GI'98 §3: one control point. Every vector is in eye space when tessellated (the viewer at
// the origin looking down -z, as in GL).
struct StrokePoint {
    glm::vec3 position{0.0f};
    float radius = 0.0f;            // same units as position
    glm::vec3 colour{0.0f};         // linear RGB in [0, 1]
    float reflectance = 0.0f;       // linear reflectance: specular weight in [0, 1]
    float op_min = 1.0f;            // lengthwise opacity seen head-on (eq. 3)
    float op_max = 1.0f;            // ... seen orthogonally to the path
    glm::vec3 global_normal{0.0f};  // §5.3 N_gl (unit, or zero: no global shading)
    float global_depth = 0.0f;      // §5.3 d_gl in [0, 1]: 0 on the global surface
    // op_min / op_max: eq. 3 as printed, which tessellate_stroke implements, weights op_max by
    // |view . unit tangent|: op_max where the view runs along the path, op_min where the path
    // is seen broadside; §5.1's prose names them the other way round. See
    // runtime/paintstroke_breadthwise.cpp.
};

// Per stroke (not per control point): breadthwise opacity (eq. 5).
struct StrokeStyle {
    float op_centre = 1.0f;
    float op_edge = 1.0f;
};

// Quality levels of §4.3: log2 of the polygons tiling the viewer's side of a segment.
enum StrokeQuality : int {
    kStrokeQualityAuto = -1,
    kStrokeQuality0 = 0,
    kStrokeQuality1 = 1,
    kStrokeQuality2 = 2
};

// The camera as tessellation sees it: perspective, square pixels, viewer at the origin looking
// down -z. A point (x, y, z) projects to (focal_px * x / -z, focal_px * y / -z) pixels from the
// image centre; focal_px is §4.2.2's projection distance d_proj.
struct StrokeCamera {
    float focal_px = 0.0f;
    float near_z = 1e-3f;  // a segment with a point at -z < near_z is not drawn
};

struct TessellationParams {
    float tol_theta_px = 1.0f;  // tol_theta of Position Constraint I (pixels)
    float tol_z_px = 0.5f;      // tol_z of Position Constraint II and the radius constraint
    int quality = kStrokeQualityAuto;
    // Auto quality (§4.3, chosen per stroke): by the largest projected radius of its control
    // points; below q1_radius_px quality 0, below q2_radius_px quality 1, else 2.
    float q1_radius_px = 1.5f;
    float q2_radius_px = 6.0f;
    float nudge = 0.5f;    // §4.4: how far quality-0 edge normals move toward the centre
    int max_depth = 10;    // recursion limit of the lengthwise subdivision per section
    bool end_caps = true;  // close both ends (a fan over the end disc's visible half)
    // A cap whose disc projects smaller than this radius is left out: it covers less than a
    // pixel's worth beyond the segment's own end edge (fur tips, strokes far away).
    float cap_min_radius_px = 1.0f;
    glm::vec3 light_eye{0.0f, 0.0f, 1.0f};  // unit, toward the light, eye space (§5.3's L)
};

// One tessellated vertex, eye space. The fragment shader lights it (Lambert + Phong specular
// weighted by reflectance) with the interpolated normal.
struct StrokeVertex {
    float position[3];
    float normal[3];    // not normalised: §4.4 interpolates components, the shader normalises
    float colour[4];    // rgb; a = lengthwise (eq. 3) times breadthwise (eq. 5) opacity
    float reflectance;  // after global shading (eq. 6)
    float shade;        // global shading factor exp(-k p) of §5.3 applied to diffuse, 1 = none
};
static_assert(sizeof(StrokeVertex) == 12 * sizeof(float), "vertex layout");

// A lengthwise segment's polygons: the unit the compositor sorts back to front.
struct StrokeSegment {
    uint32_t first_index;  // into StrokeMesh::indices
    uint32_t index_count;  // a multiple of 3
    float depth;           // eye-space distance of the segment's midpoint (sort key)
    uint32_t stroke;       // the caller's stroke id (tessellate_stroke's `stroke_id`)
};

// Caller-owned output buffers with their capacities. tessellate_stroke appends; when a buffer
// would overflow it stops adding segments and sets `overflow` (never writes past a capacity);
// a mesh already marked `overflow` takes nothing more until the caller clears it.
struct StrokeMesh {
    StrokeVertex* vertices = nullptr;
    uint32_t vertex_capacity = 0, vertex_count = 0;
    uint32_t* indices = nullptr;  // triangles, 3 per
    uint32_t index_capacity = 0, index_count = 0;
    StrokeSegment* segments = nullptr;
    uint32_t segment_capacity = 0, segment_count = 0;
    bool overflow = false;
};

struct TessellationStats {
    uint32_t strokes = 0, sections = 0, segments = 0, triangles = 0;
    uint32_t inflection_splits = 0;  // §4.2.3
    uint32_t back_sides_suppressed = 0;
    uint32_t quality_count[3] = {};  // strokes drawn at each quality
};

// Tessellates one paintstroke of `count` >= 2 eye-space control points and appends its
// polygons to `out`. Invalid input (count < 2, non-finite values, negative radii) draws
// nothing. `stats` may be null.
void tessellate_stroke(const StrokePoint* points, uint32_t count, const StrokeStyle& style,
                       uint32_t stroke_id, const StrokeCamera& camera,
                       const TessellationParams& params, StrokeMesh* out, TessellationStats* stats);

// Worst-case output of one stroke of `count` control points (every section split to
// params.max_depth at quality 2 with both sides and end caps), for sizing StrokeMesh. Each
// section is first cut at up to 4 inflection points (§4.2.3), each piece then recursing to
// max_depth (clamped to [0, 16]): (count - 1) * 5 * 2^max_depth segments of 16 vertices and
// 48 indices, plus 2 caps of 9 vertices and 24 indices.
struct StrokeMeshBound {
    uint64_t vertices = 0, indices = 0, segments = 0;
};
StrokeMeshBound stroke_mesh_bound(uint32_t count, const TessellationParams& params);

}  // namespace stipple
