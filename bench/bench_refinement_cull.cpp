// The refinement cull (runtime/refinement_cull.h) on an asset's clip 0 at 30 fps, 1280x720
// (bench/ab_common.h's frame), 1 thread: its two paths for sigma^2 (runtime/refinement_sigma.h),
// AVX2 and scalar, alternated in one process on the same posed frame, blocks of 10 calls, and
// the clusters each keeps compared (the same, or exit 2). Reports, per frame where some cluster
// stays active (where the stage goes on past the cull), ms per call, min and median, and the
// ratio. On a CPU without AVX2 both runs are the scalar code.
//   stipple_bench_refinement_cull FILE.stip [BLOCKS]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <vector>

#include "bench/ab_common.h"
#include "runtime/point_simd.h"
#include "runtime/refinement_cull.h"

namespace {

using namespace stipple;
using Clock = std::chrono::steady_clock;

struct Run {
    std::vector<double> ms;
    uint32_t active = 0, listed = 0;
};

void cull_calls(Pipeline* p, const float* normals, Run* run) {
    RefinementCull& c = p->refinement.cull;
    for (int r = 0; r < 10; ++r) {
        const Clock::time_point start = Clock::now();
        run->active =
            refinement_cull(&c, p->asset->mesh, p->vertex_positions.get(), normals, p->size_params,
                            p->config.relevance_update, refinement_near_w(p->size_params));
        run->ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
    }
    run->listed = c.list_count;
}

double at(std::vector<double> v, double q) {
    std::sort(v.begin(), v.end());
    return v[size_t(q * double(v.size() - 1))];
}

}  // namespace

int main(int argc, char** argv) {
    Asset asset;
    if (!bench::ab_load(argc, argv, "stipple_bench_refinement_cull FILE.stip [BLOCKS]", &asset))
        return 1;
    const int blocks = argc > 2 ? std::max(1, std::atoi(argv[2])) : 100;
    bench::HeadlessGl gl;
    if (!bench::ab_context(&gl)) return 1;
    auto p = std::make_unique<Pipeline>();
    if (!pipeline_init(p.get(), asset, gl.gl, bench::ab_config()).ok()) return 1;
    if (p->refinement.cull.cluster_count == 0) {
        std::printf("no refinement cull on this asset (mesh domain or refinement off)\n");
        return 0;
    }
    const float* normals = asset.sides.triangle_double_sided ? nullptr : p->vertex_normals.get();
    const PointSimd detected = point_simd_detected();
    std::printf("%u clusters; sigma^2 paths: %s against baseline; ms per call (min / median)\n\n",
                p->refinement.cull.cluster_count, point_simd_name(detected));
    std::printf("| t (s) | active | baseline | %s | %s / baseline (min, median) |\n",
                point_simd_name(detected), point_simd_name(detected));
    std::printf("| ---: | ---: | ---: | ---: | ---: |\n");
    int differ = 0;
    for (int frame = 0; frame < 30; ++frame) {
        AnimationState state;
        state.clip = 0;
        state.time = float(frame) / 30.0f;
        pipeline_update(p.get(), state, nullptr);
        Run run[2];
        point_simd_force(PointSimd::baseline);
        cull_calls(p.get(), normals, &run[0]);
        if (run[0].active == 0) continue;
        for (int b = 0; b < blocks; ++b)
            for (int k = 0; k < 2; ++k) {
                point_simd_force(k == 0 ? PointSimd::baseline : detected);
                cull_calls(p.get(), normals, &run[k]);
            }
        point_simd_force(detected);
        differ += run[0].active != run[1].active || run[0].listed != run[1].listed;
        std::printf("| %.3f | %u | %.4f / %.4f | %.4f / %.4f | %.2f, %.2f |\n", state.time,
                    run[1].active, at(run[0].ms, 0), at(run[0].ms, 0.5), at(run[1].ms, 0),
                    at(run[1].ms, 0.5), at(run[1].ms, 0) / at(run[0].ms, 0),
                    at(run[1].ms, 0.5) / at(run[0].ms, 0.5));
    }
    std::printf("\nframes whose active clusters differ between the paths: %d\n", differ);
    return differ ? 2 : 0;
}
