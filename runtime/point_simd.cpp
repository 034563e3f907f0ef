#include "runtime/point_simd.h"

#include <atomic>
#include <cstdlib>
#include <cstring>

namespace stipple {

namespace {

PointSimd detect() {
    const char* forced = std::getenv("STIPPLE_SIMD");
    if (forced && std::strcmp(forced, "baseline") == 0) return PointSimd::baseline;
#if STIPPLE_AVX2_KERNELS
    __builtin_cpu_init();
    if (!__builtin_cpu_supports("avx2")) return PointSimd::baseline;
    const bool avx512 = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
                        __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512bw");
    const bool capped = forced && std::strcmp(forced, "avx2") == 0;
    return avx512 && !capped ? PointSimd::avx512 : PointSimd::avx2;
#endif
    return PointSimd::baseline;
}

// -1: not forced.
std::atomic<int> g_forced{-1};

}  // namespace

PointSimd point_simd_detected() {
    static const PointSimd detected = detect();  // thread-safe once
    return detected;
}

PointSimd point_simd() {
    const int forced = g_forced.load(std::memory_order_relaxed);
    return forced < 0 ? point_simd_detected() : PointSimd(forced);
}

void point_simd_force(PointSimd simd) {
    // Forcing a path wider than the CPU's (or than STIPPLE_SIMD allows) takes the widest there is.
    if (simd > point_simd_detected()) simd = point_simd_detected();
    g_forced.store(int(simd), std::memory_order_relaxed);
}

const char* point_simd_name(PointSimd simd) {
    return simd == PointSimd::avx512 ? "avx512" : simd == PointSimd::avx2 ? "avx2" : "baseline";
}

void pair_vertices(uint32_t count, const float* positions, const float* normals, float* out) {
    for (uint32_t v = 0; v < count; ++v) {
        float* o = out + size_t(v) * 8;
        std::memcpy(o, positions + size_t(v) * 3, 12);
        std::memcpy(o + 4, normals + size_t(v) * 3, 12);
        const float len = glm::length(glm::vec3(o[4], o[5], o[6]));  // for normal_bounds.h
        o[3] = len;
        o[7] = len > 0.0f ? 1.0f / len : 0.0f;
    }
}

bool point_hosts(const PointsView& points, const uint32_t* indices, uint32_t vertex_count,
                 PointHost* out) {
    if (vertex_count > kPointHostMaxVertices) return false;
    for (uint32_t i = 0; i < points.point_count; ++i) {
        const uint32_t* tri = indices + size_t(points.host_triangle[i]) * 3;
        out[i].corners = uint64_t(tri[0]) | uint64_t(tri[1]) << 21 | uint64_t(tri[2]) << 42;
        out[i].u = points.bary_u[i];
        out[i].v = points.bary_v[i];
    }
    return true;
}

bool quad_neighbours(const PointsView& points, uint32_t* out) {
    if (points.point_count > kQuadMaxPoints) return false;  // 3 i must fit in 32 bits
    for (uint32_t i = 0; i < points.point_count; ++i) {
        const uint32_t begin = points.neighbour_offsets[i], end = points.neighbour_offsets[i + 1];
        if (end - begin > 4) return false;
        uint32_t* o = out + size_t(i) * 4;
        for (uint32_t k = 0; k < 4; ++k)
            o[k] = 3 * (begin + k < end ? points.neighbours[begin + k] : i);
    }
    return true;
}

#if !STIPPLE_AVX2_KERNELS
// No AVX2 anywhere else: point_simd() is never avx2 there, so these are never called.
void pair_vertices_avx2(uint32_t, const float*, const float*, float*) {}
void place_points_avx2(const PointsView&, const uint32_t*, const PointHost*, const float*,
                       const uint32_t*, uint32_t, uint32_t, float*, float*) {}
void recompute_relevance_avx2(const PointsView&, const uint32_t*, const float*, const float*,
                              const float*, const uint32_t*, uint32_t, uint32_t, float*) {}
void size_stipples_avx2(const SizeFrame&, const float*, const float*, const float*, const uint32_t*,
                        uint32_t, uint32_t, float*) {}
void relevance_size_avx2(const PointsView&, const uint32_t*, const SizeFrame&, const float*,
                         const float*, const float*, const float*, const uint32_t*, uint32_t,
                         uint32_t, float*, float*) {}
void relevance_size_avx512(const PointsView&, const uint32_t*, const SizeFrame&, const float*,
                           const float*, const float*, const float*, const uint32_t*, uint32_t,
                           uint32_t, float*, float*) {}
uint32_t triangle_stretch_avx2(const uint32_t*, const float*, const float*, uint32_t, float*,
                               float*) {
    return 0;
}
uint32_t triangle_facing_avx2(const uint32_t*, const float*, const float*, uint32_t, uint8_t*) {
    return 0;
}
uint32_t triangle_sigma2_avx2(const uint32_t*, uint32_t, const uint32_t*, const float*,
                              const float*, float*) {
    return 0;
}
#endif

}  // namespace stipple
