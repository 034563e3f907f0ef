// Skinning of positions and normals by 4 influences per vertex:
//   LBS, glTF 2.0 §3.7.3 "Skins" / "Skinned Mesh Attributes": skin matrix = sum over the
//       influences of weight * joint matrix.
//   DQS, Kavan, Collins, Zara, O'Sullivan 2007, "Skinning with dual quaternions" (DLB:
//       dual quaternion linear blending, signs aligned to the first influence, normalised),
//       with the non-rigid remainder S of each joint blended linearly and applied first.
//
// Two implementations of each, which tests keep in agreement:
//   - scalar: one vertex at a time, plain C++, the reference;
//   - SIMD (anim/simd.h: SSE2, NEON, or the portable 4-lane fallback): blocks of 4
//     vertices. LBS blends the 4 joint-matrix columns per vertex in vector registers; DQS
//     works structure-of-arrays on the 4 vertices (one lane per vertex). Each block runs the
//     kernel for the largest influence count in the block (weights that are exactly 0 at
//     the end are skipped), so vertices sorted by influence count (the glTF importer does
//     this per primitive) pay only for the influences they have (ozz splits its meshes the
//     same way; PLATFORM-NOTES measured 1.4-1.7x from it).
#include <algorithm>
#include <cmath>
#include <cstring>

#include "anim/anim.h"
#include "anim/simd.h"

namespace stipple::anim {
namespace {

using simd::f4;

struct Mesh {
    size_t vertex_count;
    const float* palette;  // LBS: 16 floats per joint, column-major
    const DqsJoint* dq;    // DQS
    size_t joint_count;    // palette entries
    const uint16_t* joints;
    const float* weights;
    const float* in_p;
    const float* in_n;  // nullptr: no normals
    float* out_p;
    float* out_n;
};

inline size_t joint_index(uint16_t j, size_t count) {
    // Out-of-range joint indices read joint 0: a bad asset can never read out of bounds.
    return j < count ? j : 0u;
}

// ---------------------------------------------------------------------------------------
// Scalar reference

void lbs_vertex(const Mesh& m, size_t v) {
    const uint16_t* jv = m.joints + 4 * v;
    const float* wv = m.weights + 4 * v;
    float blended[16] = {};
    for (int k = 0; k < 4; ++k) {
        const float* mk = m.palette + 16 * joint_index(jv[k], m.joint_count);
        for (int e = 0; e < 16; ++e) blended[e] += wv[k] * mk[e];
    }
    const float* p = m.in_p + 3 * v;
    float pos[3];
    for (int r = 0; r < 3; ++r) {
        pos[r] =
            blended[r] * p[0] + blended[4 + r] * p[1] + blended[8 + r] * p[2] + blended[12 + r];
    }
    std::memcpy(m.out_p + 3 * v, pos, sizeof(pos));
    if (m.in_n == nullptr) return;
    const float* n = m.in_n + 3 * v;
    float nor[3];
    for (int r = 0; r < 3; ++r) {
        nor[r] = blended[r] * n[0] + blended[4 + r] * n[1] + blended[8 + r] * n[2];
    }
    // Renormalise. Clamping the squared length (instead of branching) keeps a degenerate
    // zero normal at zero rather than NaN.
    const float len2 = nor[0] * nor[0] + nor[1] * nor[1] + nor[2] * nor[2];
    const float inv_len = 1.0f / std::sqrt(std::max(len2, 1e-30f));
    for (int r = 0; r < 3; ++r) m.out_n[3 * v + r] = nor[r] * inv_len;
}

// Rotates v by the unit quaternion (qv, qw): v + 2 qv x (qv x v + qw v).
void rotate(const float* q, const float* v, float* out) {
    const float tx = q[1] * v[2] - q[2] * v[1] + q[3] * v[0];
    const float ty = q[2] * v[0] - q[0] * v[2] + q[3] * v[1];
    const float tz = q[0] * v[1] - q[1] * v[0] + q[3] * v[2];
    out[0] = v[0] + 2.0f * (q[1] * tz - q[2] * ty);
    out[1] = v[1] + 2.0f * (q[2] * tx - q[0] * tz);
    out[2] = v[2] + 2.0f * (q[0] * ty - q[1] * tx);
}

void dqs_vertex(const Mesh& m, size_t v, bool rigid) {
    const uint16_t* jv = m.joints + 4 * v;
    const float* wv = m.weights + 4 * v;
    const DqsJoint* js[4];
    for (int k = 0; k < 4; ++k) js[k] = m.dq + joint_index(jv[k], m.joint_count);
    float p[3];
    float n[3] = {0, 0, 0};
    std::memcpy(p, m.in_p + 3 * v, sizeof(p));
    if (m.in_n != nullptr) std::memcpy(n, m.in_n + 3 * v, sizeof(n));
    if (!rigid) {
        // Phase 1: the linearly blended non-rigid parts S.
        float s[12] = {};
        for (int k = 0; k < 4; ++k) {
            for (int e = 0; e < 12; ++e) s[e] += wv[k] * js[k]->stretch[e];
        }
        float sp[3];
        float sn[3];
        for (int r = 0; r < 3; ++r) {
            sp[r] = s[r] * p[0] + s[4 + r] * p[1] + s[8 + r] * p[2];
            sn[r] = s[r] * n[0] + s[4 + r] * n[1] + s[8 + r] * n[2];
        }
        std::memcpy(p, sp, sizeof(p));
        std::memcpy(n, sn, sizeof(n));
    }
    // Phase 2: DLB. Quaternions q and -q are the same rotation; each influence joins the
    // first one's hemisphere so the blend takes the short way (Kavan et al. 2007 §4).
    float bq[4] = {};
    float bd[4] = {};
    const float* pivot = js[0]->real;
    for (int k = 0; k < 4; ++k) {
        const float* q = js[k]->real;
        const float dot = pivot[0] * q[0] + pivot[1] * q[1] + pivot[2] * q[2] + pivot[3] * q[3];
        const float w = std::signbit(dot) ? -wv[k] : wv[k];
        for (int c = 0; c < 4; ++c) {
            bq[c] += w * q[c];
            bd[c] += w * js[k]->dual[c];
        }
    }
    const float len2 = bq[0] * bq[0] + bq[1] * bq[1] + bq[2] * bq[2] + bq[3] * bq[3];
    const float inv = 1.0f / std::sqrt(std::max(len2, 1e-30f));
    for (int c = 0; c < 4; ++c) {
        bq[c] *= inv;
        bd[c] *= inv;
    }
    // Translation 2 * vector part of dual * conj(real):
    //   2 (qw dv - dw qv + qv x dv).
    const float t[3] = {
        2.0f * (bq[3] * bd[0] - bd[3] * bq[0] + bq[1] * bd[2] - bq[2] * bd[1]),
        2.0f * (bq[3] * bd[1] - bd[3] * bq[1] + bq[2] * bd[0] - bq[0] * bd[2]),
        2.0f * (bq[3] * bd[2] - bd[3] * bq[2] + bq[0] * bd[1] - bq[1] * bd[0]),
    };
    float rp[3];
    rotate(bq, p, rp);
    for (int c = 0; c < 3; ++c) m.out_p[3 * v + c] = rp[c] + t[c];
    if (m.in_n == nullptr) return;
    float rn[3];
    rotate(bq, n, rn);
    const float nl2 = rn[0] * rn[0] + rn[1] * rn[1] + rn[2] * rn[2];
    const float inv_n = 1.0f / std::sqrt(std::max(nl2, 1e-30f));
    for (int c = 0; c < 3; ++c) m.out_n[3 * v + c] = rn[c] * inv_n;
}

// ---------------------------------------------------------------------------------------
// SIMD: blocks of 4 vertices

// Number of leading influences that matter in the 4 vertices at v: 1 + the index of the
// last weight that is non-zero in any of them (0-weight influences contribute nothing).
inline int block_influences(const float* weights, size_t v) {
    const int mask = simd::nonzero_mask(simd::load(weights + 4 * v)) |
                     simd::nonzero_mask(simd::load(weights + 4 * v + 4)) |
                     simd::nonzero_mask(simd::load(weights + 4 * v + 8)) |
                     simd::nonzero_mask(simd::load(weights + 4 * v + 12));
    return mask >= 8 ? 4 : mask >= 4 ? 3 : mask >= 2 ? 2 : 1;
}

// Adds influence K (weight lane K times joint matrix K) to the blended matrix columns.
template <int K>
inline void add_influence(const Mesh& m, const uint16_t* jv, f4 w, f4& c0, f4& c1, f4& c2, f4& c3) {
    const float* mk = m.palette + 16 * joint_index(jv[K], m.joint_count);
    const f4 wk = simd::lane<K>(w);
    c0 = simd::madd(simd::load(mk), wk, c0);
    c1 = simd::madd(simd::load(mk + 4), wk, c1);
    c2 = simd::madd(simd::load(mk + 8), wk, c2);
    c3 = simd::madd(simd::load(mk + 12), wk, c3);
}

// LBS of one vertex: the 4 columns of sum_k w_k M_k, applied to p (and n).
template <int N, bool kNormals>
inline void lbs_one(const Mesh& m, size_t v, f4 px, f4 py, f4 pz, f4 nx, f4 ny, f4 nz, f4* pos,
                    f4* nor) {
    const uint16_t* jv = m.joints + 4 * v;
    const f4 w = simd::load(m.weights + 4 * v);
    const float* m0 = m.palette + 16 * joint_index(jv[0], m.joint_count);
    const f4 w0 = simd::lane<0>(w);
    f4 c0 = simd::mul(simd::load(m0), w0);
    f4 c1 = simd::mul(simd::load(m0 + 4), w0);
    f4 c2 = simd::mul(simd::load(m0 + 8), w0);
    f4 c3 = simd::mul(simd::load(m0 + 12), w0);
    if (N > 1) add_influence<1>(m, jv, w, c0, c1, c2, c3);
    if (N > 2) add_influence<2>(m, jv, w, c0, c1, c2, c3);
    if (N > 3) add_influence<3>(m, jv, w, c0, c1, c2, c3);
    *pos = simd::madd(c0, px, simd::madd(c1, py, simd::madd(c2, pz, c3)));
    if (kNormals) *nor = simd::madd(c0, nx, simd::madd(c1, ny, simd::mul(c2, nz)));
}

template <int N, bool kNormals>
void lbs_block(const Mesh& m, size_t v) {
    // All loads of the block happen before its stores, so in-place skinning is safe.
    const float* p = m.in_p + 3 * v;
    const f4 pa = simd::load(p);
    const f4 pb = simd::load(p + 4);
    const f4 pc = simd::load(p + 8);
    f4 na = simd::zero(), nb = simd::zero(), nc = simd::zero();
    if (kNormals) {
        const float* n = m.in_n + 3 * v;
        na = simd::load(n);
        nb = simd::load(n + 4);
        nc = simd::load(n + 8);
    }
    f4 pos[4];
    f4 nor[4] = {simd::zero(), simd::zero(), simd::zero(), simd::zero()};
    // Packed x0 y0 z0 x1 | y1 z1 x2 y2 | z2 x3 y3 z3: each coordinate splat from its lane.
    using simd::lane;
    lbs_one<N, kNormals>(m, v + 0, lane<0>(pa), lane<1>(pa), lane<2>(pa), lane<0>(na), lane<1>(na),
                         lane<2>(na), &pos[0], &nor[0]);
    lbs_one<N, kNormals>(m, v + 1, lane<3>(pa), lane<0>(pb), lane<1>(pb), lane<3>(na), lane<0>(nb),
                         lane<1>(nb), &pos[1], &nor[1]);
    lbs_one<N, kNormals>(m, v + 2, lane<2>(pb), lane<3>(pb), lane<0>(pc), lane<2>(nb), lane<3>(nb),
                         lane<0>(nc), &pos[2], &nor[2]);
    lbs_one<N, kNormals>(m, v + 3, lane<1>(pc), lane<2>(pc), lane<3>(pc), lane<1>(nc), lane<2>(nc),
                         lane<3>(nc), &pos[3], &nor[3]);
    f4 a, b, c;
    simd::pack_xyz(pos[0], pos[1], pos[2], pos[3], a, b, c);
    float* op = m.out_p + 3 * v;
    simd::store(op, a);
    simd::store(op + 4, b);
    simd::store(op + 8, c);
    if (kNormals) {
        // Renormalise the 4 normals at once: transpose to x, y, z lanes.
        f4 x = nor[0], y = nor[1], z = nor[2], w = nor[3];
        simd::transpose(x, y, z, w);
        const f4 len2 = simd::madd(x, x, simd::madd(y, y, simd::mul(z, z)));
        const f4 inv =
            simd::div(simd::splat(1.0f), simd::sqrt(simd::max(len2, simd::splat(1e-30f))));
        simd::soa_to_aos3(simd::mul(x, inv), simd::mul(y, inv), simd::mul(z, inv), a, b, c);
        float* on = m.out_n + 3 * v;
        simd::store(on, a);
        simd::store(on + 4, b);
        simd::store(on + 8, c);
    }
}

// DQS of 4 vertices, one per lane, in steps: the block's inputs to lanes, the stretch phase
// (two-phase skinning), the dual-quaternion blend, then rotation + translation and the stores.

// The steps are always inlined: called once per block, they must compile to the same code
// as one function (a call would spill the lanes to memory).
#define STIPPLE_STEP inline __attribute__((always_inline))

// x, y, z of the 4 vertices of a block, one vertex per lane.
struct Lanes3 {
    f4 x, y, z;
};

// A blended dual quaternion per lane: real part q, dual part d.
struct DualQuat4 {
    f4 qx, qy, qz, qw, dx, dy, dz, dw;
};

// Loads 4 packed xyz triples (12 floats) into lanes.
STIPPLE_STEP Lanes3 load_lanes3(const float* p) {
    Lanes3 v;
    simd::aos3_to_soa(simd::load(p), simd::load(p + 4), simd::load(p + 8), v.x, v.y, v.z);
    return v;
}

// Stores lanes as 4 packed xyz triples.
STIPPLE_STEP void store_lanes3(float* out, f4 x, f4 y, f4 z) {
    f4 a, b, c;
    simd::soa_to_aos3(x, y, z, a, b, c);
    simd::store(out, a);
    simd::store(out + 4, b);
    simd::store(out + 8, c);
}

STIPPLE_STEP f4 inverse_length(f4 len2) {
    return simd::div(simd::splat(1.0f), simd::sqrt(simd::max(len2, simd::splat(1e-30f))));
}

// Phase 1: applies sum_k w_k S_k to each vertex's position and normal (AoS columns, as in
// LBS), then back to lanes.
template <int N>
STIPPLE_STEP void apply_stretch(const Mesh& m, size_t v, Lanes3* p, Lanes3* n) {
    const uint16_t* jv = m.joints + 4 * v;
    f4 sp[4], sn[4];
    float pv[12], nv[12];
    store_lanes3(pv, p->x, p->y, p->z);
    store_lanes3(nv, n->x, n->y, n->z);
    for (int i = 0; i < 4; ++i) {
        const float* wi = m.weights + 4 * (v + i);
        f4 s0 = simd::zero(), s1 = simd::zero(), s2 = simd::zero();
        for (int k = 0; k < N; ++k) {
            const float* s = m.dq[joint_index(jv[4 * i + k], m.joint_count)].stretch;
            const f4 wk = simd::splat(wi[k]);
            s0 = simd::madd(simd::load(s), wk, s0);
            s1 = simd::madd(simd::load(s + 4), wk, s1);
            s2 = simd::madd(simd::load(s + 8), wk, s2);
        }
        sp[i] = simd::madd(
            s0, simd::splat(pv[3 * i]),
            simd::madd(s1, simd::splat(pv[3 * i + 1]), simd::mul(s2, simd::splat(pv[3 * i + 2]))));
        sn[i] = simd::madd(
            s0, simd::splat(nv[3 * i]),
            simd::madd(s1, simd::splat(nv[3 * i + 1]), simd::mul(s2, simd::splat(nv[3 * i + 2]))));
    }
    f4 junk;
    p->x = sp[0], p->y = sp[1], p->z = sp[2], junk = sp[3];
    simd::transpose(p->x, p->y, p->z, junk);
    n->x = sn[0], n->y = sn[1], n->z = sn[2], junk = sn[3];
    simd::transpose(n->x, n->y, n->z, junk);
}

// Phase 2: DLB over the lanes, normalised. w[k]: influence k's weight of the 4 vertices.
template <int N>
STIPPLE_STEP DualQuat4 blend_dual_quaternions(const Mesh& m, size_t v, const f4* w) {
    const uint16_t* jv = m.joints + 4 * v;
    DualQuat4 b = {simd::zero(), simd::zero(), simd::zero(), simd::zero(),
                   simd::zero(), simd::zero(), simd::zero(), simd::zero()};
    f4 ux = simd::zero(), uy = simd::zero(), uz = simd::zero(), uw = simd::zero();  // pivot
    for (int k = 0; k < N; ++k) {
        const DqsJoint* j0 = m.dq + joint_index(jv[k], m.joint_count);
        const DqsJoint* j1 = m.dq + joint_index(jv[4 + k], m.joint_count);
        const DqsJoint* j2 = m.dq + joint_index(jv[8 + k], m.joint_count);
        const DqsJoint* j3 = m.dq + joint_index(jv[12 + k], m.joint_count);
        f4 rx = simd::load(j0->real), ry = simd::load(j1->real), rz = simd::load(j2->real),
           rw = simd::load(j3->real);
        simd::transpose(rx, ry, rz, rw);
        f4 ex = simd::load(j0->dual), ey = simd::load(j1->dual), ez = simd::load(j2->dual),
           ew = simd::load(j3->dual);
        simd::transpose(ex, ey, ez, ew);
        f4 wk = w[k];
        if (k == 0) {
            ux = rx, uy = ry, uz = rz, uw = rw;
        } else {
            // Join the first influence's hemisphere (Kavan et al. 2007 §4): flip the weight's
            // sign where dot(pivot, q) < 0.
            const f4 dot =
                simd::madd(ux, rx, simd::madd(uy, ry, simd::madd(uz, rz, simd::mul(uw, rw))));
            wk = simd::flip_sign(wk, dot);
        }
        b.qx = simd::madd(wk, rx, b.qx);
        b.qy = simd::madd(wk, ry, b.qy);
        b.qz = simd::madd(wk, rz, b.qz);
        b.qw = simd::madd(wk, rw, b.qw);
        b.dx = simd::madd(wk, ex, b.dx);
        b.dy = simd::madd(wk, ey, b.dy);
        b.dz = simd::madd(wk, ez, b.dz);
        b.dw = simd::madd(wk, ew, b.dw);
    }
    const f4 inv = inverse_length(simd::madd(
        b.qx, b.qx, simd::madd(b.qy, b.qy, simd::madd(b.qz, b.qz, simd::mul(b.qw, b.qw)))));
    b.qx = simd::mul(b.qx, inv), b.qy = simd::mul(b.qy, inv), b.qz = simd::mul(b.qz, inv),
    b.qw = simd::mul(b.qw, inv);
    b.dx = simd::mul(b.dx, inv), b.dy = simd::mul(b.dy, inv), b.dz = simd::mul(b.dz, inv),
    b.dw = simd::mul(b.dw, inv);
    return b;
}

// The translation of a unit dual quaternion: 2 (qw dv - dw qv + qv x dv).
STIPPLE_STEP Lanes3 dq_translation(const DualQuat4& b) {
    const f4 two = simd::splat(2.0f);
    return {simd::mul(two,
                      simd::sub(simd::madd(b.qw, b.dx,
                                           simd::sub(simd::mul(b.qy, b.dz), simd::mul(b.qz, b.dy))),
                                simd::mul(b.dw, b.qx))),
            simd::mul(two,
                      simd::sub(simd::madd(b.qw, b.dy,
                                           simd::sub(simd::mul(b.qz, b.dx), simd::mul(b.qx, b.dz))),
                                simd::mul(b.dw, b.qy))),
            simd::mul(two,
                      simd::sub(simd::madd(b.qw, b.dz,
                                           simd::sub(simd::mul(b.qx, b.dy), simd::mul(b.qy, b.dx))),
                                simd::mul(b.dw, b.qz)))};
}

// Rotation by the real part: v + 2 qv x (qv x v + qw v).
STIPPLE_STEP Lanes3 dq_rotate(const DualQuat4& b, const Lanes3& v) {
    const f4 two = simd::splat(2.0f);
    const f4 cx = simd::madd(b.qw, v.x, simd::sub(simd::mul(b.qy, v.z), simd::mul(b.qz, v.y)));
    const f4 cy = simd::madd(b.qw, v.y, simd::sub(simd::mul(b.qz, v.x), simd::mul(b.qx, v.z)));
    const f4 cz = simd::madd(b.qw, v.z, simd::sub(simd::mul(b.qx, v.y), simd::mul(b.qy, v.x)));
    return {simd::madd(two, simd::sub(simd::mul(b.qy, cz), simd::mul(b.qz, cy)), v.x),
            simd::madd(two, simd::sub(simd::mul(b.qz, cx), simd::mul(b.qx, cz)), v.y),
            simd::madd(two, simd::sub(simd::mul(b.qx, cy), simd::mul(b.qy, cx)), v.z)};
}

template <int N, bool kNormals, bool kStretch>
void dqs_block(const Mesh& m, size_t v) {
    f4 w[4] = {simd::load(m.weights + 4 * v), simd::load(m.weights + 4 * v + 4),
               simd::load(m.weights + 4 * v + 8), simd::load(m.weights + 4 * v + 12)};
    simd::transpose(w[0], w[1], w[2], w[3]);  // w[k]: influence k of the 4 vertices
    Lanes3 p = load_lanes3(m.in_p + 3 * v);
    Lanes3 n = {simd::zero(), simd::zero(), simd::zero()};
    if (kNormals) n = load_lanes3(m.in_n + 3 * v);
    if (kStretch) apply_stretch<N>(m, v, &p, &n);
    const DualQuat4 b = blend_dual_quaternions<N>(m, v, w);
    const Lanes3 t = dq_translation(b);
    const Lanes3 o = dq_rotate(b, p);
    store_lanes3(m.out_p + 3 * v, simd::add(o.x, t.x), simd::add(o.y, t.y), simd::add(o.z, t.z));
    if (kNormals) {
        const Lanes3 r = dq_rotate(b, n);
        const f4 inv =
            inverse_length(simd::madd(r.x, r.x, simd::madd(r.y, r.y, simd::mul(r.z, r.z))));
        store_lanes3(m.out_n + 3 * v, simd::mul(r.x, inv), simd::mul(r.y, inv),
                     simd::mul(r.z, inv));
    }
}

#undef STIPPLE_STEP

template <bool kNormals>
void lbs_simd(const Mesh& m) {
    const size_t blocks = m.vertex_count / 4 * 4;
    for (size_t v = 0; v < blocks; v += 4) {
        switch (block_influences(m.weights, v)) {
            case 1:
                lbs_block<1, kNormals>(m, v);
                break;
            case 2:
                lbs_block<2, kNormals>(m, v);
                break;
            case 3:
                lbs_block<3, kNormals>(m, v);
                break;
            default:
                lbs_block<4, kNormals>(m, v);
                break;
        }
    }
    for (size_t v = blocks; v < m.vertex_count; ++v) lbs_vertex(m, v);
}

template <bool kNormals, bool kStretch>
void dqs_simd(const Mesh& m) {
    const size_t blocks = m.vertex_count / 4 * 4;
    for (size_t v = 0; v < blocks; v += 4) {
        switch (block_influences(m.weights, v)) {
            case 1:
                dqs_block<1, kNormals, kStretch>(m, v);
                break;
            case 2:
                dqs_block<2, kNormals, kStretch>(m, v);
                break;
            case 3:
                dqs_block<3, kNormals, kStretch>(m, v);
                break;
            default:
                dqs_block<4, kNormals, kStretch>(m, v);
                break;
        }
    }
    for (size_t v = blocks; v < m.vertex_count; ++v) dqs_vertex(m, v, !kStretch);
}

// Exact aliasing (in place) is allowed; any other overlap is not.
bool overlap_ok(const float* in, const float* out, size_t n) {
    if (n == 0 || in == out) return true;
    return in + n <= out || out + n <= in;
}

Mesh make_mesh(const SkinningJob& job) {
    Mesh m;
    m.vertex_count = job.vertex_count;
    m.palette = job.joint_matrices.empty() ? nullptr : &job.joint_matrices.data[0][0][0];
    m.dq = job.dq_joints.data;
    m.joint_count = job.method == Skinning::dqs ? job.dq_joints.size : job.joint_matrices.size;
    m.joints = job.joints.data;
    m.weights = job.weights.data;
    m.in_p = job.in_positions.data;
    m.in_n = job.in_normals.empty() ? nullptr : job.in_normals.data;
    m.out_p = job.out_positions.data;
    m.out_n = job.in_normals.empty() ? nullptr : job.out_normals.data;
    return m;
}

}  // namespace

bool SkinningJob::validate() const {
    if (method != Skinning::lbs && method != Skinning::dqs) return false;
    if (vertex_count == 0) return true;
    const size_t n3 = size_t{vertex_count} * 3;
    const size_t n4 = size_t{vertex_count} * 4;
    if (method == Skinning::lbs && (joint_matrices.empty() || joint_matrices.data == nullptr))
        return false;
    if (method == Skinning::dqs && (dq_joints.empty() || dq_joints.data == nullptr)) return false;
    if (joints.size < n4 || joints.data == nullptr || weights.size < n4 || weights.data == nullptr)
        return false;
    if (in_positions.size < n3 || in_positions.data == nullptr || out_positions.size < n3 ||
        out_positions.data == nullptr)
        return false;
    if (in_normals.empty() != out_normals.empty()) return false;
    if (!in_normals.empty() && (in_normals.size < n3 || in_normals.data == nullptr ||
                                out_normals.size < n3 || out_normals.data == nullptr))
        return false;
    if (!overlap_ok(in_positions.data, out_positions.data, n3)) return false;
    if (!in_normals.empty() && !overlap_ok(in_normals.data, out_normals.data, n3)) return false;
    return true;
}

bool SkinningJob::run_scalar() const {
    if (!validate()) return false;
    const Mesh m = make_mesh(*this);
    if (method == Skinning::lbs) {
        for (size_t v = 0; v < m.vertex_count; ++v) lbs_vertex(m, v);
    } else {
        for (size_t v = 0; v < m.vertex_count; ++v) dqs_vertex(m, v, dq_rigid);
    }
    return true;
}

bool SkinningJob::run() const {
    if (!validate()) return false;
    const Mesh m = make_mesh(*this);
    const bool normals = m.in_n != nullptr;
    if (method == Skinning::lbs) {
        if (normals) {
            lbs_simd<true>(m);
        } else {
            lbs_simd<false>(m);
        }
    } else if (dq_rigid) {
        if (normals) {
            dqs_simd<true, false>(m);
        } else {
            dqs_simd<false, false>(m);
        }
    } else {
        if (normals) {
            dqs_simd<true, true>(m);
        } else {
            dqs_simd<false, true>(m);
        }
    }
    return true;
}

}  // namespace stipple::anim
