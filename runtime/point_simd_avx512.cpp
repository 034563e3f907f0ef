// The fused relevance + size kernel (Thesis Alg. 6.4, then Alg. 3.2) 16 points per step in
// AVX-512 lanes, for CPUs that have AVX-512 F, VL, DQ and BW (runtime/point_simd.h's avx512
// path; the other stages keep their AVX2 kernels there). It mirrors relevance_size_avx2 of
// runtime/point_simd_avx2.cpp operation by operation, 16 lanes instead of 8: the same loads,
// products, sums in the same order, sqrt and divide (no rsqrt14/rcp14), the same comparisons
// and clamps (max_ps(c, x) for c < x ? c : x, as there), no FMA (this file is built with
// -ffp-contract=off), so every lane gives the bits the scalar code gives. What the width buys:
// half the arithmetic and half the transposes' shuffles per point, and the ink table's 33
// entries read by two two-source permutes per value instead of four permutes and three blends.
// A block whose scales are not all > 0 (the mean distance, the fallback radius) and the last
// block of fewer than 16 points go to the AVX2 kernel, which gives them the same bits.
#include <cstddef>
#include <cstdint>

#include "runtime/point_simd.h"

#if STIPPLE_AVX2_KERNELS
#include <immintrin.h>

#if defined(__clang__)
#pragma clang attribute push(__attribute__((target("avx512f,avx512vl,avx512dq,avx512bw"))), \
                             apply_to = function)
#else
#pragma GCC push_options
#pragma GCC target("avx512f,avx512vl,avx512dq,avx512bw")
// GCC 12's AVX-512 headers pass _mm512_undefined_ps() (`__m512 __Y = __Y;`) as the unused
// source of unmasked intrinsics, which -Wmaybe-uninitialized (-O3) and -Wuninitialized (-O2,
// the sanitizer build) report once they are inlined (GCC PR 105593, fixed in GCC 13).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"
#endif

namespace stipple {
namespace {

using f16 = __m512;
using i16 = __m512i;

inline f16 splat(float x) {
    return _mm512_set1_ps(x);
}

// Four points' x, y, z and one float past them (16-byte loads, point_simd.h's kSimdPadFloats),
// point 0 in the lowest 128 bits.
inline f16 quarters(const float* a, const float* b, const float* c, const float* d) {
    const __m256 lo =
        _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(a)), _mm_loadu_ps(b), 1);
    const __m256 hi =
        _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(c)), _mm_loadu_ps(d), 1);
    return _mm512_insertf32x8(_mm512_castps256_ps512(lo), hi, 1);
}
// Points k, k + 4, k + 8, k + 12 in the four 128-bit lanes of a, b, c, d (k = 0 .. 3) to x, y, z
// across 16 lanes in point order: one in-lane transpose (point_simd_avx2_lanes.inc's
// transpose_xyz8, four lanes wide).
inline void transpose_xyz16(f16 a, f16 b, f16 c, f16 d, f16& x, f16& y, f16& z) {
    const f16 ab_xy = _mm512_unpacklo_ps(a, b), cd_xy = _mm512_unpacklo_ps(c, d);  // x x y y
    const f16 ab_z = _mm512_unpackhi_ps(a, b), cd_z = _mm512_unpackhi_ps(c, d);    // z z w w
    x = _mm512_shuffle_ps(ab_xy, cd_xy, _MM_SHUFFLE(1, 0, 1, 0));
    y = _mm512_shuffle_ps(ab_xy, cd_xy, _MM_SHUFFLE(3, 2, 3, 2));
    z = _mm512_shuffle_ps(ab_z, cd_z, _MM_SHUFFLE(1, 0, 1, 0));
}
// The x, y, z of the 16 points at float offsets o[0 .. 16).
inline void xyz16(const float* base, const uint32_t* o, f16& x, f16& y, f16& z) {
    const f16 a = quarters(base + o[0], base + o[4], base + o[8], base + o[12]);
    const f16 b = quarters(base + o[1], base + o[5], base + o[9], base + o[13]);
    const f16 c = quarters(base + o[2], base + o[6], base + o[10], base + o[14]);
    const f16 d = quarters(base + o[3], base + o[7], base + o[11], base + o[15]);
    transpose_xyz16(a, b, c, d, x, y, z);
}
// The 16 points' quad_neighbours records (4 float offsets each) transposed: o[n][l] is
// neighbour n of point l (one load per neighbour later, not a pointer and then an offset).
inline void neighbour_offsets16(const uint32_t* quads, const uint32_t* i, uint32_t (*o)[16]) {
    auto rec = [&](int l) { return reinterpret_cast<const float*>(quads + size_t(i[l]) * 4); };
    const f16 a = quarters(rec(0), rec(4), rec(8), rec(12));
    const f16 b = quarters(rec(1), rec(5), rec(9), rec(13));
    const f16 c = quarters(rec(2), rec(6), rec(10), rec(14));
    const f16 d = quarters(rec(3), rec(7), rec(11), rec(15));
    const f16 ab_01 = _mm512_unpacklo_ps(a, b), cd_01 = _mm512_unpacklo_ps(c, d);
    const f16 ab_23 = _mm512_unpackhi_ps(a, b), cd_23 = _mm512_unpackhi_ps(c, d);
    _mm512_store_ps(reinterpret_cast<float*>(o[0]),
                    _mm512_shuffle_ps(ab_01, cd_01, _MM_SHUFFLE(1, 0, 1, 0)));
    _mm512_store_ps(reinterpret_cast<float*>(o[1]),
                    _mm512_shuffle_ps(ab_01, cd_01, _MM_SHUFFLE(3, 2, 3, 2)));
    _mm512_store_ps(reinterpret_cast<float*>(o[2]),
                    _mm512_shuffle_ps(ab_23, cd_23, _MM_SHUFFLE(1, 0, 1, 0)));
    _mm512_store_ps(reinterpret_cast<float*>(o[3]),
                    _mm512_shuffle_ps(ab_23, cd_23, _MM_SHUFFLE(3, 2, 3, 2)));
}

// x0 y0 + x1 y1 + x2 y2, left to right (glm::dot on vec3).
inline f16 dot3(f16 x0, f16 x1, f16 x2, f16 y0, f16 y1, f16 y2) {
    return _mm512_add_ps(_mm512_add_ps(_mm512_mul_ps(x0, y0), _mm512_mul_ps(x1, y1)),
                         _mm512_mul_ps(x2, y2));
}

// Alg. 6.4's area measure of the 16 points, each lane summing its point's 4 neighbours in
// order (a padded entry is the point itself: d = +0, which leaves a sum's bits), then
// k I2^(1/4) with I2 clamped at 0 (relevance_area8 and area_radius8 of point_simd_avx2.cpp).
inline f16 area_radius16(const float* positions, const uint32_t (*o)[16], f16 px, f16 py, f16 pz,
                         f16 k) {
    f16 xx = _mm512_setzero_ps(), yy = xx, zz = xx, xy = xx, xz = xx, yz = xx;
    for (int n = 0; n < 4; ++n) {
        f16 qx, qy, qz;
        xyz16(positions, o[n], qx, qy, qz);
        const f16 dx = _mm512_sub_ps(qx, px), dy = _mm512_sub_ps(qy, py),
                  dz = _mm512_sub_ps(qz, pz);
        xx = _mm512_add_ps(xx, _mm512_mul_ps(dx, dx));
        yy = _mm512_add_ps(yy, _mm512_mul_ps(dy, dy));
        zz = _mm512_add_ps(zz, _mm512_mul_ps(dz, dz));
        xy = _mm512_add_ps(xy, _mm512_mul_ps(dx, dy));
        xz = _mm512_add_ps(xz, _mm512_mul_ps(dx, dz));
        yz = _mm512_add_ps(yz, _mm512_mul_ps(dy, dz));
    }
    const f16 i2 =
        _mm512_add_ps(_mm512_add_ps(_mm512_sub_ps(_mm512_mul_ps(xx, yy), _mm512_mul_ps(xy, xy)),
                                    _mm512_sub_ps(_mm512_mul_ps(xx, zz), _mm512_mul_ps(xz, xz))),
                      _mm512_sub_ps(_mm512_mul_ps(yy, zz), _mm512_mul_ps(yz, yz)));
    const f16 kept = _mm512_max_ps(_mm512_setzero_ps(), i2);  // i2 < 0 ? 0 : i2
    return _mm512_mul_ps(k, _mm512_sqrt_ps(_mm512_sqrt_ps(kept)));
}

// stipple_size.h's lighting(): ambient + sum of intensity max(N.L, 0), then lit < 1 ? lit : 1.
inline f16 lighting16(const SizeParams& s, f16 nx, f16 ny, f16 nz) {
    f16 lit = splat(s.ambient);
    for (int k = 0; k < s.light_count; ++k) {
        const f16 d = dot3(nx, ny, nz, splat(s.light_direction[k].x), splat(s.light_direction[k].y),
                           splat(s.light_direction[k].z));
        const f16 m = _mm512_max_ps(_mm512_setzero_ps(), d);  // d < 0 ? 0 : d
        lit = _mm512_add_ps(lit, _mm512_mul_ps(splat(s.light_intensity[k]), m));
    }
    return _mm512_min_ps(lit, splat(1.0f));  // lit < 1 ? lit : 1
}

// InkTable::at: table[i] and table[i + 1] for i in [0, 32), each one two-source permute of the
// same 32 loaded entries (so the same values as the AVX2 lookup).
inline f16 ink_at16(const InkTable& t, f16 x) {
    static_assert(InkTable::kSteps == 32, "the permutes read 32 entries");
    const f16 zero = _mm512_setzero_ps();
    const f16 inner = _mm512_min_ps(x, splat(1.0f));  // x < 1 ? x : 1
    const f16 c = _mm512_maskz_mov_ps(_mm512_cmp_ps_mask(x, zero, _CMP_GT_OQ), inner);
    const f16 xs = _mm512_mul_ps(c, splat(float(InkTable::kSteps)));
    const i16 i =
        _mm512_min_epi32(_mm512_cvttps_epi32(xs), _mm512_set1_epi32(InkTable::kSteps - 1));
    const f16 lo = _mm512_permutex2var_ps(_mm512_loadu_ps(t.ink), i, _mm512_loadu_ps(t.ink + 16));
    const f16 hi =
        _mm512_permutex2var_ps(_mm512_loadu_ps(t.ink + 1), i, _mm512_loadu_ps(t.ink + 17));
    return _mm512_add_ps(
        lo, _mm512_mul_ps(_mm512_sub_ps(hi, lo), _mm512_sub_ps(xs, _mm512_cvtepi32_ps(i))));
}

// Alg. 3.2 for the 16 points whose positions are in lanes (size8 of point_simd_avx2.cpp).
inline f16 size16(const SizeFrame& f, f16 px, f16 py, f16 pz, const float* normals,
                  const uint32_t* o, f16 r) {
    const SizeParams& s = *f.params;
    const f16 zero = _mm512_setzero_ps(), one = splat(1.0f);
    f16 nx, ny, nz;
    xyz16(normals, o, nx, ny, nz);
    const f16 tx = _mm512_sub_ps(splat(s.eye.x), px), ty = _mm512_sub_ps(splat(s.eye.y), py),
              tz = _mm512_sub_ps(splat(s.eye.z), pz);
    const f16 n_dot_t = dot3(nx, ny, nz, tx, ty, tz);
    // glm::dot(vec4): (x + y) + (z + w), with w's product row_w[3] * 1.
    const f16 w = _mm512_add_ps(
        _mm512_add_ps(_mm512_mul_ps(splat(f.row_w[0]), px), _mm512_mul_ps(splat(f.row_w[1]), py)),
        _mm512_add_ps(_mm512_mul_ps(splat(f.row_w[2]), pz), splat(f.row_w[3])));
    const __mmask16 shown = _mm512_cmp_ps_mask(n_dot_t, zero, _CMP_NLE_UQ) &
                            _mm512_cmp_ps_mask(w, zero, _CMP_NLE_UQ);  // not (<= 0)
    const f16 rf = _mm512_mul_ps(r, splat(f.focal));
    const f16 ink = ink_at16(f.table, lighting16(s, nx, ny, nz));
    const f16 num = _mm512_mul_ps(_mm512_mul_ps(ink, _mm512_mul_ps(rf, rf)), n_dot_t);
    const f16 den = _mm512_mul_ps(
        _mm512_mul_ps(w, w),
        _mm512_mul_ps(_mm512_sqrt_ps(dot3(tx, ty, tz, tx, ty, tz)), splat(f.dot_area_per_region)));
    f16 t = _mm512_mul_ps(_mm512_sub_ps(_mm512_div_ps(num, den), one), splat(f.inv_slope));
    t = _mm512_max_ps(zero, _mm512_min_ps(one, t));  // t < 0 ? 0 : (t > 1 ? 1 : t)
    return _mm512_maskz_mov_ps(shown, _mm512_mul_ps(t, splat(s.max_point_size)));  // hidden: +0
}

// Writes the 16 lanes of v to out[idx[k]].
inline void store16(float* out, const uint32_t* idx, f16 v) {
    alignas(64) float vv[16];
    _mm512_store_ps(vv, v);
    for (int k = 0; k < 16; ++k) out[idx[k]] = vv[k];
}

// One step: the 16 points i[0 .. 16). False (nothing written) when a scale is not > 0.
inline bool relevance_size16(const uint32_t* quads, const SizeFrame& f, const float* positions,
                             const float* normals, const float* scale, const uint32_t* i,
                             float* out_radius, float* out_size) {
    const i16 idx = _mm512_loadu_si512(i);
    const f16 k = _mm512_i32gather_ps(idx, scale, 4);
    if (_mm512_cmp_ps_mask(k, _mm512_setzero_ps(), _CMP_GT_OQ) != 0xFFFF) return false;
    alignas(64) uint32_t o[16];  // float offsets of the points: 3 i
    _mm512_store_si512(o, _mm512_mullo_epi32(idx, _mm512_set1_epi32(3)));
    alignas(64) uint32_t q[4][16];
    neighbour_offsets16(quads, i, q);
    f16 px, py, pz;
    xyz16(positions, o, px, py, pz);
    const f16 r = area_radius16(positions, q, px, py, pz, k);
    store16(out_radius, i, r);
    store16(out_size, i, size16(f, px, py, pz, normals, o, r));
    return true;
}

}  // namespace

// relevance_size_avx2, 16 points a step (point_simd.h). Needs `quads`: without them every
// block goes to the AVX2 kernel.
void relevance_size_avx512(const PointsView& points, const uint32_t* quads, const SizeFrame& f,
                           const float* positions, const float* normals, const float* scale,
                           const float* fallback_radius, const uint32_t* list, uint32_t begin,
                           uint32_t end, float* out_radius, float* out_size) {
    uint32_t j = begin;
    for (; quads && j + 16 <= end; j += 16) {
        uint32_t own[16];
        const uint32_t* i = list ? list + j : own;
        if (!list)
            for (uint32_t l = 0; l < 16; ++l) own[l] = j + l;
        if (!relevance_size16(quads, f, positions, normals, scale, i, out_radius, out_size))
            relevance_size_avx2(points, quads, f, positions, normals, scale, fallback_radius, i, 0,
                                16, out_radius, out_size);
    }
    if (j < end)
        relevance_size_avx2(points, quads, f, positions, normals, scale, fallback_radius, list, j,
                            end, out_radius, out_size);
}

}  // namespace stipple

#if defined(__clang__)
#pragma clang attribute pop
#else
#pragma GCC diagnostic pop
#pragma GCC pop_options
#endif
#endif
