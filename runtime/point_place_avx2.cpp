// AVX2 place (Thesis Alg. 6.3; runtime/point_simd.h): one point per step with its position and
// normal in the lanes of one vector (the vertex pairs), 4 points' normal lengths rooted and
// divided in one vector; and the vertex pairs themselves. Each mirrors its scalar original
// operation by operation, as runtime/point_simd_avx2.cpp's header says (the same rules: no FMA,
// -ffp-contract=off, headers before the target pragma, only this file's own internal functions
// and the shared lanes of point_simd_avx2_lanes.inc under it).
#include <cstddef>
#include <cstdint>

#include "runtime/point_simd.h"

#if STIPPLE_AVX2_KERNELS
#include "runtime/point_simd_avx2_begin.inc"

namespace stipple {

#include "runtime/point_simd_avx2_lanes.inc"

namespace {

// One point of place_point: its position and normal in the lanes of one vector, blended from
// its host corners' vertex pairs (pair_vertices: x y z |n| nx ny nz 1/|n|; the 4th lanes blend to
// values never stored) in place_point's order, (u a + v b) + w c; the normal's length as
// place_point sums it.
inline void place_point8(const float* pairs, uint32_t a_at, uint32_t b_at, uint32_t c_at, float u,
                         float v, float* out_position, float* out_normal) {
    const float w = 1.0f - u - v;
    const f8 a = _mm256_loadu_ps(pairs + size_t(a_at) * 8);
    const f8 b = _mm256_loadu_ps(pairs + size_t(b_at) * 8);
    const f8 c = _mm256_loadu_ps(pairs + size_t(c_at) * 8);
    const f8 pn =
        _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(splat(u), a), _mm256_mul_ps(splat(v), b)),
                      _mm256_mul_ps(splat(w), c));
    const __m128 p = _mm256_castps256_ps128(pn), n = _mm256_extractf128_ps(pn, 1);
    const __m128 nn = _mm_mul_ps(n, n);
    const float len2 = (lane0(nn) + lane<1>(nn)) + lane<2>(nn);
    const float inv = len2 > 1e-20f ? 1.0f / sqrt1(len2) : 0.0f;
    store3(out_position, p);
    store3(out_normal, _mm_mul_ps(n, _mm_set1_ps(inv)));
}

}  // namespace

namespace {

// Points are stored coarse to fine, so consecutive points lie far apart on the surface and a
// large mesh (the horse: 48k vertices, 97k triangles) misses the cache on every host triangle
// and vertex. On the path without host records (meshes of more than 2^21 vertices) each
// point's triangle is three dependent loads, so its indices are prefetched kFar points ahead
// and its vertices kNear points ahead (their indices arrived by then). (Measured before the
// host records: the horse's place 1.5x faster; CesiumMan's ~10% slower. Prefetching
// relevance's neighbour positions the same way cost CesiumMan 20%.) The host records' path
// prefetches nothing: one record, then the corners, is a chain the core runs ahead of itself,
// and the 4 prefetches a point cost more than they hid (docs/performance.md, fourteenth round).
constexpr uint32_t kNear = 8, kFar = 16;

inline void prefetch(const void* p) {
    _mm_prefetch(static_cast<const char*>(p), _MM_HINT_T0);
}

inline void prefetch_host(const PointsView& points, const uint32_t* indices, uint32_t i) {
    prefetch(indices + size_t(points.host_triangle[i]) * 3);
}

inline void prefetch_vertices(const PointsView& points, const uint32_t* indices, const float* pairs,
                              uint32_t i) {
    const uint32_t* tri = indices + size_t(points.host_triangle[i]) * 3;
    for (int k = 0; k < 3; ++k) prefetch(pairs + size_t(tri[k]) * 8);
}

constexpr uint64_t kCornerMask = (uint64_t(1) << 21) - 1;

// place_point8 for 4 points of host records at once, up to their normals' lengths; then the 4
// lengths' roots and reciprocals in one vector (correctly rounded like the scalar ones, so the
// same bits): the divider, which a point's root and divide would hold for about 9 cycles,
// takes one step for the 4. len2 <= 1e-20 (or NaN) gives inv = +0, as place_point8.
inline void place_points4(const float* pairs, const PointHost* hosts, const uint32_t* i,
                          float* out_positions, float* out_normals) {
    __m128 p[4], n[4], nn[4];
    for (int k = 0; k < 4; ++k) {
        const PointHost h = hosts[i[k]];
        const float u = h.u, v = h.v, w = 1.0f - u - v;
        const f8 a = _mm256_loadu_ps(pairs + size_t(h.corners & kCornerMask) * 8);
        const f8 b = _mm256_loadu_ps(pairs + size_t(h.corners >> 21 & kCornerMask) * 8);
        const f8 c = _mm256_loadu_ps(pairs + size_t(h.corners >> 42) * 8);
        const f8 pn =
            _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(splat(u), a), _mm256_mul_ps(splat(v), b)),
                          _mm256_mul_ps(splat(w), c));
        p[k] = _mm256_castps256_ps128(pn);
        n[k] = _mm256_extractf128_ps(pn, 1);
        nn[k] = _mm_mul_ps(n[k], n[k]);
    }
    // The 4 squares transposed, so each |n|^2 is (x x + y y) + z z in one vector's lanes.
    _MM_TRANSPOSE4_PS(nn[0], nn[1], nn[2], nn[3]);
    const __m128 l = _mm_add_ps(_mm_add_ps(nn[0], nn[1]), nn[2]);
    const __m128 inv = _mm_and_ps(_mm_cmpgt_ps(l, _mm_set1_ps(1e-20f)),
                                  _mm_div_ps(_mm_set1_ps(1.0f), _mm_sqrt_ps(l)));
    for (int k = 0; k < 4; ++k) {
        store3(out_positions + size_t(i[k]) * 3, p[k]);
        store3(out_normals + size_t(i[k]) * 3, _mm_mul_ps(n[k], lane_of(inv, k)));
    }
}

}  // namespace

// point_simd.cpp's pair_vertices, 4 vertices a step: each normal's |n|^2 summed as glm::length
// does, (x x + y y) + z z (4 at once, the squares transposed), then the 4 roots and reciprocals in
// one vector (correctly rounded, so the same bits as std::sqrt and 1 / len; len > 0 false for 0 and
// NaN: 1/|n| = +0).
void pair_vertices_avx2(uint32_t count, const float* positions, const float* normals, float* out) {
    uint32_t v = 0;
    for (; v + 4 <= count; v += 4) {
        __m128 p[4], n[4], nn[4];
        for (int k = 0; k < 4; ++k) {
            p[k] = load3(positions + size_t(v + k) * 3);
            n[k] = load3(normals + size_t(v + k) * 3);
            nn[k] = _mm_mul_ps(n[k], n[k]);
        }
        _MM_TRANSPOSE4_PS(nn[0], nn[1], nn[2], nn[3]);  // as place_points4
        const __m128 len = _mm_sqrt_ps(_mm_add_ps(_mm_add_ps(nn[0], nn[1]), nn[2]));
        const __m128 inv =
            _mm_and_ps(_mm_cmpgt_ps(len, _mm_setzero_ps()), _mm_div_ps(_mm_set1_ps(1.0f), len));
        for (int k = 0; k < 4; ++k) {
            float* o = out + size_t(v + k) * 8;
            _mm_storeu_ps(o, _mm_blend_ps(p[k], lane_of(len, k), 0x8));      // x y z |n|
            _mm_storeu_ps(o + 4, _mm_blend_ps(n[k], lane_of(inv, k), 0x8));  // nx ny nz 1/|n|
        }
    }
    if (v < count)
        pair_vertices(count - v, positions + size_t(v) * 3, normals + size_t(v) * 3,
                      out + size_t(v) * 8);
}

// point_placement.cpp's place_point (Thesis Alg. 6.3), from the points' 16-byte hosts when
// there are (one line per point, the corners without the triangle's indices in between).
void place_points_avx2(const PointsView& points, const uint32_t* indices, const PointHost* hosts,
                       const float* pairs, const uint32_t* list, uint32_t begin, uint32_t end,
                       float* out_positions, float* out_normals) {
    if (hosts) {
        for (; begin + 4 <= end; begin += 4) {
            uint32_t i[4];
            for (int k = 0; k < 4; ++k) i[k] = list ? list[begin + k] : begin + k;
            place_points4(pairs, hosts, i, out_positions, out_normals);
        }
        for (uint32_t j = begin; j < end; ++j) {
            const uint32_t i = list ? list[j] : j;
            const PointHost h = hosts[i];
            place_point8(pairs, uint32_t(h.corners & kCornerMask),
                         uint32_t(h.corners >> 21 & kCornerMask), uint32_t(h.corners >> 42), h.u,
                         h.v, out_positions + size_t(i) * 3, out_normals + size_t(i) * 3);
        }
        return;
    }
    for (uint32_t j = begin; j < end; ++j) {
        if (j + kFar < end) prefetch_host(points, indices, list ? list[j + kFar] : j + kFar);
        if (j + kNear < end)
            prefetch_vertices(points, indices, pairs, list ? list[j + kNear] : j + kNear);
        const uint32_t i = list ? list[j] : j;
        const uint32_t* tri = indices + size_t(points.host_triangle[i]) * 3;
        place_point8(pairs, tri[0], tri[1], tri[2], points.bary_u[i], points.bary_v[i],
                     out_positions + size_t(i) * 3, out_normals + size_t(i) * 3);
    }
}

}  // namespace stipple

#include "runtime/point_simd_avx2_end.inc"
#endif
