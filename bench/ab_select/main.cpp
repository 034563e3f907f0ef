// bench/ab_select: the level-of-detail selection (runtime/point_clusters_select.cpp) of two
// source trees in one process, alternating call by call on two pipelines of the same asset,
// over `frames` frames of clip 0 (1280x720, 1 thread); after each frame the two selections'
// run and placed lists and cuts are compared (build.sh says how to build it). The PointClusters,
// Asset and LodFrame layouts must be the same in both trees (members added at the end only).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <vector>

#include "bench/ab_common.h"
#include "runtime/frame_pipeline.h"
#include "runtime/point_clusters.h"

#define AB_SELECT_DECLARE(ns)                                                  \
    namespace ns {                                                             \
    struct PointClusters;                                                      \
    struct Asset;                                                              \
    struct LodFrame;                                                           \
    void point_clusters_select(PointClusters*, const Asset&, const LodFrame&); \
    }
AB_SELECT_DECLARE(stipple_old)
AB_SELECT_DECLARE(stipple_new)

namespace {

using Clock = std::chrono::steady_clock;

// The selection's input for pipeline p's last update, as lod_point_stages builds it.
stipple::LodFrame lod_frame(const stipple::Pipeline& p) {
    stipple::LodFrame f;
    f.vertex_positions = p.vertex_positions.get();
    f.vertex_normals = p.vertex_normals.get();
    f.vertex_pairs = p.vertex_pairs.get();
    f.params = &p.size_params;
    f.viewport_width = p.viewport_width;
    f.relevance_update = p.config.relevance_update;
    const uint32_t baked = p.asset->points.point_count;
    if (p.config.refinement_budget > 0) f.size_from = baked - baked / 4;
    return f;
}

double select_ms(bool old, stipple::Pipeline* p, const stipple::LodFrame& f) {
    const Clock::time_point t0 = Clock::now();
    if (old)
        stipple_old::point_clusters_select(
            reinterpret_cast<stipple_old::PointClusters*>(&p->clusters),
            reinterpret_cast<const stipple_old::Asset&>(*p->asset),
            reinterpret_cast<const stipple_old::LodFrame&>(f));
    else
        stipple_new::point_clusters_select(
            reinterpret_cast<stipple_new::PointClusters*>(&p->clusters),
            reinterpret_cast<const stipple_new::Asset&>(*p->asset),
            reinterpret_cast<const stipple_new::LodFrame&>(f));
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

bool same_selection(const stipple::PointClusters& a, const stipple::PointClusters& b) {
    return a.run_count == b.run_count && a.placed_count == b.placed_count &&
           std::memcmp(a.run.get(), b.run.get(), size_t(a.run_count) * 4) == 0 &&
           std::memcmp(a.placed.get(), b.placed.get(), size_t(a.placed_count) * 4) == 0 &&
           std::memcmp(a.keep.get(), b.keep.get(), size_t(a.cluster_count) * 4) == 0;
}

double at(std::vector<double> v, double q) {
    std::sort(v.begin(), v.end());
    return v[size_t(q * double(v.size() - 1))];
}

}  // namespace

int main(int argc, char** argv) {
    stipple::Asset asset;
    if (!stipple::bench::ab_load(argc, argv, "ab_select FILE.stip [CALLS] [FRAMES]", &asset))
        return 1;
    const int frames = argc > 3 ? std::max(1, std::atoi(argv[3])) : 10;
    const int per_frame = std::max(1, (argc > 2 ? std::atoi(argv[2]) : 300) / frames);
    stipple::bench::HeadlessGl context;
    if (!stipple::bench::ab_context(&context)) return 1;
    const stipple::FrameConfig config = stipple::bench::ab_config();
    auto po = std::make_unique<stipple::Pipeline>(), pn = std::make_unique<stipple::Pipeline>();
    if (!stipple::pipeline_init(po.get(), asset, context.gl, config).ok() ||
        !stipple::pipeline_init(pn.get(), asset, context.gl, config).ok())
        return 1;
    std::vector<double> to, tn;
    int differing = 0;
    for (int k = 0; k < frames; ++k) {
        stipple::AnimationState state;
        state.clip = 0;
        state.time = 0.1f * float(k);
        stipple::pipeline_update(po.get(), state, nullptr);
        stipple::pipeline_update(pn.get(), state, nullptr);
        const stipple::LodFrame fo = lod_frame(*po), fn = lod_frame(*pn);
        for (int r = 0; r < per_frame; ++r) {
            const bool old_first = r % 2 == 0;
            (old_first ? to : tn)
                .push_back(
                    select_ms(old_first, old_first ? po.get() : pn.get(), old_first ? fo : fn));
            (old_first ? tn : to)
                .push_back(
                    select_ms(!old_first, old_first ? pn.get() : po.get(), old_first ? fn : fo));
        }
        differing += !same_selection(po->clusters, pn->clusters);
    }
    const double omin = at(to, 0), omed = at(to, 0.5), nmin = at(tn, 0), nmed = at(tn, 0.5);
    std::printf(
        "run %u placed %u | old %.4f / %.4f ms | new %.4f / %.4f ms | new/old min %.3f median "
        "%.3f | frames whose selections differ: %d of %d\n",
        pn->clusters.run_count, pn->clusters.placed_count, omin, omed, nmin, nmed, nmin / omin,
        nmed / omed, differing, frames);
    return differing ? 2 : 0;
}
