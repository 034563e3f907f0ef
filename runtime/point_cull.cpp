#include "runtime/point_cull.h"

#include <atomic>
#include <glm/glm.hpp>

#include "runtime/point_placement.h"

namespace stipple {

CullKernelFrame::CullKernelFrame(const PointStageFrame& f, const PointClusters& c, bool relevance)
    : sizing(*f.params),
      points(f.points),
      positions(f.positions),
      normals(f.normals),
      scale(f.scale),
      fallback_radius(f.fallback_radius),
      area_bound(c.point_area_bound.get()),
      line_bound(c.point_line_bound.get()),
      point_cluster(c.point_cluster.get()),
      cluster_factor(c.cluster_factor.get()),
      forced_bits(c.forced_bits.get()),
      relevance_update(relevance),
      radius_bound(point_cull_radius_bound_enabled()),
      radius(f.radius),
      size(f.size) {}

namespace {

std::atomic<PointCullMode> g_cull{PointCullMode::off};  // see point_cull.h
std::atomic<bool> g_radius_bound{false};

// stipple_size.cpp's stipple_size after its facing test, for a given radius (Alg. 3.2,
// §3.1.1, §3.1.2): the same operations in the same order.
inline float size_for_radius(const CullKernelFrame& k, float radius, float n_dot_v, float w,
                             float ink) {
    const SizeParams& params = *k.sizing.params;
    const float r_px = radius * k.sizing.focal / w;
    const float region_px = kRegionPerRadiusSquared * r_px * r_px * n_dot_v;  // §3.1.2
    return smooth_point_size(ink, region_px, params.max_point_size, params.smooth_slope);
}

// A placed point's N.V (over |V|) and clip w, as stipple_size.cpp computes them.
struct Facing {
    glm::vec3 n;
    float n_dot_v, w;
};
inline Facing facing(const SizeKernelFrame& sizing, const float* positions, const float* normals,
                     uint32_t i) {
    const float* pp = positions + size_t(i) * 3;
    const float* np = normals + size_t(i) * 3;
    const glm::vec3 p(pp[0], pp[1], pp[2]);
    Facing r;
    r.n = glm::vec3(np[0], np[1], np[2]);
    const glm::vec3 to_eye = sizing.params->eye - p;
    r.n_dot_v = glm::dot(r.n, to_eye) / glm::length(to_eye);
    const glm::vec4 row_w(sizing.row_w[0], sizing.row_w[1], sizing.row_w[2], sizing.row_w[3]);
    r.w = glm::dot(row_w, glm::vec4(p, 1.0f));
    return r;
}

// One point: whether it is kept, and then its radius and size.
inline bool cull_point(const CullKernelFrame& k, uint32_t i) {
    const SizeParams& params = *k.sizing.params;
    const Facing fc = facing(k.sizing, k.positions, k.normals, i);
    const glm::vec3 n = fc.n;
    const float n_dot_v = fc.n_dot_v, w = fc.w;
    const bool forced = (k.forced_bits[i >> 6] >> (i & 63)) & 1;
    const bool hidden = n_dot_v <= 0.0f || w <= 0.0f;
    float ink = 0.0f;
    if (!hidden) {
        ink = k.sizing.table.at(lighting(params, n));
        const float bound =
            k.radius_bound ? size_for_radius(k, cull_radius_bound(k, i), n_dot_v, w, ink) : 1.0f;
        if (bound == 0.0f && !forced) return false;  // size 0 (a NaN bound is kept)
    } else if (!forced) {
        return false;
    }
    const float r = k.relevance_update ? point_relevance_radius(*k.points, k.positions, k.scale,
                                                                k.fallback_radius, i)
                                       : k.fallback_radius[i];
    k.radius[i] = r;
    k.size[i] = hidden ? 0.0f : size_for_radius(k, r, n_dot_v, w, ink);
    return true;
}

struct CullTask {
    const CullKernelFrame* k;
    const uint32_t* list;
    PointSimd simd;
    std::atomic<uint32_t> kept{0};
};

void cull_range(void* context, uint32_t begin, uint32_t end) {
    CullTask& t = *static_cast<CullTask*>(context);
    const uint32_t kept = t.simd == PointSimd::avx2
                              ? cull_relevance_size_avx2(*t.k, t.list, begin, end)
                              : cull_relevance_size(*t.k, t.list, begin, end);
    t.kept.fetch_add(kept, std::memory_order_relaxed);
}

}  // namespace

void point_cull_set_mode(PointCullMode mode) {
    g_cull.store(mode, std::memory_order_relaxed);
}

PointCullMode point_cull_mode() {
    return g_cull.load(std::memory_order_relaxed);
}

void point_cull_radius_bound(bool on) {
    g_radius_bound.store(on, std::memory_order_relaxed);
}

bool point_cull_radius_bound_enabled() {
    return g_radius_bound.load(std::memory_order_relaxed);
}

uint32_t cull_relevance_size(const CullKernelFrame& k, const uint32_t* list, uint32_t begin,
                             uint32_t end) {
    uint32_t kept = 0;
    for (uint32_t j = begin; j < end; ++j) kept += cull_point(k, list[j]);
    return kept;
}

uint32_t point_facing_list(const PointStageFrame& f, const PointClusters& c, const uint32_t* list,
                           uint32_t count, uint32_t* kept) {
    // N.(eye - p) instead of the size rule's N.V over |V|: the same sign, or > 0 where the
    // quotient underflows to 0 (then the point is kept and sized 0: a superset, still exact).
    // w as the size rule computes it.
    const glm::vec3 eye = f.params->eye;
    const glm::mat4& m = f.params->view_projection;
    const glm::vec4 row_w(m[0][3], m[1][3], m[2][3], m[3][3]);
    const uint64_t* forced = c.forced_bits.get();
    uint32_t n = 0;
    for (uint32_t j = 0; j < count; ++j) {
        const uint32_t i = list[j];
        const float* pp = f.positions + size_t(i) * 3;
        const float* np = f.normals + size_t(i) * 3;
        const glm::vec3 p(pp[0], pp[1], pp[2]);
        const float d = glm::dot(glm::vec3(np[0], np[1], np[2]), eye - p);
        const float w = glm::dot(row_w, glm::vec4(p, 1.0f));
        const bool shown = !(d <= 0.0f || w <= 0.0f);  // as cull_point: NaN kept
        kept[n] = i;
        n += shown || ((forced[i >> 6] >> (i & 63)) & 1);
    }
    return n;
}

uint32_t point_stage_cull_relevance_size(ThreadPool* pool, const PointStageFrame& f,
                                         const PointClusters& c, bool relevance_update,
                                         const uint32_t* list, uint32_t count) {
    const CullKernelFrame k(f, c, relevance_update);
    CullTask task;
    task.k = &k;
    task.list = list;
    task.simd = point_simd();
    thread_pool_run(pool, count, kMinPointsPerThread, cull_range, &task);
    return task.kept.load(std::memory_order_relaxed);
}

#if !((defined(__x86_64__) || defined(__i386__)) && (defined(__GNUC__) || defined(__clang__)))
// No AVX2 anywhere else: point_simd() is never avx2 there.
uint32_t cull_relevance_size_avx2(const CullKernelFrame& k, const uint32_t* list, uint32_t begin,
                                  uint32_t end) {
    return cull_relevance_size(k, list, begin, end);
}
#endif

}  // namespace stipple
