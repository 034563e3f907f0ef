// bench/ab_kernels: one tree's kernels behind a namespace-free entry (build.sh).
#include <vector>

#include "ab.h"
#include "runtime/point_simd.h"
#ifndef FRAME
#define FRAME SizeFrame
#endif
// RELEVANCE_SIZE: the fused kernel to time (build.sh: NEW_RELEVANCE_SIZE=relevance_size_avx512).
#ifndef RELEVANCE_SIZE
#define RELEVANCE_SIZE relevance_size_avx2
#endif
#define CAT2(a, b) a##b
#define CAT(a, b) CAT2(a, b)
void STAGES(const AbState& s, int part) {
    const auto& points = *static_cast<const stipple::PointsView*>(s.points);
    const auto& params = *static_cast<const stipple::SizeParams*>(s.params);
    if (part & 1)
        stipple::place_points_avx2(points, s.indices,
                                   static_cast<const stipple::PointHost*>(s.hosts), s.pairs,
                                   s.placed, 0, s.placed_count, s.positions, s.normals);
    if (!(part & 2)) return;
    const stipple::FRAME frame(params);
    // This tree's own neighbour records (their layout changed in the fifteenth round).
    static std::vector<uint32_t> quads;
    if (s.quads && quads.empty()) {
        quads.resize(size_t(points.point_count) * 4);
        if (!stipple::quad_neighbours(points, quads.data())) quads.clear();
    }
    stipple::RELEVANCE_SIZE(points, quads.empty() ? nullptr : quads.data(), frame, s.positions,
                            s.normals, s.scale, s.fallback, s.run, 0, s.run_count, s.radius,
                            s.size);
}
