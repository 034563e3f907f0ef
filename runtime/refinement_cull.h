// An exact, cheap test of where the run-time refinement (runtime/point_refinement.h) can add
// points this frame, taken before the baked points it is built on are placed (thesis §9.1.1:
// traverse only the sections of the hierarchy the rendition needs; §4.5: the refinement).
//
// The points domain's triangles (corners: baked points) are grouped at load into spatial
// clusters. refine_points adds a point to triangle t only if
//     stretch_t * need_t * focal^2 / (dot area * w_t^2) >= lower_t
// (lower_t = rho0 + phase_t / bind area_t; need_t = max N.V * ink at its corners; w_t the
// nearest clip w of its corners, at least the near plane's; stretch_t its posed / bind area).
// Per cluster and frame, each factor gets an upper bound from the posed render mesh alone:
//   - a baked point lies in its host triangle (barycentric), so the cluster's corners lie in
//     the box of its hosts' posed vertices: frustum planes and the nearest w from that box;
//   - need <= N.V * ink <= the N.V and ink bounds of the hosts' vertex normals (a corner's
//     normal blends its host's: runtime/normal_bounds.h), or the frame's largest ink;
//   - stretch: the posed map is affine on each render triangle, so a segment inside one
//     stretches at most by its largest singular value sigma (per frame, from the bind and
//     posed Gram matrices). Each edge of a domain triangle is bounded at load by a path
//     inside one, two (through their shared edge or vertex) or three render triangles (through
//     a mesh edge between the hosts): |posed edge| <= L g, L the largest sigma over the
//     cluster's path triangles, g the bind path length; so posed area <= L^2 g_i g_j / 2 for
//     any two edges. An edge without such a path makes its cluster never skipped.
// A cluster whose bound stays under min_t lower_t (over its triangles) is skipped; no point of
// it could have been added, so the stage's output is byte-identical whether it runs or not
// (tests/runtime/test_refinement_cull.cpp checks that against the full stage).
// Once the active clusters' corners are placed, refinement_cull_posed tests them again with
// each triangle's exact posed area in place of the stretch bound (which sums worst cases over
// the cluster's paths: 2-24x the largest stretch on the CesiumMan walk), before any corner is
// classified (docs/performance.md, eleventh round).
#pragma once
#include <cstdint>

#include "runtime/asset.h"
#include "runtime/memory.h"
#include "runtime/status.h"
#include "runtime/stipple_size.h"

namespace stipple {

struct ThreadPool;

// A domain edge's bind path crosses at most this many render triangles.
constexpr uint32_t kCullSpanPerEdge = 6;
// Relative slack on every bound against the full stage's float rounding.
constexpr float kCullSlack = 1e-3f;

struct RefinementCull {
    uint32_t cluster_count = 0;                // 0: no culling (mesh domain, or no host mesh given)
    uint32_t point_count = 0;                  // domain vertices (baked points)
    Buffer<uint32_t> triangle_cluster;         // per domain triangle
    Buffer<uint32_t> tri_begin, triangles;     // per cluster: its domain triangles
    Buffer<uint32_t> host_begin, host_vertex;  // per cluster: render vertices of its hosts
    Buffer<uint32_t> span_begin, span;         // per cluster: render triangles of its paths
    Buffer<uint32_t> corner_begin, corner;     // per cluster: its triangles' corners
    Buffer<float> lower_stretch;  // per cluster: min over its triangles of lower_t / q_t
    Buffer<float> lower_rest;     // per cluster: min lower_t (relevance updates off)
    // Per cluster, the largest over its triangles of 1 / lower_t, (|e1| + |e2|) / (2 A lower_t)
    // and 1 / (2 A lower_t): the second bound on the stretch (refinement_cull.cpp).
    Buffer<float> affine;
    Buffer<float> min_path;  // per cluster: its triangles' shortest edge path bound
    // Along `triangles`: 2 bind area_t lower_t (+inf where the triangle has no bind area: the
    // full stage skips it), refinement_cull_posed's limit on |posed e1 x e2| times the density.
    Buffer<float> cross_limit;
    Buffer<float> bind_gram;  // per render triangle: e1.e1, e1.e2, e2.e2 (bind pose)
    // Pairs of render vertices at one bind position (seams); paths cross them only while both
    // pose to the same point.
    Buffer<uint32_t> seam;
    uint32_t seam_count = 0;
    // Per frame.
    Buffer<uint8_t> active;        // per cluster
    Buffer<uint8_t> candidate;     // per domain triangle: refine_points_culled's probe
    Buffer<uint32_t> list;         // the active clusters' corners, each once (point_count)
    Buffer<uint64_t> stamp;        // bit per corner: already listed
    Buffer<float> sigma;           // per render triangle: its squared stretch bound this frame
    Buffer<uint32_t> sigma_frame;  // per render triangle: the frame sigma was computed in
    Buffer<uint32_t> sigma_todo;   // a cluster's span triangles whose sigma is not yet computed
    uint32_t frame = 0;
    // Per active cluster: an upper bound on max_t stretch_t / lower_t over its triangles (1 /
    // min lower_t with relevance updates off; INFINITY: none), the factor the cull multiplied
    // its density bound by; refine_points_culled multiplies the density its classified corners
    // give (their exact need and nearest w) by it, and probes only the clusters it cannot skip
    // (probed: 1).
    Buffer<float> ratio_bound;
    // Per active cluster: the bound on need_t focal^2 / (dot area w_t^2) the cull took (with its
    // slack; +inf: none), for refinement_cull_posed.
    Buffer<float> density_bound;
    Buffer<uint8_t> probed;
    Buffer<uint32_t> active_list;  // the active clusters, ascending (active_count)
    Buffer<uint32_t> refine_list;  // refine_points_culled: the triangles it refines, ascending
    uint32_t active_count = 0;
    uint32_t list_count = 0;
};

// Builds the clusters of the points domain `domain` (its vertices are the baked points, bind
// pose; `bind_area`, `density` and `phase` per domain triangle as refinement_init set them)
// over the render mesh `host` (bind pose) the baked `points` lie on. Fails only with
// out_of_memory.
[[nodiscard]] Status refinement_cull_init(RefinementCull* c, const MeshView& domain,
                                          const MeshView& host, const PointsView& points,
                                          const float* bind_area, const float* density,
                                          const float* phase);

// Per frame: marks the clusters where refine_points could add a point (`posed`: the render
// mesh's posed vertices, 3 floats each; `stretch` as refine_points'), lists their corners
// into c->list and returns how many clusters are active. near_w: refinement_near_w(params).
// posed_normals (the posed vertex normals; null where the mesh has double-sided triangles, or
// to leave it out) bounds need_t by the hosts' normals (runtime/normal_bounds.h).
uint32_t refinement_cull(RefinementCull* c, const MeshView& host, const float* posed,
                         const float* posed_normals, const SizeParams& params, bool stretch,
                         float near_w);

// After refinement_cull (stretch on: relevance updates), with the listed corners placed
// (`positions`: the points domain's vertices, this frame): keeps the active clusters where
// some triangle t passes density_bound * |posed e1 x e2| >= 2 bind area_t lower_t (with
// the cull's slack; the full stage's test with the exact stretch and the cull's need and w
// bounds), relists their corners and returns how many are active.
uint32_t refinement_cull_posed(RefinementCull* c, const MeshView& domain, const float* positions);

}  // namespace stipple
