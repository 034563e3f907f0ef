// AVX2 variants of the CPU point stages (runtime/point_simd.h): size and relevance 8 points
// per step (scattered points loaded one by one and transposed: AVX2 gathers measured twice as
// slow per element on this Zen 5), place one point per step with its position and normal in
// the lanes of one vector (runtime/point_simd.h's vertex pairs). Each kernel mirrors its scalar
// original operation by operation: same products, sums in the same order, sqrt and divide (no
// rsqrt/rcp), the scalar code's comparisons and clamps as blends with the same NaN behaviour, no
// FMA (the target is avx2 alone and this file is built with -ffp-contract=off), so every lane gives
// the bits the scalar code gives. Every header is included before the target pragma, and only
// intrinsics and this file's own internal functions run under it, so no inline function shared with
// other files is compiled for AVX2 (which the linker could pick for the baseline callers too).
#include <cstddef>
#include <cstdint>

#include "runtime/point_simd.h"

#if (defined(__x86_64__) || defined(__i386__)) && (defined(__GNUC__) || defined(__clang__))
#include <immintrin.h>

#if defined(__clang__)
#pragma clang attribute push(__attribute__((target("avx2"))), apply_to = function)
#else
#pragma GCC push_options
#pragma GCC target("avx2")
#endif

namespace stipple {

namespace {

using f8 = __m256;
using i8 = __m256i;

// The 8 point indices of a step into idx: list[j ..] or j .., repeating the last one past
// `end` (those lanes compute a valid point again and are not stored); returns how many are
// real.
inline int step_indices(const uint32_t* list, uint32_t j, uint32_t end, uint32_t* idx) {
    const uint32_t n = end - j < 8u ? end - j : 8u;
    for (uint32_t k = 0; k < 8; ++k) {
        const uint32_t at = j + (k < n ? k : n - 1);
        idx[k] = list ? list[at] : at;
    }
    return int(n);
}
inline f8 splat(float x) {
    return _mm256_set1_ps(x);
}
// cond ? a : b per lane (cond: an all-ones/zeros comparison mask).
inline f8 select(f8 cond, f8 a, f8 b) {
    return _mm256_blendv_ps(b, a, cond);
}

// Writes lanes 0 .. lanes - 1 of v to out[idx[k]].
inline void store1(float* out, const uint32_t* idx, int lanes, f8 v) {
    alignas(32) float vv[8];
    _mm256_store_ps(vv, v);
    for (int k = 0; k < lanes; ++k) out[idx[k]] = vv[k];
}

// 12 packed floats x0 y0 z0 .. z3 to x, y, z (4 lanes each; anim/simd.h's shuffles).
inline void aos3_to_soa(__m128 a, __m128 b, __m128 c, __m128& x, __m128& y, __m128& z) {
    const __m128 t0 = _mm_shuffle_ps(a, b, _MM_SHUFFLE(2, 2, 3, 0));
    const __m128 t1 = _mm_shuffle_ps(b, c, _MM_SHUFFLE(1, 1, 2, 2));
    x = _mm_shuffle_ps(t0, t1, _MM_SHUFFLE(2, 0, 1, 0));
    const __m128 y01 = _mm_shuffle_ps(a, b, _MM_SHUFFLE(0, 0, 1, 1));
    const __m128 y23 = _mm_shuffle_ps(b, c, _MM_SHUFFLE(2, 2, 3, 3));
    y = _mm_shuffle_ps(y01, y23, _MM_SHUFFLE(2, 0, 2, 0));
    const __m128 z01 = _mm_shuffle_ps(a, b, _MM_SHUFFLE(1, 1, 2, 2));
    const __m128 z23 = _mm_shuffle_ps(c, c, _MM_SHUFFLE(3, 3, 0, 0));
    z = _mm_shuffle_ps(z01, z23, _MM_SHUFFLE(2, 0, 2, 0));
}
// 8 consecutive points' x, y, z from p[0 .. 24).
inline void load_xyz8(const float* p, f8& x, f8& y, f8& z) {
    __m128 x0, y0, z0, x1, y1, z1;
    aos3_to_soa(_mm_loadu_ps(p), _mm_loadu_ps(p + 4), _mm_loadu_ps(p + 8), x0, y0, z0);
    aos3_to_soa(_mm_loadu_ps(p + 12), _mm_loadu_ps(p + 16), _mm_loadu_ps(p + 20), x1, y1, z1);
    x = _mm256_set_m128(x1, x0);
    y = _mm256_set_m128(y1, y0);
    z = _mm256_set_m128(z1, z0);
}
// x, y, z from memory, w = 0; reads exactly 3 floats. x, y as one unaligned 8-byte load
// (_mm_loadu_si64: floats are only 4-byte aligned, and _mm_load_sd wants 8).
inline __m128 load3(const float* p) {
    const __m128 xy = _mm_castsi128_ps(_mm_loadu_si64(p));
    return _mm_movelh_ps(xy, _mm_load_ss(p + 2));
}
// Point i's x, y, z and one float past them (the next point's x, or the arrays' padding:
// point_simd.h's kSimdPadFloats) in one 16-byte load; the 4th lane is never used.
inline __m128 load4(const float* base, uint32_t i) {
    return _mm_loadu_ps(base + size_t(i) * 3);
}
// load4 of point lo in the lower half, of point hi in the upper.
inline f8 load4x2(const float* base, uint32_t lo, uint32_t hi) {
    return _mm256_insertf128_ps(_mm256_castps128_ps256(load4(base, lo)), load4(base, hi), 1);
}
// The x, y, z of points at[0 .. 8): 8 consecutive points' when `run` (j the first), else
// loaded one by one and transposed (AVX2 gathers measured twice as slow per element here). The
// kernels wait on the shuffle port more than on memory: 16-byte loads, not 8 + 4 bytes and a
// shuffle, gave 5-6% on relevance.
inline void xyz8(const float* base, bool run, uint32_t j, const uint32_t* at, f8& x, f8& y, f8& z) {
    if (run) return load_xyz8(base + size_t(j) * 3, x, y, z);
    // Points k and k + 4 in the two halves of one register (the upper half loaded straight into
    // place), then one in-lane transpose for both halves: half the shuffles of two 4-point
    // transposes and the 8-lane assembly after them (13% off relevance + size).
    const f8 a = load4x2(base, at[0], at[4]), b = load4x2(base, at[1], at[5]);
    const f8 c = load4x2(base, at[2], at[6]), d = load4x2(base, at[3], at[7]);
    const f8 ab_xy = _mm256_unpacklo_ps(a, b), cd_xy = _mm256_unpacklo_ps(c, d);  // x x y y
    const f8 ab_z = _mm256_unpackhi_ps(a, b), cd_z = _mm256_unpackhi_ps(c, d);    // z z w w
    x = _mm256_shuffle_ps(ab_xy, cd_xy, _MM_SHUFFLE(1, 0, 1, 0));
    y = _mm256_shuffle_ps(ab_xy, cd_xy, _MM_SHUFFLE(3, 2, 3, 2));
    z = _mm256_shuffle_ps(ab_z, cd_z, _MM_SHUFFLE(1, 0, 1, 0));
}
inline f8 one8(const float* base, bool run, uint32_t j, const uint32_t* at) {
    if (run) return _mm256_loadu_ps(base + j);
    return _mm256_setr_ps(base[at[0]], base[at[1]], base[at[2]], base[at[3]], base[at[4]],
                          base[at[5]], base[at[6]], base[at[7]]);
}
inline void put8(float* base, bool run, uint32_t j, const uint32_t* idx, int lanes, f8 v) {
    if (run) return _mm256_storeu_ps(base + j, v);
    store1(base, idx, lanes, v);
}

// x0 y0 + x1 y1 + x2 y2, left to right (glm::dot on vec3).
inline f8 dot3(f8 x0, f8 x1, f8 x2, f8 y0, f8 y1, f8 y2) {
    return _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(x0, y0), _mm256_mul_ps(x1, y1)),
                         _mm256_mul_ps(x2, y2));
}

}  // namespace

namespace {

inline float lane0(__m128 v) {
    return _mm_cvtss_f32(v);
}
template <int i>
inline float lane(__m128 v) {
    return _mm_cvtss_f32(_mm_shuffle_ps(v, v, _MM_SHUFFLE(i, i, i, i)));
}
inline float sqrt1(float x) {
    return _mm_cvtss_f32(_mm_sqrt_ss(_mm_set_ss(x)));
}

// One point's relevance radius, x, y, z in the lanes of one vector: the neighbour moment's
// sums xx, yy, zz in one accumulator and xy, yz, zx in another, each in the scalar order.
// For the points relevance_area8 (8 at a time) does not take: the mean distance, the fallback.
inline float relevance_radius4(const PointsView& points, const float* positions, const float* scale,
                               const float* fallback_radius, uint32_t i) {
    const float k = scale[i];
    const uint32_t begin = points.neighbour_offsets[i], end = points.neighbour_offsets[i + 1];
    const __m128 p = load3(positions + size_t(i) * 3);
    if (k > 0.0f) {
        __m128 square = _mm_setzero_ps(), cross = _mm_setzero_ps();
        for (uint32_t n = begin; n < end; ++n) {
            const __m128 d = _mm_sub_ps(load3(positions + size_t(points.neighbours[n]) * 3), p);
            square = _mm_add_ps(square, _mm_mul_ps(d, d));  // dx dx, dy dy, dz dz
            cross = _mm_add_ps(cross, _mm_mul_ps(d, _mm_shuffle_ps(d, d, _MM_SHUFFLE(3, 0, 2, 1))));
        }
        const float xx = lane0(square), yy = lane<1>(square), zz = lane<2>(square);
        const float xy = lane0(cross), yz = lane<1>(cross), xz = lane<2>(cross);
        const float i2 = (xx * yy - xy * xy) + (xx * zz - xz * xz) + (yy * zz - yz * yz);
        return k * sqrt1(sqrt1(i2 < 0.0f ? 0.0f : i2));  // std::max(i2, 0)
    }
    if (k < 0.0f) {
        if (begin == end) return -k * 0.0f;
        float sum = 0.0f;
        for (uint32_t n = begin; n < end; ++n) {
            const __m128 d = _mm_sub_ps(load3(positions + size_t(points.neighbours[n]) * 3), p);
            const __m128 dd = _mm_mul_ps(d, d);
            sum += sqrt1((lane0(dd) + lane<1>(dd)) + lane<2>(dd));
        }
        return -k * (sum / float(end - begin));
    }
    return fallback_radius[i];
}

// Alg. 6.4's neighbour moment of 8 points, one per lane: the six sums in neighbour order per
// lane (point_placement.cpp's neighbour_moment).
struct Moment8 {
    f8 xx, yy, zz, xy, xz, yz;
};
inline Moment8 zero_moment8() {  // (no default member initializers: they would not be AVX2 code)
    const f8 z = _mm256_setzero_ps();
    return Moment8{z, z, z, z, z, z};
}
inline void add_neighbours8(Moment8* m, f8 px, f8 py, f8 pz, const float* positions,
                            const uint32_t* at) {
    f8 qx, qy, qz;
    xyz8(positions, false, 0, at, qx, qy, qz);
    const f8 dx = _mm256_sub_ps(qx, px), dy = _mm256_sub_ps(qy, py), dz = _mm256_sub_ps(qz, pz);
    m->xx = _mm256_add_ps(m->xx, _mm256_mul_ps(dx, dx));
    m->yy = _mm256_add_ps(m->yy, _mm256_mul_ps(dy, dy));
    m->zz = _mm256_add_ps(m->zz, _mm256_mul_ps(dz, dz));
    m->xy = _mm256_add_ps(m->xy, _mm256_mul_ps(dx, dy));
    m->xz = _mm256_add_ps(m->xz, _mm256_mul_ps(dx, dz));
    m->yz = _mm256_add_ps(m->yz, _mm256_mul_ps(dy, dz));
}
// k I2^(1/4) per lane, I2 clamped at 0 (std::max(i2, 0)).
inline f8 area_radius8(const Moment8& m, const float* k) {
    const f8 i2 = _mm256_add_ps(
        _mm256_add_ps(_mm256_sub_ps(_mm256_mul_ps(m.xx, m.yy), _mm256_mul_ps(m.xy, m.xy)),
                      _mm256_sub_ps(_mm256_mul_ps(m.xx, m.zz), _mm256_mul_ps(m.xz, m.xz))),
        _mm256_sub_ps(_mm256_mul_ps(m.yy, m.zz), _mm256_mul_ps(m.yz, m.yz)));
    const f8 kept =
        select(_mm256_cmp_ps(i2, _mm256_setzero_ps(), _CMP_LT_OQ), _mm256_setzero_ps(), i2);
    return _mm256_mul_ps(_mm256_load_ps(k), _mm256_sqrt_ps(_mm256_sqrt_ps(kept)));
}

// Alg. 6.4's area measure for the 8 points i[0 .. 8) at once, each point's neighbours in its
// lane, lanes past a point's last neighbour adding d = p - p = +0 (a sum that starts at +0
// never becomes -0, so adding +0 leaves its bits), then k I2^(1/4) into *radius; px, py, pz
// are the 8 points' positions. Returns false (radius not set) when a real lane's scale is not > 0
// (the mean distance or the fallback radius: the caller takes those points one by one). With
// `quads` (point_simd.h's quad_neighbours) the neighbours come from one 16-byte record per point,
// four steps for every block (a padded entry is the point itself: the same +0); otherwise from the
// offsets and the list.
inline bool relevance_area8(const PointsView& points, const uint32_t* quads, const float* positions,
                            const float* scale, const uint32_t* i, f8 px, f8 py, f8 pz,
                            f8* radius) {
    alignas(32) float k[8];
    for (int l = 0; l < 8; ++l) {
        k[l] = scale[i[l]];
        if (!(k[l] > 0.0f)) return false;  // the repeated lanes repeat a real one
    }
    Moment8 m = zero_moment8();
    uint32_t at[8];
    if (quads) {
        const uint32_t* q[8];
        for (int l = 0; l < 8; ++l) q[l] = quads + size_t(i[l]) * 4;
        for (int n = 0; n < 4; ++n) {
            for (int l = 0; l < 8; ++l) at[l] = q[l][n];
            add_neighbours8(&m, px, py, pz, positions, at);
        }
    } else {
        uint32_t first[8], count[8], most = 0;
        for (int l = 0; l < 8; ++l) {
            first[l] = points.neighbour_offsets[i[l]];
            count[l] = points.neighbour_offsets[i[l] + 1] - first[l];
            most = count[l] > most ? count[l] : most;
        }
        for (uint32_t n = 0; n < most; ++n) {
            for (int l = 0; l < 8; ++l)
                at[l] = n < count[l] ? points.neighbours[first[l] + n] : i[l];
            add_neighbours8(&m, px, py, pz, positions, at);
        }
    }
    *radius = area_radius8(m, k);
    return true;
}

}  // namespace

namespace {

// Writes x, y, z; exactly 3 floats.
inline void store3(float* p, __m128 v) {
    _mm_storeu_si64(p, _mm_castps_si128(v));  // x, y: unaligned, as in load3
    _mm_store_ss(p + 2, _mm_movehl_ps(v, v));
}

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
    __m128 p[4], n[4];
    alignas(16) float len2[4];
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
        const __m128 nn = _mm_mul_ps(n[k], n[k]);
        len2[k] = (lane0(nn) + lane<1>(nn)) + lane<2>(nn);
    }
    const __m128 l = _mm_load_ps(len2);
    const __m128 inv = _mm_and_ps(_mm_cmpgt_ps(l, _mm_set1_ps(1e-20f)),
                                  _mm_div_ps(_mm_set1_ps(1.0f), _mm_sqrt_ps(l)));
    const __m128 s[4] = {_mm_shuffle_ps(inv, inv, 0x00), _mm_shuffle_ps(inv, inv, 0x55),
                         _mm_shuffle_ps(inv, inv, 0xaa), _mm_shuffle_ps(inv, inv, 0xff)};
    for (int k = 0; k < 4; ++k) {
        store3(out_positions + size_t(i[k]) * 3, p[k]);
        store3(out_normals + size_t(i[k]) * 3, _mm_mul_ps(n[k], s[k]));
    }
}

}  // namespace

// point_simd.cpp's pair_vertices, 4 vertices a step: each normal's |n|^2 summed as glm::length
// does, (x x + y y) + z z, then the 4 roots and reciprocals in one vector (correctly rounded, so
// the same bits as std::sqrt and 1 / len; len > 0 false for 0 and NaN: 1/|n| = +0).
void pair_vertices_avx2(uint32_t count, const float* positions, const float* normals, float* out) {
    uint32_t v = 0;
    for (; v + 4 <= count; v += 4) {
        __m128 p[4], n[4];
        alignas(16) float len2[4];
        for (int k = 0; k < 4; ++k) {
            p[k] = load3(positions + size_t(v + k) * 3);
            n[k] = load3(normals + size_t(v + k) * 3);
            const __m128 nn = _mm_mul_ps(n[k], n[k]);
            len2[k] = (lane0(nn) + lane<1>(nn)) + lane<2>(nn);
        }
        const __m128 len = _mm_sqrt_ps(_mm_load_ps(len2));
        const __m128 inv =
            _mm_and_ps(_mm_cmpgt_ps(len, _mm_setzero_ps()), _mm_div_ps(_mm_set1_ps(1.0f), len));
        const __m128 ls[4] = {_mm_shuffle_ps(len, len, 0x00), _mm_shuffle_ps(len, len, 0x55),
                              _mm_shuffle_ps(len, len, 0xaa), _mm_shuffle_ps(len, len, 0xff)};
        const __m128 is[4] = {_mm_shuffle_ps(inv, inv, 0x00), _mm_shuffle_ps(inv, inv, 0x55),
                              _mm_shuffle_ps(inv, inv, 0xaa), _mm_shuffle_ps(inv, inv, 0xff)};
        for (int k = 0; k < 4; ++k) {
            float* o = out + size_t(v + k) * 8;
            _mm_storeu_ps(o, _mm_blend_ps(p[k], ls[k], 0x8));      // x y z |n|
            _mm_storeu_ps(o + 4, _mm_blend_ps(n[k], is[k], 0x8));  // nx ny nz 1/|n|
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

// point_placement.cpp's relevance_radius (Thesis Alg. 6.4): the neighbour moment's I2^(1/4)
// (scale > 0), the mean neighbour distance (scale < 0) or the fallback radius.
void recompute_relevance_avx2(const PointsView& points, const uint32_t* quads,
                              const float* point_positions, const float* scale,
                              const float* fallback_radius, const uint32_t* list, uint32_t begin,
                              uint32_t end, float* out_radius) {
    for (uint32_t j = begin; j < end; j += 8) {
        uint32_t i[8];
        const int lanes = step_indices(list, j, end, i);
        f8 px, py, pz, r;
        xyz8(point_positions, false, 0, i, px, py, pz);
        if (relevance_area8(points, quads, point_positions, scale, i, px, py, pz, &r))
            store1(out_radius, i, lanes, r);
        else
            for (int l = 0; l < lanes; ++l)  // a lane without the area measure: one by one
                out_radius[i[l]] =
                    relevance_radius4(points, point_positions, scale, fallback_radius, i[l]);
    }
}

namespace {

// stipple_size.h's lighting(): ambient + sum of intensity max(N.L, 0), then lit < 1 ? lit : 1.
inline f8 lighting8(const SizeParams& s, f8 nx, f8 ny, f8 nz) {
    const f8 zero = _mm256_setzero_ps(), one = splat(1.0f);
    f8 lit = splat(s.ambient);
    for (int k = 0; k < s.light_count; ++k) {
        const f8 d = dot3(nx, ny, nz, splat(s.light_direction[k].x), splat(s.light_direction[k].y),
                          splat(s.light_direction[k].z));
        const f8 m = select(_mm256_cmp_ps(d, zero, _CMP_LT_OQ), zero, d);  // glm::max(d, 0)
        lit = _mm256_add_ps(lit, _mm256_mul_ps(splat(s.light_intensity[k]), m));
    }
    return select(_mm256_cmp_ps(lit, one, _CMP_LT_OQ), lit, one);
}

// InkTable's 33 entries from i in [0, 32) per lane, table[i]: 4 in-register permutes and 3
// blends by the index's bits 3 and 4 (two AVX2 gathers measured 4% slower over relevance +
// size; the same loads, so the same bits).
inline f8 lookup32(const float* table, i8 i, f8 bit3, f8 bit4) {
    const f8 a = _mm256_permutevar8x32_ps(_mm256_loadu_ps(table), i);
    const f8 b = _mm256_permutevar8x32_ps(_mm256_loadu_ps(table + 8), i);
    const f8 c = _mm256_permutevar8x32_ps(_mm256_loadu_ps(table + 16), i);
    const f8 d = _mm256_permutevar8x32_ps(_mm256_loadu_ps(table + 24), i);
    return _mm256_blendv_ps(_mm256_blendv_ps(a, b, bit3), _mm256_blendv_ps(c, d, bit3), bit4);
}

// InkTable::at.
inline f8 ink_at(const InkTable& t, f8 x) {
    static_assert(InkTable::kSteps == 32, "lookup32 reads 32 entries");
    const f8 zero = _mm256_setzero_ps(), one = splat(1.0f);
    const f8 inner = select(_mm256_cmp_ps(x, one, _CMP_LT_OQ), x, one);
    const f8 c = select(_mm256_cmp_ps(x, zero, _CMP_GT_OQ), inner, zero);
    const f8 xs = _mm256_mul_ps(c, splat(float(InkTable::kSteps)));
    const i8 i = _mm256_min_epi32(_mm256_cvttps_epi32(xs), _mm256_set1_epi32(InkTable::kSteps - 1));
    const f8 bit3 = _mm256_castsi256_ps(_mm256_slli_epi32(i, 28));  // bit 3 in the sign
    const f8 bit4 = _mm256_castsi256_ps(_mm256_slli_epi32(i, 27));
    const f8 lo = lookup32(t.ink, i, bit3, bit4);
    const f8 hi = lookup32(t.ink + 1, i, bit3, bit4);
    return _mm256_add_ps(
        lo, _mm256_mul_ps(_mm256_sub_ps(hi, lo), _mm256_sub_ps(xs, _mm256_cvtepi32_ps(i))));
}

// Alg. 3.2 for 8 points whose positions are in lanes: their normals loaded, r their
// relevance radii; stipple_size.cpp's stipple_size operation by operation (one divide: the
// region's and Alg. 3.2's folded into one ratio).
inline f8 size8(const SizeFrame& f, f8 px, f8 py, f8 pz, const float* normals, f8 r, bool run,
                uint32_t j, const uint32_t* i) {
    const SizeParams& s = *f.params;
    const f8 zero = _mm256_setzero_ps(), one = splat(1.0f);
    f8 nx, ny, nz;
    xyz8(normals, run, j, i, nx, ny, nz);
    const f8 tx = _mm256_sub_ps(splat(s.eye.x), px), ty = _mm256_sub_ps(splat(s.eye.y), py),
             tz = _mm256_sub_ps(splat(s.eye.z), pz);
    const f8 n_dot_t = dot3(nx, ny, nz, tx, ty, tz);
    // glm::dot(vec4): (x + y) + (z + w), with w's product row_w[3] * 1.
    const f8 w = _mm256_add_ps(
        _mm256_add_ps(_mm256_mul_ps(splat(f.row_w[0]), px), _mm256_mul_ps(splat(f.row_w[1]), py)),
        _mm256_add_ps(_mm256_mul_ps(splat(f.row_w[2]), pz), splat(f.row_w[3])));
    const f8 hidden =
        _mm256_or_ps(_mm256_cmp_ps(n_dot_t, zero, _CMP_LE_OQ), _mm256_cmp_ps(w, zero, _CMP_LE_OQ));
    const f8 rf = _mm256_mul_ps(r, splat(f.focal));
    const f8 ink = ink_at(f.table, lighting8(s, nx, ny, nz));
    const f8 num = _mm256_mul_ps(_mm256_mul_ps(ink, _mm256_mul_ps(rf, rf)), n_dot_t);
    const f8 den = _mm256_mul_ps(
        _mm256_mul_ps(w, w),
        _mm256_mul_ps(_mm256_sqrt_ps(dot3(tx, ty, tz, tx, ty, tz)), splat(f.dot_area_per_region)));
    // smooth_size_from_ratio
    f8 t = _mm256_mul_ps(_mm256_sub_ps(_mm256_div_ps(num, den), one), splat(f.inv_slope));
    t = select(_mm256_cmp_ps(t, zero, _CMP_LT_OQ), zero,
               select(_mm256_cmp_ps(t, one, _CMP_GT_OQ), one, t));
    return select(hidden, zero, _mm256_mul_ps(t, splat(s.max_point_size)));
}

}  // namespace

// stipple_size.cpp's stipple_size (Thesis §3.1.1, §3.1.2, Alg. 3.2), 8 points at a time.
void size_stipples_avx2(const SizeFrame& f, const float* positions, const float* normals,
                        const float* radius, const uint32_t* list, uint32_t begin, uint32_t end,
                        float* out_size) {
    for (uint32_t j = begin; j < end; j += 8) {
        uint32_t i[8];
        const int lanes = step_indices(list, j, end, i);
        const bool run = !list && lanes == 8;
        f8 px, py, pz;
        xyz8(positions, run, j, i, px, py, pz);
        put8(out_size, run, j, i, lanes,
             size8(f, px, py, pz, normals, one8(radius, run, j, i), run, j, i));
    }
}

// Relevance then size over the same 8 points (Thesis Alg. 6.4, then Alg. 3.2): each point's
// position is loaded once, into the lanes both stages read, and its new radius goes to size in
// the register it was computed in (stored for the later stages too). The same operations as
// recompute_relevance_avx2 followed by size_stipples_avx2, so the same bits.
void relevance_size_avx2(const PointsView& points, const uint32_t* quads, const SizeFrame& f,
                         const float* positions, const float* normals, const float* scale,
                         const float* fallback_radius, const uint32_t* list, uint32_t begin,
                         uint32_t end, float* out_radius, float* out_size) {
    for (uint32_t j = begin; j < end; j += 8) {
        uint32_t i[8];
        const int lanes = step_indices(list, j, end, i);
        f8 px, py, pz, r;
        xyz8(positions, false, 0, i, px, py, pz);
        if (relevance_area8(points, quads, positions, scale, i, px, py, pz, &r)) {
            store1(out_radius, i, lanes, r);
        } else {
            for (int l = 0; l < lanes; ++l)  // a lane without the area measure: one by one
                out_radius[i[l]] =
                    relevance_radius4(points, positions, scale, fallback_radius, i[l]);
            r = one8(out_radius, false, 0, i);
        }
        store1(out_size, i, lanes, size8(f, px, py, pz, normals, r, false, 0, i));
    }
}

namespace {

// Corner `k` (0, 1, 2) of the 8 triangles tri[0 .. 24): x, y, z across the lanes.
inline void corner8(const float* posed, const uint32_t* tri, int k, f8& x, f8& y, f8& z) {
    uint32_t at[8];
    for (int l = 0; l < 8; ++l) at[l] = tri[3 * l + k];
    xyz8(posed, false, 0, at, x, y, z);
}

}  // namespace

// point_clusters_select.cpp's triangle_stretch (the squared stretches of each triangle, bind
// -> posed), 8 triangles a step: the same products, sums, divides and the std::max choices as
// blends; returns how many triangles it did (a multiple of 8; the caller does the rest).
uint32_t triangle_stretch_avx2(const uint32_t* indices, const float* posed, const float* gram,
                               uint32_t count, float* area_ratio, float* edge_ratio) {
    const f8 zero = _mm256_setzero_ps(), one = splat(1.0f), huge = splat(1e30f), two = splat(2.0f);
    uint32_t t = 0;
    for (; t + 8 <= count; t += 8) {
        // The corners by plain loads transposed into lanes (AVX2 gathers of scattered vertices
        // measured 3x slower than these on the horse), the edges as the scalar code forms
        // them; the 8 triangles' Gram entries are 24 consecutive floats.
        const uint32_t* tri = indices + size_t(t) * 3;
        f8 ox, oy, oz, e1x, e1y, e1z, e2x, e2y, e2z;
        corner8(posed, tri, 0, ox, oy, oz);
        corner8(posed, tri, 1, e1x, e1y, e1z);
        corner8(posed, tri, 2, e2x, e2y, e2z);
        e1x = _mm256_sub_ps(e1x, ox), e1y = _mm256_sub_ps(e1y, oy), e1z = _mm256_sub_ps(e1z, oz);
        e2x = _mm256_sub_ps(e2x, ox), e2y = _mm256_sub_ps(e2y, oy), e2z = _mm256_sub_ps(e2z, oz);
        f8 a, b, cc;
        load_xyz8(gram + size_t(t) * 3, a, b, cc);
        const f8 a2 = dot3(e1x, e1y, e1z, e1x, e1y, e1z), b2 = dot3(e1x, e1y, e1z, e2x, e2y, e2z),
                 c2 = dot3(e2x, e2y, e2z, e2x, e2y, e2z);
        const f8 e3 = _mm256_add_ps(_mm256_sub_ps(a2, _mm256_mul_ps(two, b2)), c2);
        const f8 e3_bind = _mm256_add_ps(_mm256_sub_ps(a, _mm256_mul_ps(two, b)), cc);
        // x > 0 ? num / x : (num > 0 ? 1e30 : 1)
        auto ratio = [&](f8 num, f8 den) {
            const f8 other = select(_mm256_cmp_ps(num, zero, _CMP_GT_OQ), huge, one);
            return select(_mm256_cmp_ps(den, zero, _CMP_GT_OQ), _mm256_div_ps(num, den), other);
        };
        f8 m = ratio(a2, a);  // std::max({..}): the first largest
        const f8 r2 = ratio(c2, cc), r3 = ratio(e3, e3_bind);
        m = select(_mm256_cmp_ps(m, r2, _CMP_LT_OQ), r2, m);
        m = select(_mm256_cmp_ps(m, r3, _CMP_LT_OQ), r3, m);
        _mm256_storeu_ps(edge_ratio + t, m);
        const f8 det = _mm256_sub_ps(_mm256_mul_ps(a, cc), _mm256_mul_ps(b, b));
        const f8 det2 = _mm256_sub_ps(_mm256_mul_ps(a2, c2), _mm256_mul_ps(b2, b2));
        const f8 kept = select(_mm256_cmp_ps(det2, zero, _CMP_LT_OQ), zero, det2);  // std::max
        _mm256_storeu_ps(area_ratio + t, _mm256_div_ps(kept, det));
    }
    return t;
}

}  // namespace stipple

#if defined(__clang__)
#pragma clang attribute pop
#else
#pragma GCC pop_options
#endif

#endif
