// Run-time refinement: the point hierarchy continued past its finest baked level, so close-ups
// and stretched surfaces never run out of dots (issue 7, item 1; docs/tone.md).
//
// The baked hierarchy orders points coarse to fine with region of influence ~ A / i for the
// i-th point (thesis §4.5, §3.1.1). When a triangle's screen area asks for more points than the
// bake holds, the triangle continues that order with its own deterministic sequence:
//   - Domain: the triangles between the baked points themselves (point_triangulation.h), so
//     the extra points fill the holes between baked points whatever the render mesh looks
//     like; the render mesh only for bakes too small to triangulate (then the baked points
//     hand over to the sequence in close-ups, see below).
//   - Where: the k-th extra point of triangle t lies at a fixed barycentric position
//     (runtime/refinement_sequence.h): root cells by longest-edge bisection (slivers, large
//     triangles), then a progressive farthest-point pattern per cell, then midpoint sub-cells.
//   - How relevant: the region of extra point k of a triangle of bind area a is
//     1 / (rho0 + (k + phase) / a), rho0 the baked density there: the A / i law, continued
//     (phase in (0, 1] per triangle, so triangles smaller than one point fill in smoothly, in
//     the farthest-point order of runtime/refinement_order.h).
//   - Under deformation: its neighbours are the triangle's corners, so Alg. 6.4's "radius
//     follows the neighbours" becomes "region follows the triangle's area":
//     region *= current area / bind area.
//   - Which: only the points the size rule (Alg. 3.2) can draw are generated — per triangle the
//     count whose ratio can reach 1 at any corner, and only inside sub-triangles that touch the
//     view frustum. They appear at size 0 and grow with the same smooth rule as baked points,
//     so zooming in is as frame-coherent as zooming out.
//   - Hand-over (render-mesh domain only): two even point sets laid over each other are not
//     even, so where the size rule wants the surface 1.1x to 1.4x denser than the bake, the
//     baked points fade out (ink times 1 - h, h smooth in log density) while the sequence
//     takes over their share; deeper close-ups are drawn by the sequence alone.
//   - Memory: a fixed budget taken at load. When a frame needs more, every triangle keeps the
//     same fraction of its extra points (the coarsest, so the order still holds) and tone in the
//     refined areas drops by that fraction; RefinementStats::budget_scale reports it.
#pragma once
#include <cstdint>
#include <glm/glm.hpp>
#include <memory>

#include "runtime/asset.h"
#include "runtime/memory.h"
#include "runtime/refinement_cull.h"
#include "runtime/refinement_sequence.h"
#include "runtime/stipple_size.h"

namespace stipple {

// Per-vertex values of one frame that the refinement interpolates over triangles.
struct RefinementVertex {
    glm::vec4 clip;    // clip-space position
    float need;        // max(N.V, 0) * ink: the density the size rule asks for, without 1/w^2
    float need_back;   // the same for the flipped normal (double-sided triangles seen from behind)
    uint32_t outside;  // frustum outcode: bit set per clip plane the vertex lies beyond
};

// Per-triangle data computed once at load from the bind pose, and per-vertex scratch.
struct RefinementMesh {
    uint32_t triangle_count = 0;
    Buffer<float> bind_area;          // per triangle
    Buffer<float> frame;              // per triangle: 2D isometric corners B.x, C.x, C.y
    Buffer<uint8_t> root_depth;       // longest-edge bisections before the sequence
    Buffer<float> density;            // baked points per unit bind area, per triangle
    Buffer<float> phase;              // rank offset of the first extra point, (0, 1]
    Buffer<float> fade;               // per frame: size factor of the baked points here
    Buffer<RefinementVertex> vertex;  // per vertex, rewritten every frame
    // The same frame's outcodes, front need and clip w again, small and apart: the per-triangle
    // tests read these (cache resident), the whole RefinementVertex only where a triangle refines.
    Buffer<uint8_t> vertex_outside;
    Buffer<float> vertex_need, vertex_w;
    float finest_density = 0.0f;  // rho0: baked points per unit bind area, finest level
    bool hand_over = true;        // baked points fade in close-ups (mesh domain)
    RefinementCull cull;          // points domain with its host mesh: runtime/refinement_cull.h
};

// Extra points of one frame, structure of arrays. Positions/normals/radius go straight into the
// caller's point arrays after the baked points; triangle and index name each point (stable ids).
struct RefinedPoints {
    uint32_t capacity = 0;
    uint32_t count = 0;
    float* positions = nullptr;  // 3 per point
    float* normals = nullptr;    // 3 per point
    float* radius = nullptr;     // current relevance radius (region = radius^2)
    uint32_t* triangle = nullptr;
    uint32_t* index = nullptr;  // k: rank of the point in its triangle's sequence
};

struct RefinementStats {
    uint64_t wanted = 0;        // extra points the frame asked for (after frustum culling)
    uint32_t generated = 0;     // extra points generated
    float budget_scale = 1.0f;  // < 1 when the budget bound
};

// What the refinement's triangles are: the render mesh (baked points hosted on them, hand-over
// to the sequence in close-ups), or a triangulation of the baked points themselves
// (runtime/point_triangulation.h: corners are baked points, no hand-over).
enum class RefinementDomain { mesh, points };

// Builds the per-triangle tables of `mesh` (the domain's bind pose): finest_density = baked
// points / bind surface area, per triangle the local baked density, root cells, first-point
// phases (bind_point_positions: the baked points, 3 floats each). With the points domain and
// `host` (the render mesh the baked points lie on, bind pose), also the clusters of
// runtime/refinement_cull.h for refine_points_culled. Fails only with out_of_memory.
[[nodiscard]] Status refinement_init(RefinementMesh* r, const MeshView& mesh,
                                     const PointsView& points, const float* bind_point_positions,
                                     RefinementDomain domain = RefinementDomain::mesh,
                                     const MeshView* host = nullptr);

// Generates the frame's extra points: `positions`/`normals` are the posed mesh vertices
// (3 floats each); `stretch` false keeps bind-pose regions (relevance updates off);
// `double_sided` (per triangle, or null) marks triangles drawn from both sides, whose extra
// points get their normal turned toward the viewer (runtime/double_sided.h).
void refine_points(RefinementMesh* r, const MeshView& mesh, const float* positions,
                   const float* normals, const uint8_t* double_sided, const SizeParams& params,
                   bool stretch, RefinedPoints* out, RefinementStats* stats);

// refine_points over the clusters the last refinement_cull left active only (r->cull: points
// domain): the per-vertex pass over their corners (r->cull.list), the per-triangle pass over
// their triangles, both over `pool` (null: the caller alone). Byte-identical to refine_points
// when every skipped cluster could add no point, which refinement_cull guarantees.
void refine_points_culled(RefinementMesh* r, const MeshView& mesh, const float* positions,
                          const float* normals, const SizeParams& params, bool stretch,
                          RefinedPoints* out, RefinementStats* stats, ThreadPool* pool);

// Clip-space w of the near plane along the view ray (the least w the refinement divides by).
float refinement_near_w(const SizeParams& params);

// Hand-over (mesh domain only), after size_stipples: scales each baked point's diameter by
// its host triangle's fade from the last refine_points (1 where the bake alone draws).
void fade_baked_points(const RefinementMesh& r, const PointsView& points, float* size);

}  // namespace stipple
