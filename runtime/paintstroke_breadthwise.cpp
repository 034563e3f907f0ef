#include "runtime/paintstroke_breadthwise.h"

#include <cmath>

namespace stipple {

float global_penetration(const glm::vec3& n_gl, float d_gl, const glm::vec3& light) {
    const float ln = glm::length(n_gl), ll = glm::length(light);
    if (!(ln > 0.0f) || !(ll > 0.0f)) return 0.0f;
    // GI'98 eq. 6: 2p = sqrt((alpha beta)^2 - alpha^2 + 1) - alpha beta,
    // alpha = 1 - d_gl, beta = N_gl . L.
    const float alpha = 1.0f - glm::clamp(d_gl, 0.0f, 1.0f);
    const float beta = glm::clamp(glm::dot(n_gl, light) / (ln * ll), -1.0f, 1.0f);
    const float ab = alpha * beta;
    const float two_p = std::sqrt(glm::max(ab * ab - alpha * alpha + 1.0f, 0.0f)) - ab;
    return glm::clamp(0.5f * two_p, 0.0f, 1.0f);
}

float global_shade(const glm::vec3& n_gl, float d_gl, const glm::vec3& light) {
    if (!(glm::dot(n_gl, n_gl) > 0.0f)) return 1.0f;
    return std::exp(-kGlobalShadingK * global_penetration(n_gl, d_gl, light));
}

float lengthwise_opacity(float op_min, float op_max, const glm::vec3& view,
                         const glm::vec3& tangent) {
    // GI'98 eq. 3 as printed. Note: the prose of §5.1 says op_min applies "head-on" and op_max
    // "orthogonally to its path", but with alpha = |view . unit tangent| the formula gives
    // op_max when the view runs along the path (alpha = 1, the longest path through the
    // material, as the volume-opacity motivation wants) and op_min when the path is seen
    // broadside (alpha = 0). We implement the formula.
    const float lv = glm::length(view), lt = glm::length(tangent);
    float alpha = 0.0f;
    if (lv > 0.0f && lt > 0.0f)
        alpha = glm::min(std::fabs(glm::dot(view, tangent)) / (lv * lt), 1.0f);
    return alpha * op_max + (1.0f - alpha) * op_min;
}

namespace {

// Any unit vector perpendicular to unit n (for a tangent parallel to the view).
glm::vec3 any_perpendicular(const glm::vec3& n) {
    const glm::vec3 h = std::fabs(n.x) < 0.6f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    return glm::normalize(glm::cross(n, h));
}

}  // namespace

RingFrame ring_frame(const SectionCurve& s, float t) {
    RingFrame f;
    f.pos = section_pos(s, t);
    f.tangent = section_pos_d1(s, t);
    f.rad = glm::max(section_rad(s, t), 0.0f);
    const float dist = glm::length(f.pos);
    f.view = dist > 0.0f ? f.pos / dist : glm::vec3(0, 0, -1);
    const float tl2 = glm::dot(f.tangent, f.tangent);
    f.tangent_defined = tl2 > 0.0f;
    const glm::vec3 tu = f.tangent_defined ? f.tangent / std::sqrt(tl2) : -f.view;
    // GI'98 §4.3.2: out_edge is perpendicular to the tangent and to the view vector (the
    // silhouette of a cylinder; not corrected for a cone's rad', whose silhouette moves
    // slightly to the far side, see back_side_visible).
    const glm::vec3 e = glm::cross(tu, f.view);
    const float el = glm::length(e);
    f.edge = el > 1e-6f ? e / el : any_perpendicular(tu);
    // out_centre: perpendicular to the tangent, toward the viewer (-view side).
    f.centre = glm::normalize(glm::cross(f.edge, tu));
    if (glm::dot(f.centre, f.view) > 0.0f) f.centre = -f.centre;
    // GI'98 eq. 2. Its norm |rad'| / |pos'| = |d rad / d arclength| is dimensionless, so it is
    // added to the *unit* out direction (out / rad): then out + adj is the true normal
    // direction of the truncated cone for any units of the radius.
    if (f.tangent_defined) f.adj = -(section_rad_d1(s, t) / tl2) * f.tangent;
    return f;
}

bool back_side_visible(const RingFrame& f) {
    if (!f.tangent_defined || !(f.rad > 0.0f)) return false;
    const glm::vec3 tu = f.tangent / glm::length(f.tangent);
    // adj = -(dr/ds) unit tangent (eq. 2), so dr/ds = -adj . unit tangent.
    const float drds_cos = -glm::dot(f.adj, tu) * glm::dot(tu, f.view);
    return drds_cos > f.rad / glm::length(f.pos);
}

int ring_front_count(int quality) {
    return quality <= 0 ? 2 : (quality == 1 ? 3 : 5);
}

int ring_size(int quality, bool back) {
    if (quality <= 0) return 2;
    return ring_front_count(quality) + (back ? (quality == 1 ? 1 : 3) : 0);
}

int ring_directions(const RingFrame& f, int quality, bool back, glm::vec3* dirs) {
    const glm::vec3 e = f.edge, c = f.centre;
    const float h = 0.70710678f;  // angular midpoints: normalised (e +- c)
    if (quality <= 0) {
        dirs[0] = e;
        dirs[1] = -e;
        return 2;
    }
    if (quality == 1) {
        dirs[0] = e;
        dirs[1] = c;
        dirs[2] = -e;
        if (back) dirs[3] = -c;
        return back ? 4 : 3;
    }
    dirs[0] = e;
    dirs[1] = h * (e + c);
    dirs[2] = c;
    dirs[3] = h * (c - e);
    dirs[4] = -e;
    if (!back) return 5;
    dirs[5] = -h * (e + c);
    dirs[6] = -c;
    dirs[7] = h * (e - c);
    return 8;
}

int build_ring(const RingFrame& f, int quality, bool back, const RingAttributes& attr,
               const StrokeStyle& style, float nudge, StrokeVertex* out) {
    glm::vec3 dirs[8], normals[8];
    const int n = ring_directions(f, quality, back, dirs);
    for (int i = 0; i < n; ++i) normals[i] = dirs[i] + f.adj;  // GI'98 eq. 2
    if (quality <= 0) {
        // GI'98 §4.4: quality-0 edge normals nudged toward the centre normal.
        const glm::vec3 nc = f.centre + f.adj;
        for (int i = 0; i < n; ++i) normals[i] += nudge * (nc - normals[i]);
    }
    // GI'98 eq. 4 over the viewer's side: s_i = (N_i . v) / max_j (N_j . v), v toward the
    // viewer, with unit normals; 1 when no vertex faces the viewer (degenerate head-on).
    float facing[8], max_facing = 0.0f;
    const int front = ring_front_count(quality);
    for (int i = 0; i < n; ++i) {
        const float l = glm::length(normals[i]);
        facing[i] = l > 0.0f ? -glm::dot(normals[i], f.view) / l : 0.0f;
        if (i < front) max_facing = glm::max(max_facing, facing[i]);
    }
    const float op_len = lengthwise_opacity(attr.op_min, attr.op_max, f.view, f.tangent);
    for (int i = 0; i < n; ++i) {
        float s = max_facing > 1e-6f ? glm::clamp(facing[i] / max_facing, 0.0f, 1.0f) : 1.0f;
        // GI'98 §4.3.1 (4): quality 0 has no breadthwise opacity variation; its single polygon
        // takes the stroke's body (centre) opacity.
        if (quality <= 0) s = 1.0f;
        const float o = (1.0f - s) * style.op_edge + s * style.op_centre;  // GI'98 eq. 5
        const glm::vec3 p = f.pos + f.rad * dirs[i];
        StrokeVertex& v = out[i];
        v.position[0] = p.x;
        v.position[1] = p.y;
        v.position[2] = p.z;
        v.normal[0] = normals[i].x;
        v.normal[1] = normals[i].y;
        v.normal[2] = normals[i].z;
        v.colour[0] = attr.colour.r;
        v.colour[1] = attr.colour.g;
        v.colour[2] = attr.colour.b;
        v.colour[3] = op_len * o;
        v.reflectance = attr.reflectance * attr.shade;  // §5.3: reflectance scaled down
        v.shade = attr.shade;
    }
    return n;
}

int ring_indices(int quality, bool back, uint32_t base, uint32_t* out) {
    const int size = ring_size(quality, back), front = ring_front_count(quality);
    const int quads = quality <= 0 ? 1 : (front - 1) + (back ? size - front + 1 : 0);
    int k = 0;
    for (int q = 0; q < quads; ++q) {
        const uint32_t i = base + uint32_t(q % size), j = base + uint32_t((q + 1) % size);
        const uint32_t bi = i + uint32_t(size), bj = j + uint32_t(size);
        out[k++] = i;
        out[k++] = j;
        out[k++] = bj;
        out[k++] = i;
        out[k++] = bj;
        out[k++] = bi;
    }
    return k;
}

}  // namespace stipple
