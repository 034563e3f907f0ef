// AVX2 variants of the CPU point stages (runtime/point_simd.h): size and relevance 8 points
// per step (scattered points loaded one by one and transposed: AVX2 gathers measured twice as
// slow per element on this Zen 5); place is in point_place_avx2.cpp, the lanes and loads both
// share in point_simd_avx2_lanes.inc. Each kernel mirrors its scalar
// original operation by operation: same products, sums in the same order, sqrt and divide (no
// rsqrt/rcp), the scalar code's comparisons and clamps as blends with the same NaN behaviour, no
// FMA (the target is avx2 alone and this file is built with -ffp-contract=off), so every lane gives
// the bits the scalar code gives. A choice c < x ? c : x is max_ps(c, x) and x < c ? x : c is
// min_ps(x, c), one instruction with the same result for NaN and signed zeros (max_ps(a, b) is
// a > b ? a : b). Every header is included before the target pragma, and only
// intrinsics and this file's own internal functions run under it, so no inline function shared with
// other files is compiled for AVX2 (which the linker could pick for the baseline callers too).
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "runtime/point_simd.h"

#if STIPPLE_AVX2_KERNELS
#include "runtime/point_simd_avx2_begin.inc"

namespace stipple {

#include "runtime/point_simd_avx2_lanes.inc"

namespace {

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
// The neighbours at[0 .. 8) of the 8 points px, py, pz, one per lane: float offsets (3 times
// the index) when `offsets`, else indices.
inline void add_neighbours8(Moment8* m, f8 px, f8 py, f8 pz, const float* positions,
                            const uint32_t* at, bool offsets) {
    f8 qx, qy, qz;
    if (offsets)
        xyz8_at(positions, at, qx, qy, qz);
    else
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
inline f8 area_radius8(const Moment8& m, f8 k) {
    const f8 i2 = _mm256_add_ps(
        _mm256_add_ps(_mm256_sub_ps(_mm256_mul_ps(m.xx, m.yy), _mm256_mul_ps(m.xy, m.xy)),
                      _mm256_sub_ps(_mm256_mul_ps(m.xx, m.zz), _mm256_mul_ps(m.xz, m.xz))),
        _mm256_sub_ps(_mm256_mul_ps(m.yy, m.zz), _mm256_mul_ps(m.yz, m.yz)));
    const f8 kept = _mm256_max_ps(_mm256_setzero_ps(), i2);  // i2 < 0 ? 0 : i2
    return _mm256_mul_ps(k, _mm256_sqrt_ps(_mm256_sqrt_ps(kept)));
}

// Alg. 6.4's area measure for the 8 points i[0 .. 8) at once, each point's neighbours in its
// lane, lanes past a point's last neighbour adding d = p - p = +0 (a sum that starts at +0
// never becomes -0, so adding +0 leaves its bits), then k I2^(1/4) into *radius; px, py, pz
// are the 8 points' positions. Returns false (radius not set) when a real lane's scale is not > 0
// (the mean distance or the fallback radius: the caller takes those points one by one). With
// `quads` (point_simd.h's quad_neighbours) the neighbours come from one 16-byte record per point
// (their float offsets), four steps for every block (a padded entry is the point itself: the same
// +0); otherwise from the offsets and the list. Always inlined: GCC's size heuristics may leave
// it out of line, and a call that passes 8-lane vectors on the stack costs 1.5x.
__attribute__((always_inline)) inline bool relevance_area8(const PointsView& points,
                                                           const uint32_t* quads,
                                                           const float* positions,
                                                           const float* scale, const uint32_t* i,
                                                           f8 px, f8 py, f8 pz, f8* radius) {
    // One comparison for the 8 scales (the repeated lanes repeat a real one; NaN is not > 0).
    const f8 k = _mm256_setr_ps(scale[i[0]], scale[i[1]], scale[i[2]], scale[i[3]], scale[i[4]],
                                scale[i[5]], scale[i[6]], scale[i[7]]);
    if (_mm256_movemask_ps(_mm256_cmp_ps(k, _mm256_setzero_ps(), _CMP_GT_OQ)) != 0xFF) return false;
    Moment8 m = zero_moment8();
    uint32_t at[8];
    if (quads) {
        const uint32_t* q[8];
        for (int l = 0; l < 8; ++l) q[l] = quads + size_t(i[l]) * 4;
        for (int n = 0; n < 4; ++n) {
            for (int l = 0; l < 8; ++l) at[l] = q[l][n];
            add_neighbours8(&m, px, py, pz, positions, at, true);
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
            add_neighbours8(&m, px, py, pz, positions, at, false);
        }
    }
    *radius = area_radius8(m, k);
    return true;
}

}  // namespace

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
        const f8 m = _mm256_max_ps(zero, d);  // glm::max(d, 0): d < 0 ? 0 : d
        lit = _mm256_add_ps(lit, _mm256_mul_ps(splat(s.light_intensity[k]), m));
    }
    return _mm256_min_ps(lit, one);  // lit < 1 ? lit : 1
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
    const f8 inner = _mm256_min_ps(x, one);                                 // x < 1 ? x : 1
    const f8 c = _mm256_and_ps(_mm256_cmp_ps(x, zero, _CMP_GT_OQ), inner);  // x > 0 ? inner : 0
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
    t = _mm256_max_ps(zero, _mm256_min_ps(one, t));  // t < 0 ? 0 : (t > 1 ? 1 : t)
    return _mm256_andnot_ps(hidden, _mm256_mul_ps(t, splat(s.max_point_size)));  // hidden: 0
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

namespace {

// relevance_size_avx2's step: the points i[0 .. 8), of which the first `lanes` are real.
__attribute__((always_inline)) inline void relevance_size8(
    const PointsView& points, const uint32_t* quads, const SizeFrame& f, const float* positions,
    const float* normals, const float* scale, const float* fallback_radius, const uint32_t* i,
    int lanes, float* out_radius, float* out_size) {
    f8 px, py, pz, r;
    xyz8(positions, false, 0, i, px, py, pz);
    if (relevance_area8(points, quads, positions, scale, i, px, py, pz, &r)) {
        store1(out_radius, i, lanes, r);
    } else {
        for (int l = 0; l < lanes; ++l)  // a lane without the area measure: one by one
            out_radius[i[l]] = relevance_radius4(points, positions, scale, fallback_radius, i[l]);
        r = one8(out_radius, false, 0, i);
    }
    store1(out_size, i, lanes, size8(f, px, py, pz, normals, r, false, 0, i));
}

}  // namespace

// Relevance then size over the same 8 points (Thesis Alg. 6.4, then Alg. 3.2): each point's
// position is loaded once, into the lanes both stages read, and its new radius goes to size in
// the register it was computed in (stored for the later stages too). The same operations as
// recompute_relevance_avx2 followed by size_stipples_avx2, so the same bits. The full steps of a
// list read their indices from the list itself (no copy and no test per lane: 5% of the time).
void relevance_size_avx2(const PointsView& points, const uint32_t* quads, const SizeFrame& f,
                         const float* positions, const float* normals, const float* scale,
                         const float* fallback_radius, const uint32_t* list, uint32_t begin,
                         uint32_t end, float* out_radius, float* out_size) {
    uint32_t j = begin;
    if (list)
        for (; j + 8 <= end; j += 8)
            relevance_size8(points, quads, f, positions, normals, scale, fallback_radius, list + j,
                            8, out_radius, out_size);
    for (; j < end; j += 8) {
        uint32_t i[8];
        const int lanes = step_indices(list, j, end, i);
        relevance_size8(points, quads, f, positions, normals, scale, fallback_radius, i, lanes,
                        out_radius, out_size);
    }
}

namespace {

// Corner `k` (0, 1, 2) of the 8 triangles tri[0 .. 24): x, y, z across the lanes.
inline void corner8(const float* posed, const uint32_t* tri, int k, f8& x, f8& y, f8& z) {
    uint32_t at[8];
    for (int l = 0; l < 8; ++l) at[l] = tri[3 * l + k];
    xyz8(posed, false, 0, at, x, y, z);
}

// The 8 triangles tri[0 .. 24): their corner 0 and their edges from it (corner 1 - corner 0,
// corner 2 - corner 0), across the lanes, formed as the scalar code forms them. The corners by
// plain loads transposed into lanes (AVX2 gathers of scattered vertices measured 3x slower than
// these on the horse).
struct Edges8 {
    f8 ox, oy, oz, e1x, e1y, e1z, e2x, e2y, e2z;
};
__attribute__((always_inline)) inline Edges8 edges8(const float* posed, const uint32_t* tri) {
    Edges8 e;
    corner8(posed, tri, 0, e.ox, e.oy, e.oz);
    corner8(posed, tri, 1, e.e1x, e.e1y, e.e1z);
    corner8(posed, tri, 2, e.e2x, e.e2y, e.e2z);
    e.e1x = _mm256_sub_ps(e.e1x, e.ox), e.e1y = _mm256_sub_ps(e.e1y, e.oy);
    e.e1z = _mm256_sub_ps(e.e1z, e.oz);
    e.e2x = _mm256_sub_ps(e.e2x, e.ox), e.e2y = _mm256_sub_ps(e.e2y, e.oy);
    e.e2z = _mm256_sub_ps(e.e2z, e.oz);
    return e;
}

// The x, y, z of corner k of the 4 triangles listed at tris[0 .. 4), as doubles across 4 lanes
// (float to double is exact: converting before or after the transpose gives the same values).
// load3 reads exactly 3 floats, so `posed` needs no padding.
inline void corner4d(const float* posed, const uint32_t* indices, const uint32_t* tris, int k,
                     __m256d& x, __m256d& y, __m256d& z) {
    __m128 r0 = load3(posed + size_t(indices[size_t(tris[0]) * 3 + k]) * 3);
    __m128 r1 = load3(posed + size_t(indices[size_t(tris[1]) * 3 + k]) * 3);
    __m128 r2 = load3(posed + size_t(indices[size_t(tris[2]) * 3 + k]) * 3);
    __m128 r3 = load3(posed + size_t(indices[size_t(tris[3]) * 3 + k]) * 3);
    _MM_TRANSPOSE4_PS(r0, r1, r2, r3);
    x = _mm256_cvtps_pd(r0), y = _mm256_cvtps_pd(r1), z = _mm256_cvtps_pd(r2);
}
// dot3 in double lanes: x0 y0 + x1 y1 + x2 y2, left to right (glm::dot on dvec3).
inline __m256d dot3d(__m256d x0, __m256d x1, __m256d x2, __m256d y0, __m256d y1, __m256d y2) {
    return _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(x0, y0), _mm256_mul_pd(x1, y1)),
                         _mm256_mul_pd(x2, y2));
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
        // The 8 triangles' Gram entries are 24 consecutive floats.
        const Edges8 e = edges8(posed, indices + size_t(t) * 3);
        const f8 e1x = e.e1x, e1y = e.e1y, e1z = e.e1z, e2x = e.e2x, e2y = e.e2y, e2z = e.e2z;
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
        m = _mm256_max_ps(r2, m);  // m < r2 ? r2 : m
        m = _mm256_max_ps(r3, m);
        _mm256_storeu_ps(edge_ratio + t, m);
        const f8 det = _mm256_sub_ps(_mm256_mul_ps(a, cc), _mm256_mul_ps(b, b));
        const f8 det2 = _mm256_sub_ps(_mm256_mul_ps(a2, c2), _mm256_mul_ps(b2, b2));
        const f8 kept = _mm256_max_ps(zero, det2);  // std::max(det2, 0): det2 < 0 ? 0 : det2
        _mm256_storeu_ps(area_ratio + t, _mm256_div_ps(kept, det));
    }
    return t;
}

// silhouette.cpp's triangle_facing, 8 triangles a step: the same differences, cross products and
// dot products in the same order, so the same flags.
uint32_t triangle_facing_avx2(const uint32_t* indices, const float* positions, const float* eye,
                              uint32_t count, uint8_t* front) {
    const f8 zero = _mm256_setzero_ps(), edge_on2 = splat(1.0f / (64.0f * 64.0f));
    const f8 eye_x = splat(eye[0]), eye_y = splat(eye[1]), eye_z = splat(eye[2]);
    const i8 one = _mm256_set1_epi32(1), two = _mm256_set1_epi32(2);
    uint32_t t = 0;
    for (; t + 8 <= count; t += 8) {
        const Edges8 e = edges8(positions, indices + size_t(t) * 3);
        const f8 ax = e.ox, ay = e.oy, az = e.oz, ux = e.e1x, uy = e.e1y, uz = e.e1z, vx = e.e2x,
                 vy = e.e2y, vz = e.e2z;
        const f8 nx = _mm256_sub_ps(_mm256_mul_ps(uy, vz), _mm256_mul_ps(uz, vy));
        const f8 ny = _mm256_sub_ps(_mm256_mul_ps(uz, vx), _mm256_mul_ps(ux, vz));
        const f8 nz = _mm256_sub_ps(_mm256_mul_ps(ux, vy), _mm256_mul_ps(uy, vx));
        const f8 ex = _mm256_sub_ps(eye_x, ax), ey = _mm256_sub_ps(eye_y, ay),
                 ez = _mm256_sub_ps(eye_z, az);
        const f8 d = dot3(nx, ny, nz, ex, ey, ez);
        const f8 n2 = dot3(nx, ny, nz, nx, ny, nz), e2 = dot3(ex, ey, ez, ex, ey, ez);
        const f8 is_front = _mm256_cmp_ps(d, zero, _CMP_GT_OQ);
        const f8 edge_on = _mm256_cmp_ps(
            _mm256_mul_ps(d, d), _mm256_mul_ps(_mm256_mul_ps(edge_on2, n2), e2), _CMP_LE_OQ);
        // kFacingFront (1) where front, else kFacingEdgeOn (2) where edge-on, else 0.
        const i8 flags = _mm256_or_si256(
            _mm256_and_si256(_mm256_castps_si256(is_front), one),
            _mm256_and_si256(_mm256_castps_si256(_mm256_andnot_ps(is_front, edge_on)), two));
        const __m128i words =
            _mm_packus_epi32(_mm256_castsi256_si128(flags), _mm256_extracti128_si256(flags, 1));
        _mm_storel_epi64(reinterpret_cast<__m128i*>(front + t), _mm_packus_epi16(words, words));
    }
    return t;
}

// refinement_sigma.cpp's sigma2 for the triangles listed, 4 a step in double lanes: the same
// differences, dot products, products, sums, root and divide in the same order, std::max as
// max_pd(0, x) (0 > x ? 0 : x, x < 0 ? 0 : x with the same NaN), the same float rounding; returns
// how many it did (a multiple of 4; the caller runs the scalar code on the rest).
uint32_t triangle_sigma2_avx2(const uint32_t* triangles, uint32_t count, const uint32_t* indices,
                              const float* posed, const float* bind_gram, float* sigma) {
    using d4 = __m256d;
    const d4 zero = _mm256_setzero_pd(), two = _mm256_set1_pd(2.0), four = _mm256_set1_pd(4.0);
    const d4 tiny = _mm256_set1_pd(1e-10), above = _mm256_set1_pd(1.0 + 1e-5);
    uint32_t j = 0;
    for (; j + 4 <= count; j += 4) {
        const uint32_t* tris = triangles + j;
        d4 ax, ay, az, e1x, e1y, e1z, e2x, e2y, e2z;
        corner4d(posed, indices, tris, 0, ax, ay, az);
        corner4d(posed, indices, tris, 1, e1x, e1y, e1z);
        corner4d(posed, indices, tris, 2, e2x, e2y, e2z);
        e1x = _mm256_sub_pd(e1x, ax), e1y = _mm256_sub_pd(e1y, ay), e1z = _mm256_sub_pd(e1z, az);
        e2x = _mm256_sub_pd(e2x, ax), e2y = _mm256_sub_pd(e2y, ay), e2z = _mm256_sub_pd(e2z, az);
        const d4 p11 = dot3d(e1x, e1y, e1z, e1x, e1y, e1z),
                 p12 = dot3d(e1x, e1y, e1z, e2x, e2y, e2z),
                 p22 = dot3d(e2x, e2y, e2z, e2x, e2y, e2z);
        __m128 g0 = load3(bind_gram + size_t(tris[0]) * 3),
               g1 = load3(bind_gram + size_t(tris[1]) * 3);
        __m128 g2 = load3(bind_gram + size_t(tris[2]) * 3),
               g3 = load3(bind_gram + size_t(tris[3]) * 3);
        _MM_TRANSPOSE4_PS(g0, g1, g2, g3);
        const d4 g11 = _mm256_cvtps_pd(g0), g12 = _mm256_cvtps_pd(g1), g22 = _mm256_cvtps_pd(g2);
        const d4 det = _mm256_sub_pd(_mm256_mul_pd(g11, g22), _mm256_mul_pd(g12, g12));
        const d4 trace = _mm256_add_pd(g11, g22);
        const d4 has_area =
            _mm256_cmp_pd(det, _mm256_mul_pd(_mm256_mul_pd(tiny, trace), trace), _CMP_GT_OQ);
        const d4 b = _mm256_sub_pd(_mm256_add_pd(_mm256_mul_pd(p11, g22), _mm256_mul_pd(p22, g11)),
                                   _mm256_mul_pd(_mm256_mul_pd(two, p12), g12));
        const d4 q = _mm256_sub_pd(_mm256_mul_pd(p11, p22), _mm256_mul_pd(p12, p12));
        const d4 disc = _mm256_max_pd(
            zero, _mm256_sub_pd(_mm256_mul_pd(b, b), _mm256_mul_pd(_mm256_mul_pd(four, det), q)));
        const d4 s = _mm256_div_pd(_mm256_add_pd(b, _mm256_sqrt_pd(disc)), _mm256_mul_pd(two, det));
        const d4 ok = _mm256_and_pd(has_area, _mm256_cmp_pd(s, s, _CMP_EQ_OQ));
        const d4 value = _mm256_blendv_pd(_mm256_set1_pd(INFINITY), _mm256_mul_pd(s, above), ok);
        alignas(16) float lanes[4];
        _mm_store_ps(lanes, _mm256_cvtpd_ps(value));  // +inf stays +inf
        for (int k = 0; k < 4; ++k) sigma[tris[k]] = lanes[k];
    }
    return j;
}

}  // namespace stipple

#include "runtime/point_simd_avx2_end.inc"
#endif
