// Regions of influence that follow the surface density of each coarse prefix (issue 7, tone
// 0.1 on small objects; docs/tone.md, "Small objects").
//
// The bake gives the point of rank i the region A / (i + 1) (thesis §3.1.1, §5.3's "radius per
// level"): exact where the prefix [0, i] is spread evenly *over the surface*. Sample
// elimination spreads it evenly in 3-D distance, which is the same thing only where the surface
// is flat at the prefix's spacing. On parts thinner than that spacing (a horse's legs, ears,
// tail; RiggedFigure's limbs) a 3-D Poisson-disk set keeps one point per spacing *along* the
// part, far more than its area asks for: the first 64 points of the horse put 1.27x their
// share on what zoom 0.25 draws as the outline ring and 0.81x in the interior. Alg. 3.2 draws
// the first ~50 points there at tone 0.1, so the inside of the object reads 8-17% light.
//
// The fix measures the density of each coarse prefix where its newest point lies: the ball
// around point i holding its m nearest points of the prefix [0, i] covers, in surface area,
// the share of the *whole* hierarchy (even over the surface at its finest levels) that falls
// inside it. Region_i = r_i^2 (i + 1) share / (m + 1/2) (the m-th neighbour lies on the rim):
// A / (i + 1) where the prefix is even, smaller on thin parts (drawn later), larger on the
// broad ones (drawn sooner). The estimator's bias is measured on ranks where the hierarchy is
// even. Ranks past `limit` (even on every corpus asset: the horse's from rank 256 on) keep
// their regions. With it tone 0.1 at zoom 0.25 holds within 6% (tests/frames/
// test_tone_small.cpp); frames at zoom >= 1 do not change.
//
// Applied when a stipple pipeline starts (pipeline_init, runtime/frame_pipeline.cpp): the
// corrected radii are the pipeline's own copy (Pipeline::baked_radius), which every stipple
// stage reads (relevance_scale, the rest radii of recompute_relevance, the LOD clusters' bounds,
// the GPU path's buffers), so the LOD cut stays exact. The asset keeps the radii as baked:
// paintstrokes and particles (GI'01's own density law) read those. A uniform grid over the rest
// positions makes it O(count + limit^2) (docs/tone.md, "Small objects", for the cost); the
// result equals the brute force's bit for bit (tests/runtime/test_region_density.cpp).
#pragma once
#include <cstdint>

namespace stipple {

struct RegionDensityParams {
    uint32_t neighbours = 2;  // m: prefix points in the density ball
    uint32_t limit = 1024;    // ranks corrected: [1, limit); the rest are even (measured)
};

// Rewrites radius[i] for i in [1, min(limit, count)) from the points' rest positions (3 per
// point, ordered coarse to fine) and their radii as baked. Takes O(count + limit^2) time on a
// surface and a scratch grid (about 32 bytes per point, from the current allocator,
// runtime/memory.h) released on return; does nothing when count < 4 * limit, neighbours is 0
// or more than 32, a coordinate is not finite or all points coincide. False only when the
// scratch could not be had (the radii are then unchanged).
[[nodiscard]] bool density_corrected_radii(const float* positions, uint32_t count,
                                           const RegionDensityParams& params, float* radius);

}  // namespace stipple
