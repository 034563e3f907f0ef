// The run-time refinement stage of the frame (thesis §4.5, §9.1.1; runtime/point_refinement.h):
// continues the hierarchy after the baked points are sized, where it runs out.
#include "runtime/double_sided.h"
#include "runtime/frame_point_stages.h"
#include "runtime/point_stages.h"

namespace stipple {

namespace {

// The corners of the active clusters (cull.list) the selection did not place, placed; those
// it did not turn to the eye, turned (double-sided points), as for every corner below.
void place_culled_corners(Pipeline* p) {
    const RefinementCull& cull = p->refinement.cull;
    const PointClusters& c = p->clusters;
    uint32_t* scratch = p->clusters.rest.get();
    for (int set = 0; set < 2; ++set) {
        const uint64_t* bits = (set == 0 ? c.placed_bits : c.run_bits).get();
        uint32_t n = 0;
        for (uint32_t j = 0; j < cull.list_count; ++j) {
            const uint32_t i = cull.list[j];
            if (!(bits[i / 64] >> (i % 64) & 1u)) scratch[n++] = i;
        }
        if (set == 0)
            point_stage_place(&p->pool, point_stage_frame(p), scratch, n);
        else
            face_listed_double_sided_points(scratch, n, p->point_double_sided.get(),
                                            p->point_positions.get(), p->point_normals.get(),
                                            p->size_params.eye);
    }
}

}  // namespace

// The run-time refinement (runtime/point_refinement.h) after the baked points are sized.
void pipeline_refine_stage(Pipeline* p, bool lod, StageTimes* t, StageClock::time_point* clock) {
    const Asset& a = *p->asset;
    const uint32_t baked = a.points.point_count;
    RefinedPoints extra;
    extra.capacity = p->config.refinement_budget;
    extra.positions = p->point_positions.get() + size_t(baked) * 3;
    extra.normals = p->point_normals.get() + size_t(baked) * 3;
    extra.radius = p->radius.get() + baked;
    extra.triangle = p->refined_triangle.get();
    extra.index = p->refined_index.get();
    if (p->refine_on_points && p->refinement.cull.cluster_count > 0) {
        // Only the clusters where a point can be added (runtime/refinement_cull.h): when none
        // is, the stage ends here, before any baked point is placed for it.
        RefinementCull& cull = p->refinement.cull;
        const float* normals = a.sides.triangle_double_sided ? nullptr : p->vertex_normals.get();
        if (refinement_cull(&cull, a.mesh, p->vertex_positions.get(), normals, p->size_params,
                            p->config.relevance_update, refinement_near_w(p->size_params)) == 0) {
            p->refined_count = 0;
            if (t) t->refine += ms_since(clock);
            return;
        }
        if (lod) place_culled_corners(p);
        MeshView domain = p->refinement_domain;
        domain.positions = p->point_positions.get();
        domain.normals = p->point_normals.get();
        // Again with the corners' posed areas, before any corner is classified.
        if (p->config.relevance_update &&
            refinement_cull_posed(&cull, domain, domain.positions) == 0) {
            p->refined_count = 0;
            if (t) t->refine += ms_since(clock);
            return;
        }
        refine_points_culled(&p->refinement, domain, domain.positions, domain.normals,
                             p->size_params, p->config.relevance_update, &extra,
                             &p->refinement_stats, &p->pool);
    } else if (p->refine_on_points) {  // corners are the baked points, as placed this frame
        if (lod) {  // every corner, not only the selection (close-ups: the cut keeps most):
            // the points the selection did not place, then those it did not turn to the eye
            PointClusters& c = p->clusters;
            point_stage_place(&p->pool, point_stage_frame(p), c.rest.get(),
                              point_clusters_rest(&c, true));
            face_listed_double_sided_points(c.rest.get(), point_clusters_rest(&c, false),
                                            p->point_double_sided.get(), p->point_positions.get(),
                                            p->point_normals.get(), p->size_params.eye);
        }
        MeshView domain = p->refinement_domain;
        domain.positions = p->point_positions.get();
        domain.normals = p->point_normals.get();  // double-sided ones already face the eye
        refine_points(&p->refinement, domain, domain.positions, domain.normals, nullptr,
                      p->size_params, p->config.relevance_update, &extra, &p->refinement_stats);
    } else {
        refine_points(&p->refinement, a.mesh, p->vertex_positions.get(), p->vertex_normals.get(),
                      a.sides.triangle_double_sided, p->size_params, p->config.relevance_update,
                      &extra, &p->refinement_stats);
    }
    p->refined_count = extra.count;
    if (t) t->refine += ms_since(clock);
    size_stipples(extra.count, extra.positions, extra.normals, extra.radius, p->size_params,
                  p->size.get() + baked);
    if (!lod) {
        fade_baked_points(p->refinement, a.points, p->size.get());
        return;
    }
    if (!p->refinement.hand_over) return;  // as fade_baked_points: the points domain fades none
    const PointClusters& c = p->clusters;  // fade_baked_points over the selection
    for (uint32_t j = 0; j < c.run_count; ++j)
        p->size[c.run[j]] *= p->refinement.fade[a.points.host_triangle[c.run[j]]];
}

}  // namespace stipple
