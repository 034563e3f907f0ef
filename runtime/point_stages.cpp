#include "runtime/point_stages.h"

#include "runtime/frame_pipeline.h"
#include "runtime/point_placement.h"
#include "runtime/point_simd.h"

namespace stipple {

namespace {

struct StageTask {
    const PointStageFrame* f;
    const uint32_t* list;
    PointSimd simd;
    const SizeFrame* size_frame;  // the AVX2 and AVX-512 size only
};

void place_range(void* context, uint32_t begin, uint32_t end) {
    const StageTask& t = *static_cast<const StageTask*>(context);
    const PointStageFrame& f = *t.f;
    if (has_avx2(t.simd) && f.vertex_pairs) {
        place_points_avx2(*f.points, f.indices, f.point_hosts, f.vertex_pairs, t.list, begin, end,
                          f.positions, f.normals);
    } else if (t.list) {
        place_listed_points(*f.points, f.indices, f.vertex_positions, f.vertex_normals,
                            t.list + begin, end - begin, f.positions, f.normals);
    } else {  // the range as a view of its own: place reads only the point's own entries
        PointsView range = *f.points;
        range.point_count = end - begin;
        range.host_triangle += begin;
        range.bary_u += begin;
        range.bary_v += begin;
        place_points(range, f.indices, f.vertex_positions, f.vertex_normals,
                     f.positions + size_t(begin) * 3, f.normals + size_t(begin) * 3);
    }
}

void relevance_range(void* context, uint32_t begin, uint32_t end) {
    const StageTask& t = *static_cast<const StageTask*>(context);
    const PointStageFrame& f = *t.f;
    if (has_avx2(t.simd))
        recompute_relevance_avx2(*f.points, f.neighbour_quads, f.positions, f.scale,
                                 f.fallback_radius, t.list, begin, end, f.radius);
    else if (t.list)
        recompute_listed_relevance(*f.points, f.positions, f.scale, f.fallback_radius,
                                   t.list + begin, end - begin, f.radius);
    else
        recompute_relevance_range(*f.points, f.positions, f.scale, f.fallback_radius, begin, end,
                                  f.radius);
}

void size_range(void* context, uint32_t begin, uint32_t end) {
    const StageTask& t = *static_cast<const StageTask*>(context);
    const PointStageFrame& f = *t.f;
    if (has_avx2(t.simd))
        size_stipples_avx2(*t.size_frame, f.positions, f.normals, f.radius, t.list, begin, end,
                           f.size);
    else if (t.list)
        size_listed_stipples(t.list + begin, end - begin, f.positions, f.normals, f.radius,
                             *f.params, f.size);
    else
        size_stipples(end - begin, f.positions + size_t(begin) * 3, f.normals + size_t(begin) * 3,
                      f.radius + begin, *f.params, f.size + begin);
}

void relevance_size_range(void* context, uint32_t begin, uint32_t end) {
    const StageTask& t = *static_cast<const StageTask*>(context);
    const PointStageFrame& f = *t.f;
    (t.simd == PointSimd::avx512 ? relevance_size_avx512 : relevance_size_avx2)(
        *f.points, f.neighbour_quads, *t.size_frame, f.positions, f.normals, f.scale,
        f.fallback_radius, t.list, begin, end, f.radius, f.size);
}

}  // namespace

PointStageFrame point_stage_frame(Pipeline* p) {
    PointStageFrame f;
    f.points = &p->asset->points;
    f.indices = p->asset->mesh.indices;
    f.vertex_positions = p->vertex_positions.get();
    f.vertex_normals = p->vertex_normals.get();
    f.vertex_pairs = p->vertex_pairs.get();
    f.point_hosts = p->point_hosts.get();
    f.neighbour_quads = p->neighbour_quads.get();
    f.scale = p->radius_scale.get();
    f.fallback_radius = p->rest_radius.get();
    f.params = &p->size_params;
    f.positions = p->point_positions.get();
    f.normals = p->point_normals.get();
    f.radius = p->radius.get();
    f.size = p->size.get();
    return f;
}

void point_stage_pair_vertices(Pipeline* p) {
    if (!p->vertex_pairs) return;
    (has_avx2(point_simd()) ? pair_vertices_avx2 : pair_vertices)(
        p->asset->mesh.vertex_count, p->vertex_positions.get(), p->vertex_normals.get(),
        p->vertex_pairs.get());
}

void point_stage_place(ThreadPool* pool, const PointStageFrame& f, const uint32_t* list,
                       uint32_t count) {
    StageTask task{&f, list, point_simd(), nullptr};
    thread_pool_run(pool, count, kMinPointsPerThread, place_range, &task);
}

void point_stage_relevance(ThreadPool* pool, const PointStageFrame& f, const uint32_t* list,
                           uint32_t count) {
    StageTask task{&f, list, point_simd(), nullptr};
    thread_pool_run(pool, count, kMinPointsPerThread, relevance_range, &task);
}

void point_stage_size(ThreadPool* pool, const PointStageFrame& f, const uint32_t* list,
                      uint32_t count) {
    const PointSimd simd = point_simd();
    if (has_avx2(simd)) {
        const SizeFrame frame(*f.params);  // once for every range
        StageTask task{&f, list, simd, &frame};
        thread_pool_run(pool, count, kMinPointsPerThread, size_range, &task);
        return;
    }
    StageTask task{&f, list, simd, nullptr};
    thread_pool_run(pool, count, kMinPointsPerThread, size_range, &task);
}

bool point_stage_relevance_size(ThreadPool* pool, const PointStageFrame& f, const uint32_t* list,
                                uint32_t count) {
    const PointSimd simd = point_simd();
    if (!has_avx2(simd)) return false;
    const SizeFrame frame(*f.params);  // once for every range
    StageTask task{&f, list, simd, &frame};
    thread_pool_run(pool, count, kMinPointsPerThread, relevance_size_range, &task);
    return true;
}

}  // namespace stipple
