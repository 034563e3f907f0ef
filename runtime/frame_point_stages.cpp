#include "runtime/frame_point_stages.h"

#include <algorithm>
#include <cstring>

#include "runtime/double_sided.h"
#include "runtime/point_placement.h"
#include "runtime/point_stages.h"

namespace stipple {

namespace {

using Clock = StageClock;

// The finest quarter of the bake is where the run-time refinement takes over: extra points
// can be drawn only where the size rule draws baked points of that region size, so while none
// of them has a size (full views of a dense bake) the frame needs no refinement at all.
bool hierarchy_running_out(const float* size, uint32_t baked) {
    for (uint32_t i = baked - baked / 4; i < baked; ++i)
        if (size[i] > 0.0f) return true;
    return baked < 4;
}

// Thesis Alg. 6.4 then 3.2 over the points list[0 .. count) (list null: 0 .. count - 1): one
// fused pass when relevance is recomputed on the AVX2 path (runtime/point_stages.h), else
// relevance (or the rest radii) and then size.
void relevance_and_size(Pipeline* p, const PointStageFrame& f, const uint32_t* list, uint32_t count,
                        StageTimes* t, Clock::time_point* clock) {
    const bool update = p->config.relevance_update;
    if (!(update && point_stage_relevance_size(&p->pool, f, list, count))) {
        if (update)
            point_stage_relevance(&p->pool, f, list, count);
        else if (!list)
            std::memcpy(p->radius.get(), p->rest_radius.get(), size_t(count) * 4);
        else
            for (uint32_t j = 0; j < count; ++j) p->radius[list[j]] = p->rest_radius[list[j]];
        if (t) t->relevance += ms_since(clock);
        point_stage_size(&p->pool, f, list, count);
    } else if (t) {
        t->relevance += ms_since(clock);
    }
    if (t) t->size += ms_since(clock);
}

// Thesis Alg. 6.3, 6.4 and 3.2 over every baked point.
void full_point_stages(Pipeline* p, StageTimes* t, Clock::time_point* clock) {
    const Asset& a = *p->asset;
    const PointStageFrame f = point_stage_frame(p);  // threads and SIMD: runtime/point_stages.h
    point_stage_place(&p->pool, f, nullptr, a.points.point_count);
    face_double_sided_points(a.points.point_count, p->point_double_sided.get(),
                             p->point_positions.get(), p->point_normals.get(), p->size_params.eye);
    if (t) t->place += ms_since(clock);
    const uint32_t baked = a.points.point_count;
    relevance_and_size(p, f, nullptr, baked, t, clock);
    p->lod_sizes_clear = false;
    if (t) t->size += ms_since(clock);
}

// The same over the clusters' selection (thesis §9.1.1, runtime/point_clusters.h): the
// points run are placed, re-scaled and sized; their neighbours only placed; every other baked
// point keeps size 0.
void lod_point_stages(Pipeline* p, StageTimes* t, Clock::time_point* clock) {
    const Asset& a = *p->asset;
    PointClusters& c = p->clusters;
    if (p->lod_sizes_clear) {
        point_clusters_clear_sizes(c, p->size.get());
    } else {  // also the radii of points not run: defined (the rest pose's)
        std::fill(p->size.get(), p->size.get() + a.points.point_count, 0.0f);
        std::memcpy(p->radius.get(), p->rest_radius.get(), size_t(a.points.point_count) * 4);
    }
    p->lod_sizes_clear = true;
    LodFrame frame;
    frame.vertex_positions = p->vertex_positions.get();
    frame.vertex_normals = p->vertex_normals.get();
    frame.vertex_pairs = p->vertex_pairs.get();
    frame.params = &p->size_params;
    frame.viewport_width = p->viewport_width;
    frame.relevance_update = p->config.relevance_update;
    frame.pool = &p->pool;  // the clusters' tests over the threads (the same selection)
    const uint32_t baked = a.points.point_count;  // hierarchy_running_out's finest quarter
    if (p->config.refinement_budget > 0) frame.size_from = baked - baked / 4;
    point_clusters_select(&c, a, frame);
    if (t) t->select += ms_since(clock);
    const uint32_t* run = c.run.get();
    const PointStageFrame f = point_stage_frame(p);  // threads and SIMD: runtime/point_stages.h
    point_stage_place(&p->pool, f, c.placed.get(), c.placed_count);
    face_listed_double_sided_points(run, c.run_count, p->point_double_sided.get(),
                                    p->point_positions.get(), p->point_normals.get(),
                                    p->size_params.eye);
    if (t) t->place += ms_since(clock);
    relevance_and_size(p, f, run, c.run_count, t, clock);
}

// hierarchy_running_out over the selection: only run points can have a size.
bool lod_running_out(const PointClusters& c, const float* size, uint32_t baked) {
    for (uint32_t j = 0; j < c.run_count; ++j)
        if (c.run[j] >= baked - baked / 4 && size[c.run[j]] > 0.0f) return true;
    return baked < 4;
}

}  // namespace

void pipeline_point_stages(Pipeline* p, bool lod, StageTimes* t, Clock::time_point* clock) {
    point_stage_pair_vertices(p);  // before any place (runtime/point_stages.h)
    if (t) t->place += ms_since(clock);
    if (lod)
        lod_point_stages(p, t, clock);
    else
        full_point_stages(p, t, clock);
    const uint32_t baked = p->asset->points.point_count;
    // Where the baked hierarchy runs out, continue it (extra points after the baked ones).
    p->refined_count = 0;
    p->refinement_stats = RefinementStats();
    if (p->config.refinement_budget > 0 && (lod ? lod_running_out(p->clusters, p->size.get(), baked)
                                                : hierarchy_running_out(p->size.get(), baked)))
        pipeline_refine_stage(p, lod, t, clock);
}

}  // namespace stipple
