// The per-point cull after place, fused with relevance and size (issue 9 items 1, 2; thesis
// §9.1.1 "screen-space culling", Alg. 6.4, Alg. 3.2).
//
// The clusters' cut (runtime/point_clusters.h) bounds a whole cluster with its nearest depth,
// N.V <= 1, its least lighting and its largest stretch, so most of the points it runs still
// get size 0 (CesiumMan's walk at 100k: 37,879 run for ~4,400 drawn). Once a run point is
// placed its own clip w, N.V and lighting are known; only its radius is not (Alg. 6.4 reads
// the neighbours). With the radius replaced by the cut's bound for that point, R = its bind
// radius times its cluster's stretch (area measure: the area stretch times 1.1; mean
// distance: the edge stretch times 1.02; 1 on a static mesh) over the cut's 0.99 margin, or
// the rest radius itself with relevance updates off, Alg. 3.2's size is an upper bound of the
// point's size: every operation of the size rule (r f / w, squared, times N.V, dot area over
// it, ink over that, minus 1, over the slope, clamped) is monotonic in the radius under
// correctly rounded float arithmetic. Where that bound is 0 (Alg. 3.2's size-0 condition:
// tone ratio <= 1, or the point faces away / lies behind the eye), the point's size is 0 and
// it skips relevance and size. A NaN bound keeps the point. The other points get Alg. 6.4's
// radius and Alg. 3.2's size in the same pass, each point read once.
//
// The exact part: points facing away (N.V <= 0) or behind the eye (w <= 0) get size 0
// whatever their radius, and could skip relevance and size (about 35-45% of the run points on
// CesiumMan's walk). Two ways to run it, both opt-in (PointCullMode): its own pass listing the
// kept points (point_facing_list) before the separate relevance and size kernels, or fused
// with them. Neither beat the separate kernels over every run point on this 2-core machine
// (docs/performance.md), so frames run those. The radius bound's test is opt-in too
// (point_cull_radius_bound): per point it does NOT hold (see there); the cut gets away with
// the same radius bound only through its cluster-wide slack. Paintstroke roots
// (PointClusters::forced) always get their radius (the stroke stage reads it). The sizes of
// culled points are not written: the caller clears the run points' sizes before
// (frame_point_stages.cpp), and their radii keep the last value computed for them (the rest
// pose's from the first level-of-detail frame on), which nothing reads (only drawn dots'
// sizes and stroke roots' radii are read).
#pragma once
#include <cstdint>

#include "runtime/point_clusters.h"
#include "runtime/point_simd.h"
#include "runtime/point_stages.h"

namespace stipple {

// What the fused pass reads once per frame.
struct CullKernelFrame {
    SizeKernelFrame sizing;  // row_w, focal, the ink table, the params
    const PointsView* points = nullptr;
    const float* positions = nullptr;  // placed this frame, 3 floats per point
    const float* normals = nullptr;
    const float* scale = nullptr;            // relevance_scale (point_placement.h)
    const float* fallback_radius = nullptr;  // rest radii: no neighbours, or relevance off
    const float* area_bound = nullptr;       // PointClusters::point_area_bound
    const float* line_bound = nullptr;       // PointClusters::point_line_bound
    const uint32_t* point_cluster = nullptr;
    const float* cluster_factor = nullptr;  // PointClusters::cluster_factor, 2 per cluster
    const uint64_t* forced_bits = nullptr;
    bool relevance_update = true;
    bool radius_bound = false;  // point_cull_radius_bound(): also the radius bound's test
    float* radius = nullptr;    // outputs, written for the kept points only
    float* size = nullptr;
    CullKernelFrame(const PointStageFrame& f, const PointClusters& c, bool relevance_update);
};

// The cull's radius bound R of point i (see above).
inline float cull_radius_bound(const CullKernelFrame& k, uint32_t i) {
    if (!k.relevance_update) return k.fallback_radius[i];
    const float* f = k.cluster_factor + size_t(k.point_cluster[i]) * 2;
    const float area = k.area_bound[i] * f[0], line = k.line_bound[i] * f[1];
    return area < line ? line : area;  // std::max(area, line)
}

// The fused pass over the points list[begin .. end) (a thread's range); returns how many it
// kept. Scalar code (the baseline path) and AVX2 (runtime/point_simd_avx2.cpp, only when
// point_simd() is avx2): the same kept points and the same bits.
uint32_t cull_relevance_size(const CullKernelFrame& k, const uint32_t* list, uint32_t begin,
                             uint32_t end);
uint32_t cull_relevance_size_avx2(const CullKernelFrame& k, const uint32_t* list, uint32_t begin,
                                  uint32_t end);

// The pass over list[0 .. count) on the pool's threads and the run-time SIMD path; returns
// how many points it kept (sized).
uint32_t point_stage_cull_relevance_size(ThreadPool* pool, const PointStageFrame& f,
                                         const PointClusters& c, bool relevance_update,
                                         const uint32_t* list, uint32_t count);

// The exact part of the cull alone, for the separate relevance and size kernels: lists into
// kept, in their order, the points of list[0 .. count) that face the eye and lie in front of
// it (N.V > 0 and clip w > 0, computed as the size rule computes them), and the forced ones
// (paintstroke roots); returns how many. Every other point of the list has size 0 whatever its
// radius (Alg. 3.2). kept may not alias list.
uint32_t point_facing_list(const PointStageFrame& f, const PointClusters& c, const uint32_t* list,
                           uint32_t count, uint32_t* kept);

// Which per-point cull frames run, for the whole process (call between frames; the benches'
// A/B). off (the default): the separate relevance and size kernels over every run point.
// facing: point_facing_list, then those kernels over the kept points (the list pass and the
// kernels' gathers over a sparse list cost more than the 35-45% of the points they skip:
// relevance + size 0.85 against 0.76 ms at 100k, docs/performance.md). fused:
// point_stage_cull_relevance_size (AVX2: 8 points' facing and sizes a step, the kept lanes'
// relevance one point at a time), slower still.
enum class PointCullMode { off, facing, fused };
void point_cull_set_mode(PointCullMode mode);
PointCullMode point_cull_mode();

// The radius bound's test (off by default; benches and tests turn it on). NOT exact: on
// CesiumMan's walk (60k points, 1280x720) 4-13 run points a frame, the coarsest ones, get a
// recomputed radius 1.3-2.3x their bind radius times their cluster's stretch (their relevant
// neighbours lie across joints: limbs moving rigidly change the offsets' second moment without
// stretching any triangle), and one dot was lost in tests/frames/test_lod.cpp's back view. The
// cut keeps those points only through its cluster-wide slack (nearest depth, N.V <= 1, least
// lighting). Off, the cull skips exactly the points Alg. 3.2 gives size 0 whatever their
// radius: those facing away (N.V <= 0) or behind the eye (w <= 0).
void point_cull_radius_bound(bool on);
bool point_cull_radius_bound_enabled();

}  // namespace stipple
