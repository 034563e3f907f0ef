// Level of detail and culling for the point stages (thesis §9.1.1, issue 9 item 3).
//
// The thesis traverses the whole point hierarchy every frame and notes (§9.1.1) that only the
// sections needed for the rendition should be: view-frustum culling, back-face culling and
// screen-space culling. Here the baked points are grouped once, at load, into spatial clusters
// (§9.1.2's "parts of the model", sorted so each cluster's points are one contiguous run of a
// permutation). Per frame, before place / relevance / size (Alg. 6.3, 6.4, 3.2):
//   - a cluster whose posed bound lies outside the view frustum is skipped;
//   - a cluster on single-sided triangles whose every vertex normal faces away from every
//     point of its bound is skipped (its points' Gouraud normals all face away: size 0);
//   - every other cluster is cut at the prefix whose relevance radius can still give a dot:
//     the points are coarse to fine within a cluster (the asset's global order, kept by a
//     stable bucket sort), and Alg. 3.2 gives size 0 to a point whose projected region of
//     influence is below dot area / ink. With the nearest depth in the cluster, the darkest
//     ink the cluster's least lighting asks for, a bound on N.V (the cone of the cluster's
//     vertex normals against the directions to the eye: clusters seen at a grazing angle are
//     cut earlier) and a bound on how much Alg. 6.4's recompute can grow a radius (the largest
//     triangle stretch where the cluster's points and their neighbours lie: area for the area
//     measure, edges for the mean distance), every point past the cut would have had size 0.
// The clusters are computed deterministically from the asset at load (nothing is added to the
// file format; the bake's spatial clusters would be the same computation, done earlier).
// A kept point's relevance reads its relevant neighbours' positions, so they are placed too
// (the closure), whether their own cluster was cut or culled. Points not run keep size 0.
#pragma once
#include <algorithm>
#include <cstdint>

#include "runtime/asset.h"
#include "runtime/memory.h"
#include "runtime/status.h"
#include "runtime/stipple_size.h"
#include "runtime/thread_pool.h"

namespace stipple {

// What the last selection did.
struct LodStats {
    uint32_t clusters = 0;
    uint32_t culled_frustum = 0;  // clusters outside the view frustum
    uint32_t culled_back = 0;     // clusters entirely back-facing
    uint32_t cut = 0;             // clusters run only up to a prefix
    uint32_t points_run = 0;      // points placed, relevance recomputed and sized
    uint32_t points_placed = 0;   // points_run plus the neighbours they read
};

struct PointClusters {
    uint32_t cluster_count = 0;
    uint32_t point_count = 0;
    // Cluster c holds the baked points order[point_begin[c] .. point_begin[c + 1]), ascending
    // (coarse to fine).
    Buffer<uint32_t> point_begin, order;
    // Along `order`: the largest radius from this point to its cluster's end (non-increasing
    // within a cluster, so a cut is one binary search): `bound` over the points Alg. 6.4
    // re-scales by the area measure, `line_bound` by the mean distance (bind radii; times the
    // frame's stretch they bound the recomputed radii), `rest_bound` the rest-pose radii
    // (relevance updates off).
    Buffer<float> bound, line_bound, rest_bound;
    Buffer<uint32_t> vertex_begin, vertices;  // per cluster: its triangles' vertices
    Buffer<uint32_t> reach_begin, reach;  // per cluster: triangles its points and neighbours lie on
    // Deforming: per cluster, reach[reach_begin[k] .. reach_split[k]) are the triangles with a
    // non-degenerate bind pose, the rest degenerate (their area stretch is the edge stretch).
    Buffer<uint32_t> reach_split;
    Buffer<uint8_t> single_sided;  // per cluster: 1 if back-face culling may skip it
    bool deforming = false;        // skinned or morphed: stretch is measured
    Buffer<float> bind_gram;       // deforming: 3 per triangle (e1.e1, e1.e2, e2.e2)
    // Deforming, per frame, per triangle: the squares of the stretches before their roots (the
    // roots are monotonic, so a cluster takes the largest square and one root): area_ratio the
    // posed / bind squared area (its fourth root is the area stretch), edge_ratio the largest
    // squared edge ratio (its square root is the edge stretch).
    Buffer<float> area_ratio, edge_ratio;
    // Along `order`: the relevant neighbours of order[j] that the cluster's first j + 1 points
    // do not already hold (other clusters' points, finer points of its own), so the placed set
    // of a prefix is the prefix plus these (closure_begin: point_count + 1 offsets).
    Buffer<uint32_t> closure_begin, closure;
    Buffer<uint32_t> forced;  // points run every frame (paintstroke roots)
    uint32_t forced_count = 0;
    Buffer<uint64_t> forced_bits;  // the same as a bit set (64 points a word)
    // Per cluster, per frame (scratch of the selection over the thread pool): the prefix kept
    // and what the tests decided (LodStats).
    Buffer<uint32_t> keep;
    Buffer<uint8_t> keep_kind;
    // Per frame: the points run (placed, relevance, sized) and the points placed (the run ones
    // and the neighbours they read), both ascending; bit sets of both (64 points a word).
    // (Ascending beats cluster by cluster: measured on the horse, placing in cluster order read
    // fewer vertex lines but scattered the writes, 1.7x slower.)
    Buffer<uint32_t> run, placed;
    uint32_t run_count = 0, placed_count = 0;
    Buffer<uint64_t> run_bits, placed_bits;
    uint32_t word_count = 0;
    Buffer<uint32_t> rest;  // scratch list of point_count (the points outside a set)
    LodStats stats;
};

// Whether a triangle's bind pose has an area to measure its stretch against, from its bind
// Gram entries (e1.e1, e1.e2, e2.e2); otherwise its area stretch is its edge stretch.
inline bool bind_area_defined(const float* gram) {
    const float a = gram[0], b = gram[1], cc = gram[2];
    const float det = a * cc - b * b;
    return det > 1e-6f * (a + cc) * (a + cc);
}

// Builds the clusters of `asset`'s baked points: triangles grouped by dominant joint (skinned
// meshes), the direction of their bind normal (54 buckets: a cube face and a 3 x 3 cell on it, so
// a cluster faces one way and whole clusters on the far side fail the back-face test) and a grid
// cell of their bind-pose centroid; per cluster
// its vertices, its reach and the radius bounds. `baked_radius` holds the radii the stages use in
// the bake's space (Pipeline::baked_radius), `rest_radius` the rest-pose radii (point_count each).
// Fails only with out_of_memory.
[[nodiscard]] Status point_clusters_init(PointClusters* c, const Asset& asset,
                                         const float* baked_radius, const float* rest_radius);

// What one frame's selection sees.
struct LodFrame {
    const float* vertex_positions = nullptr;  // posed mesh, 3 per vertex
    const float* vertex_normals = nullptr;
    const float* vertex_pairs = nullptr;  // the same as runtime/point_simd.h's pair_vertices
    const SizeParams* params = nullptr;   // camera, tone, dot size of this frame
    int viewport_width = 0;
    bool relevance_update = true;  // Alg. 6.4 on: radii follow the stretch
    // Points from this index on are sized even outside the frustum (where their dots are not
    // drawn) when the cut keeps them: the pipeline asks whether the finest quarter of the bake
    // has a size anywhere to decide on the run-time refinement (hierarchy_running_out).
    uint32_t size_from = UINT32_MAX;
    // The clusters' tests and the triangles' stretches split over this pool (null: the
    // caller alone); the selection is the same for any thread count.
    ThreadPool* pool = nullptr;
};

// Chooses the frame's points: c->run[0 .. run_count) are placed, re-scaled and sized,
// c->placed[0 .. placed_count) (a superset) placed.
void point_clusters_select(PointClusters* c, const Asset& asset, const LodFrame& frame);

// Deforming clusters: each triangle's squared stretches (area_ratio, edge_ratio) from the bind
// pose to `posed` (3 floats per vertex of m, the asset's mesh); point_clusters_select runs it.
void point_clusters_stretch(PointClusters* c, const MeshView& m, const float* posed);

// std::partition_point's index over a[0 .. n) for a predicate true on a prefix, searched
// outward from `hint` in doubling steps: the cut moves little from frame to frame, so a few
// probes near last frame's cut replace a binary search's cache misses over the whole range.
template <typename Pred>
inline uint32_t partition_from(const float* a, uint32_t n, uint32_t hint, Pred pred) {
    hint = std::min(hint, n);
    uint32_t lo = 0, hi = n;          // the index lies in [lo, hi]; a[hi] fails when hi < n
    if (hint < n && pred(a[hint])) {  // past the hint: a[lo - 1] passes
        lo = hint + 1;
        uint32_t step = 1;
        while (lo + step - 1 < n && pred(a[lo + step - 1])) lo += step, step *= 2;
        hi = std::min(lo + step - 1, n);
    } else {  // at or before it
        hi = hint;
        uint32_t step = 1;
        while (hi >= step && !pred(a[hi - step])) hi -= step, step *= 2;
        lo = hi >= step ? hi - step + 1 : 0;
    }
    return lo + uint32_t(std::partition_point(a + lo, a + hi, pred) - (a + lo));
}

// Sets size[i] = 0 for the points the last selection ran (before a new selection).
void point_clusters_clear_sizes(const PointClusters& c, float* size);

// Lists into c->rest, ascending, the baked points outside the last selection's placed set
// (`placed` true) or run set (false); returns how many.
uint32_t point_clusters_rest(PointClusters* c, bool placed);

}  // namespace stipple
