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

// DQS of 4 vertices, one per lane.
template <int N, bool kNormals, bool kStretch>
void dqs_block(const Mesh& m, size_t v) {
    const uint16_t* jv = m.joints + 4 * v;
    f4 w[4] = {simd::load(m.weights + 4 * v), simd::load(m.weights + 4 * v + 4),
               simd::load(m.weights + 4 * v + 8), simd::load(m.weights + 4 * v + 12)};
    simd::transpose(w[0], w[1], w[2], w[3]);  // w[k]: influence k of the 4 vertices

    const float* p = m.in_p + 3 * v;
    f4 px, py, pz;
    f4 nx = simd::zero(), ny = simd::zero(), nz = simd::zero();
    simd::aos3_to_soa(simd::load(p), simd::load(p + 4), simd::load(p + 8), px, py, pz);
    if (kNormals) {
        const float* n = m.in_n + 3 * v;
        simd::aos3_to_soa(simd::load(n), simd::load(n + 4), simd::load(n + 8), nx, ny, nz);
    }
    if (kStretch) {
        // Phase 1: apply sum_k w_k S_k per vertex (AoS columns, as in LBS), then back to
        // lanes.
        f4 sp[4], sn[4];
        float pv[12], nv[12];
        f4 a, b, c;
        simd::soa_to_aos3(px, py, pz, a, b, c);
        simd::store(pv, a);
        simd::store(pv + 4, b);
        simd::store(pv + 8, c);
        simd::soa_to_aos3(nx, ny, nz, a, b, c);
        simd::store(nv, a);
        simd::store(nv + 4, b);
        simd::store(nv + 8, c);
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
            sp[i] = simd::madd(s0, simd::splat(pv[3 * i]),
                               simd::madd(s1, simd::splat(pv[3 * i + 1]),
                                          simd::mul(s2, simd::splat(pv[3 * i + 2]))));
            sn[i] = simd::madd(s0, simd::splat(nv[3 * i]),
                               simd::madd(s1, simd::splat(nv[3 * i + 1]),
                                          simd::mul(s2, simd::splat(nv[3 * i + 2]))));
        }
        f4 junk;
        px = sp[0], py = sp[1], pz = sp[2], junk = sp[3];
        simd::transpose(px, py, pz, junk);
        nx = sn[0], ny = sn[1], nz = sn[2], junk = sn[3];
        simd::transpose(nx, ny, nz, junk);
    }

    // Phase 2: DLB over the lanes.
    f4 qx = simd::zero(), qy = simd::zero(), qz = simd::zero(), qw = simd::zero();
    f4 dx = simd::zero(), dy = simd::zero(), dz = simd::zero(), dw = simd::zero();
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
        qx = simd::madd(wk, rx, qx);
        qy = simd::madd(wk, ry, qy);
        qz = simd::madd(wk, rz, qz);
        qw = simd::madd(wk, rw, qw);
        dx = simd::madd(wk, ex, dx);
        dy = simd::madd(wk, ey, dy);
        dz = simd::madd(wk, ez, dz);
        dw = simd::madd(wk, ew, dw);
    }
    const f4 len2 = simd::madd(qx, qx, simd::madd(qy, qy, simd::madd(qz, qz, simd::mul(qw, qw))));
    const f4 inv = simd::div(simd::splat(1.0f), simd::sqrt(simd::max(len2, simd::splat(1e-30f))));
    qx = simd::mul(qx, inv), qy = simd::mul(qy, inv), qz = simd::mul(qz, inv),
    qw = simd::mul(qw, inv);
    dx = simd::mul(dx, inv), dy = simd::mul(dy, inv), dz = simd::mul(dz, inv),
    dw = simd::mul(dw, inv);

    const f4 two = simd::splat(2.0f);
    // Translation: 2 (qw dv - dw qv + qv x dv).
    const f4 tx = simd::mul(
        two, simd::sub(simd::madd(qw, dx, simd::sub(simd::mul(qy, dz), simd::mul(qz, dy))),
                       simd::mul(dw, qx)));
    const f4 ty = simd::mul(
        two, simd::sub(simd::madd(qw, dy, simd::sub(simd::mul(qz, dx), simd::mul(qx, dz))),
                       simd::mul(dw, qy)));
    const f4 tz = simd::mul(
        two, simd::sub(simd::madd(qw, dz, simd::sub(simd::mul(qx, dy), simd::mul(qy, dx))),
                       simd::mul(dw, qz)));
    // Rotation: v + 2 qv x (qv x v + qw v).
    auto rotate4 = [&](f4 vx, f4 vy, f4 vz, f4& ox, f4& oy, f4& oz) {
        const f4 cx = simd::madd(qw, vx, simd::sub(simd::mul(qy, vz), simd::mul(qz, vy)));
        const f4 cy = simd::madd(qw, vy, simd::sub(simd::mul(qz, vx), simd::mul(qx, vz)));
        const f4 cz = simd::madd(qw, vz, simd::sub(simd::mul(qx, vy), simd::mul(qy, vx)));
        ox = simd::madd(two, simd::sub(simd::mul(qy, cz), simd::mul(qz, cy)), vx);
        oy = simd::madd(two, simd::sub(simd::mul(qz, cx), simd::mul(qx, cz)), vy);
        oz = simd::madd(two, simd::sub(simd::mul(qx, cy), simd::mul(qy, cx)), vz);
    };
    f4 ox, oy, oz;
    rotate4(px, py, pz, ox, oy, oz);
    f4 a, b, c;
    simd::soa_to_aos3(simd::add(ox, tx), simd::add(oy, ty), simd::add(oz, tz), a, b, c);
    float* op = m.out_p + 3 * v;
    simd::store(op, a);
    simd::store(op + 4, b);
    simd::store(op + 8, c);
    if (kNormals) {
        rotate4(nx, ny, nz, ox, oy, oz);
        const f4 nl2 = simd::madd(ox, ox, simd::madd(oy, oy, simd::mul(oz, oz)));
        const f4 ninv =
            simd::div(simd::splat(1.0f), simd::sqrt(simd::max(nl2, simd::splat(1e-30f))));
        simd::soa_to_aos3(simd::mul(ox, ninv), simd::mul(oy, ninv), simd::mul(oz, ninv), a, b, c);
        float* on = m.out_n + 3 * v;
        simd::store(on, a);
        simd::store(on + 4, b);
        simd::store(on + 8, c);
    }
}

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

void skin_lbs(const SkinJob& job) {
    const uint32_t n = job.vertex_count;
    if (n == 0) return;
    if (job.joint_count == 0) {
        // No joint to fall back on: the mesh stays in its bind pose.
        if (job.out_positions != job.in_positions)
            std::memcpy(job.out_positions, job.in_positions, size_t{n} * 3 * sizeof(float));
        if (job.out_normals != job.in_normals)
            std::memcpy(job.out_normals, job.in_normals, size_t{n} * 3 * sizeof(float));
        return;
    }
    SkinningJob s;
    s.method = Skinning::lbs;
    s.vertex_count = n;
    s.joint_matrices = Span<const glm::mat4>(job.skin, job.joint_count);
    s.joints = Span<const uint16_t>(job.joints, size_t{n} * 4);
    s.weights = Span<const float>(job.weights, size_t{n} * 4);
    s.in_positions = Span<const float>(job.in_positions, size_t{n} * 3);
    s.in_normals = Span<const float>(job.in_normals, size_t{n} * 3);
    s.out_positions = Span<float>(job.out_positions, size_t{n} * 3);
    s.out_normals = Span<float>(job.out_normals, size_t{n} * 3);
    s.run();
}

}  // namespace stipple::anim
