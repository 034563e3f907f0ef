// Internal: a 4-wide float vector for the anim/ kernels, so each kernel is written once and
// compiles to SSE2 (x86-64 baseline), NEON (AArch64/ARMv7 with NEON), or plain C++ (any
// other target, and -DSTIPPLE_ANIM_NO_SIMD). Only what the kernels need; all inline.
// Not part of the public API (anim.h).
#pragma once
#include <cmath>
#include <cstdint>
#include <cstring>

#if !defined(STIPPLE_ANIM_NO_SIMD) && defined(__SSE2__)
#include <emmintrin.h>
#define STIPPLE_ANIM_SSE2 1
#elif !defined(STIPPLE_ANIM_NO_SIMD) && (defined(__ARM_NEON) || defined(__ARM_NEON__))
#include <arm_neon.h>
#define STIPPLE_ANIM_NEON 1
#endif

namespace stipple::anim::simd {

#if defined(STIPPLE_ANIM_SSE2)

constexpr const char* kPath = "sse2";
using f4 = __m128;
inline f4 load(const float* p) {
    return _mm_loadu_ps(p);
}
inline void store(float* p, f4 v) {
    _mm_storeu_ps(p, v);
}
inline f4 splat(float x) {
    return _mm_set1_ps(x);
}
inline f4 set(float x, float y, float z, float w) {
    return _mm_setr_ps(x, y, z, w);
}
inline f4 zero() {
    return _mm_setzero_ps();
}
inline f4 add(f4 a, f4 b) {
    return _mm_add_ps(a, b);
}
inline f4 sub(f4 a, f4 b) {
    return _mm_sub_ps(a, b);
}
inline f4 mul(f4 a, f4 b) {
    return _mm_mul_ps(a, b);
}
inline f4 div(f4 a, f4 b) {
    return _mm_div_ps(a, b);
}
inline f4 madd(f4 a, f4 b, f4 c) {
    return _mm_add_ps(_mm_mul_ps(a, b), c);
}  // a * b + c
inline f4 sqrt(f4 a) {
    return _mm_sqrt_ps(a);
}
inline f4 max(f4 a, f4 b) {
    return _mm_max_ps(a, b);
}
// Flips the sign of each lane of v where the same lane of s is negative (sign bit set).
inline f4 flip_sign(f4 v, f4 s) {
    return _mm_xor_ps(v, _mm_and_ps(s, _mm_castsi128_ps(_mm_set1_epi32(INT32_MIN))));
}
template <int i>
inline f4 lane(f4 v) {
    return _mm_shuffle_ps(v, v, _MM_SHUFFLE(i, i, i, i));
}
inline float first(f4 v) {
    return _mm_cvtss_f32(v);
}
// x, y, z from memory, w = 0; reads exactly 3 floats.
inline f4 load3(const float* p) {
    const __m128 xy = _mm_castsi128_ps(_mm_loadu_si64(p));
    return _mm_movelh_ps(xy, _mm_load_ss(p + 2));
}
// Writes x, y, z; exactly 3 floats.
inline void store3(float* p, f4 v) {
    _mm_storeu_si64(p, _mm_castps_si128(v));
    _mm_store_ss(p + 2, _mm_movehl_ps(v, v));
}
inline void transpose(f4& a, f4& b, f4& c, f4& d) {
    _MM_TRANSPOSE4_PS(a, b, c, d);
}
// Bit mask of the lanes that are not 0.0 (NaN counts as not zero).
inline int nonzero_mask(f4 v) {
    return 15 & ~_mm_movemask_ps(_mm_cmpeq_ps(v, _mm_setzero_ps()));
}
// (a0 a1 a2 a3), (b..), (c..) = x0 y0 z0 x1 | y1 z1 x2 y2 | z2 x3 y3 z3 (12 packed floats) to
// SoA x = (x0 x1 x2 x3), y, z; and back.
inline void aos3_to_soa(f4 a, f4 b, f4 c, f4& x, f4& y, f4& z) {
    const f4 t0 = _mm_shuffle_ps(a, b, _MM_SHUFFLE(2, 2, 3, 0));   // x0 x1 x2 x2
    const f4 t1 = _mm_shuffle_ps(b, c, _MM_SHUFFLE(1, 1, 2, 2));   // x2 x2 x3 x3
    x = _mm_shuffle_ps(t0, t1, _MM_SHUFFLE(2, 0, 1, 0));           // x0 x1 x2 x3
    const f4 y01 = _mm_shuffle_ps(a, b, _MM_SHUFFLE(0, 0, 1, 1));  // y0 y0 y1 y1
    const f4 y23 = _mm_shuffle_ps(b, c, _MM_SHUFFLE(2, 2, 3, 3));  // y2 y2 y3 y3
    y = _mm_shuffle_ps(y01, y23, _MM_SHUFFLE(2, 0, 2, 0));         // y0 y1 y2 y3
    const f4 z01 = _mm_shuffle_ps(a, b, _MM_SHUFFLE(1, 1, 2, 2));  // z0 z0 z1 z1
    const f4 z23 = _mm_shuffle_ps(c, c, _MM_SHUFFLE(3, 3, 0, 0));  // z2 z2 z3 z3
    z = _mm_shuffle_ps(z01, z23, _MM_SHUFFLE(2, 0, 2, 0));         // z0 z1 z2 z3
}
// Four (x, y, z, any) vectors to 12 packed floats x0 y0 z0 x1 | y1 z1 x2 y2 | z2 x3 y3 z3.
inline void pack_xyz(f4 p0, f4 p1, f4 p2, f4 p3, f4& a, f4& b, f4& c) {
    const f4 t = _mm_shuffle_ps(p1, p0, _MM_SHUFFLE(2, 2, 0, 0));  // x1 x1 z0 z0
    a = _mm_shuffle_ps(p0, t, _MM_SHUFFLE(0, 2, 1, 0));            // x0 y0 z0 x1
    b = _mm_shuffle_ps(p1, p2, _MM_SHUFFLE(1, 0, 2, 1));           // y1 z1 x2 y2
    const f4 u = _mm_shuffle_ps(p2, p3, _MM_SHUFFLE(0, 0, 2, 2));  // z2 z2 x3 x3
    c = _mm_shuffle_ps(u, p3, _MM_SHUFFLE(2, 1, 2, 0));            // z2 x3 y3 z3
}
inline void soa_to_aos3(f4 x, f4 y, f4 z, f4& a, f4& b, f4& c) {
    const f4 xy01 = _mm_unpacklo_ps(x, y);                             // x0 y0 x1 y1
    const f4 xy23 = _mm_unpackhi_ps(x, y);                             // x2 y2 x3 y3
    const f4 z0z1 = _mm_shuffle_ps(z, xy01, _MM_SHUFFLE(2, 2, 0, 0));  // z0 z0 x1 x1
    a = _mm_shuffle_ps(xy01, z0z1, _MM_SHUFFLE(2, 0, 1, 0));           // x0 y0 z0 x1
    const f4 t = _mm_shuffle_ps(xy01, z, _MM_SHUFFLE(1, 1, 3, 3));     // y1 y1 z1 z1
    b = _mm_shuffle_ps(t, xy23, _MM_SHUFFLE(1, 0, 2, 0));              // y1 z1 x2 y2
    const f4 v = _mm_shuffle_ps(z, xy23, _MM_SHUFFLE(2, 2, 2, 2));     // z2 z2 x3 x3
    const f4 w = _mm_shuffle_ps(xy23, z, _MM_SHUFFLE(3, 3, 3, 3));     // y3 y3 z3 z3
    c = _mm_shuffle_ps(v, w, _MM_SHUFFLE(2, 0, 2, 0));                 // z2 x3 y3 z3
}

#elif defined(STIPPLE_ANIM_NEON)

constexpr const char* kPath = "neon";
using f4 = float32x4_t;
inline f4 load(const float* p) {
    return vld1q_f32(p);
}
inline void store(float* p, f4 v) {
    vst1q_f32(p, v);
}
inline f4 splat(float x) {
    return vdupq_n_f32(x);
}
inline f4 set(float x, float y, float z, float w) {
    const float v[4] = {x, y, z, w};
    return vld1q_f32(v);
}
inline f4 zero() {
    return vdupq_n_f32(0.0f);
}
inline f4 add(f4 a, f4 b) {
    return vaddq_f32(a, b);
}
inline f4 sub(f4 a, f4 b) {
    return vsubq_f32(a, b);
}
inline f4 mul(f4 a, f4 b) {
    return vmulq_f32(a, b);
}
inline f4 madd(f4 a, f4 b, f4 c) {
    return vmlaq_f32(c, a, b);
}
#if defined(__aarch64__)
inline f4 div(f4 a, f4 b) {
    return vdivq_f32(a, b);
}
inline f4 sqrt(f4 a) {
    return vsqrtq_f32(a);
}
#else
inline f4 div(f4 a, f4 b) {
    float x[4], y[4];
    vst1q_f32(x, a);
    vst1q_f32(y, b);
    for (int i = 0; i < 4; ++i) x[i] /= y[i];
    return vld1q_f32(x);
}
inline f4 sqrt(f4 a) {
    float x[4];
    vst1q_f32(x, a);
    for (float& v : x) v = std::sqrt(v);
    return vld1q_f32(x);
}
#endif
inline f4 max(f4 a, f4 b) {
    return vmaxq_f32(a, b);
}
inline f4 flip_sign(f4 v, f4 s) {
    const uint32x4_t sign = vandq_u32(vreinterpretq_u32_f32(s), vdupq_n_u32(0x80000000u));
    return vreinterpretq_f32_u32(veorq_u32(vreinterpretq_u32_f32(v), sign));
}
template <int i>
inline f4 lane(f4 v) {
    return vdupq_n_f32(vgetq_lane_f32(v, i));
}
inline float first(f4 v) {
    return vgetq_lane_f32(v, 0);
}
inline f4 load3(const float* p) {
    return vsetq_lane_f32(p[2], vcombine_f32(vld1_f32(p), vdup_n_f32(0)), 2);
}
inline void store3(float* p, f4 v) {
    vst1_f32(p, vget_low_f32(v));
    p[2] = vgetq_lane_f32(v, 2);
}
inline void transpose(f4& a, f4& b, f4& c, f4& d) {
    const float32x4x2_t ab = vtrnq_f32(a, b);
    const float32x4x2_t cd = vtrnq_f32(c, d);
    a = vcombine_f32(vget_low_f32(ab.val[0]), vget_low_f32(cd.val[0]));
    b = vcombine_f32(vget_low_f32(ab.val[1]), vget_low_f32(cd.val[1]));
    c = vcombine_f32(vget_high_f32(ab.val[0]), vget_high_f32(cd.val[0]));
    d = vcombine_f32(vget_high_f32(ab.val[1]), vget_high_f32(cd.val[1]));
}
inline int nonzero_mask(f4 v) {
    const uint32x4_t z = vceqq_f32(v, vdupq_n_f32(0.0f));
    return (vgetq_lane_u32(z, 0) ? 0 : 1) | (vgetq_lane_u32(z, 1) ? 0 : 2) |
           (vgetq_lane_u32(z, 2) ? 0 : 4) | (vgetq_lane_u32(z, 3) ? 0 : 8);
}
inline void aos3_to_soa(f4 a, f4 b, f4 c, f4& x, f4& y, f4& z) {
    float in[12];
    vst1q_f32(in, a);
    vst1q_f32(in + 4, b);
    vst1q_f32(in + 8, c);
    const float32x4x3_t v = vld3q_f32(in);
    x = v.val[0];
    y = v.val[1];
    z = v.val[2];
}
inline void soa_to_aos3(f4 x, f4 y, f4 z, f4& a, f4& b, f4& c) {
    float out[12];
    float32x4x3_t v;
    v.val[0] = x;
    v.val[1] = y;
    v.val[2] = z;
    vst3q_f32(out, v);
    a = vld1q_f32(out);
    b = vld1q_f32(out + 4);
    c = vld1q_f32(out + 8);
}

#else

// Portable fallback: the same kernels, one lane at a time (compilers often vectorise it).
constexpr const char* kPath = "scalar";
struct f4 {
    float v[4];
};
inline f4 load(const float* p) {
    return f4{{p[0], p[1], p[2], p[3]}};
}
inline void store(float* p, f4 a) {
    std::memcpy(p, a.v, sizeof(a.v));
}
inline f4 splat(float x) {
    return f4{{x, x, x, x}};
}
inline f4 set(float x, float y, float z, float w) {
    return f4{{x, y, z, w}};
}
inline f4 zero() {
    return splat(0.0f);
}
#define STIPPLE_F4_OP(name, expr)                  \
    inline f4 name(f4 a, f4 b) {                   \
        f4 r;                                      \
        for (int i = 0; i < 4; ++i) r.v[i] = expr; \
        return r;                                  \
    }
STIPPLE_F4_OP(add, a.v[i] + b.v[i])
STIPPLE_F4_OP(sub, a.v[i] - b.v[i])
STIPPLE_F4_OP(mul, a.v[i] * b.v[i])
STIPPLE_F4_OP(div, a.v[i] / b.v[i])
STIPPLE_F4_OP(max, a.v[i] > b.v[i] ? a.v[i] : b.v[i])
STIPPLE_F4_OP(flip_sign,
              b.v[i] < 0.0f ? -a.v[i] : a.v[i])  // (std::signbit here trips a GCC 12 ICE)
#undef STIPPLE_F4_OP
inline f4 madd(f4 a, f4 b, f4 c) {
    return add(mul(a, b), c);
}
inline f4 sqrt(f4 a) {
    return f4{{std::sqrt(a.v[0]), std::sqrt(a.v[1]), std::sqrt(a.v[2]), std::sqrt(a.v[3])}};
}
template <int i>
inline f4 lane(f4 v) {
    return splat(v.v[i]);
}
inline float first(f4 v) {
    return v.v[0];
}
inline f4 load3(const float* p) {
    return f4{{p[0], p[1], p[2], 0.0f}};
}
inline void store3(float* p, f4 v) {
    std::memcpy(p, v.v, 3 * sizeof(float));
}
inline void transpose(f4& a, f4& b, f4& c, f4& d) {
    const f4 r[4] = {a, b, c, d};
    a = f4{{r[0].v[0], r[1].v[0], r[2].v[0], r[3].v[0]}};
    b = f4{{r[0].v[1], r[1].v[1], r[2].v[1], r[3].v[1]}};
    c = f4{{r[0].v[2], r[1].v[2], r[2].v[2], r[3].v[2]}};
    d = f4{{r[0].v[3], r[1].v[3], r[2].v[3], r[3].v[3]}};
}
inline int nonzero_mask(f4 v) {
    return (v.v[0] != 0.0f ? 1 : 0) | (v.v[1] != 0.0f ? 2 : 0) | (v.v[2] != 0.0f ? 4 : 0) |
           (v.v[3] != 0.0f ? 8 : 0);
}
inline void aos3_to_soa(f4 a, f4 b, f4 c, f4& x, f4& y, f4& z) {
    float in[12];
    store(in, a);
    store(in + 4, b);
    store(in + 8, c);
    x = f4{{in[0], in[3], in[6], in[9]}};
    y = f4{{in[1], in[4], in[7], in[10]}};
    z = f4{{in[2], in[5], in[8], in[11]}};
}
inline void soa_to_aos3(f4 x, f4 y, f4 z, f4& a, f4& b, f4& c) {
    a = f4{{x.v[0], y.v[0], z.v[0], x.v[1]}};
    b = f4{{y.v[1], z.v[1], x.v[2], y.v[2]}};
    c = f4{{z.v[2], x.v[3], y.v[3], z.v[3]}};
}

#endif

#if !defined(STIPPLE_ANIM_SSE2)
// Portable (NEON and scalar): four (x, y, z, any) vectors to 12 packed floats x0 y0 z0 x1 | y1 z1
// x2 y2 | z2 x3 y3 z3.
inline void pack_xyz(f4 p0, f4 p1, f4 p2, f4 p3, f4& a, f4& b, f4& c) {
    float v[16];
    store(v, p0);
    store(v + 4, p1);
    store(v + 8, p2);
    store(v + 12, p3);
    const float out[12] = {v[0], v[1], v[2],  v[4],  v[5],  v[6],
                           v[8], v[9], v[10], v[12], v[13], v[14]};
    a = load(out);
    b = load(out + 4);
    c = load(out + 8);
}
#endif

}  // namespace stipple::anim::simd
