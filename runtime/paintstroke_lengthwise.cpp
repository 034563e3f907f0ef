#include "runtime/paintstroke_lengthwise.h"

#include <algorithm>
#include <cmath>

namespace stipple {

int lengthwise_depth_limit(const TessellationParams& params) {
    const int d = params.max_depth;
    return d < 0 ? 0 : (d > kMaxLengthwiseDepth ? kMaxLengthwiseDepth : d);
}

uint64_t max_segments_per_section(const TessellationParams& params) {
    return uint64_t(kMaxInflectionSplits + 1) << lengthwise_depth_limit(params);
}

void project_path(const SectionCurve& s, float t, float focal_px, glm::vec2* p, glm::vec2* d1,
                  glm::vec2* d2) {
    // s = f q / w with q = (x, y), w = -z:
    //   s'  = f (q' / w - q w' / w^2)
    //   s'' = f (q'' / w - 2 q' w' / w^2 - q w'' / w^2 + 2 q w'^2 / w^3)
    const glm::vec3 P = section_pos(s, t), D1 = section_pos_d1(s, t), D2 = section_pos_d2(s, t);
    const float w = -P.z, w1 = -D1.z, w2 = -D2.z;
    const glm::vec2 q(P), q1(D1), q2(D2);
    const float iw = 1.0f / w;
    *p = focal_px * q * iw;
    *d1 = focal_px * (q1 * iw - q * (w1 * iw * iw));
    *d2 = focal_px * (q2 * iw - q1 * (2.0f * w1 * iw * iw) - q * (w2 * iw * iw) +
                      q * (2.0f * w1 * w1 * iw * iw * iw));
}

namespace {

// GI'98 eq. 1: the screen point on the outside boundary at t: pos_scr(t) displaced by the
// normalised perpendicular of pos'_scr(t), scaled to the projected radius, on the side away
// from pos''_scr(t) (which points toward the centre of curvature). p, d1, d2: project_path at t.
glm::vec2 outside_point(const SectionCurve& s, float t, float focal_px, const glm::vec2& p,
                        const glm::vec2& d1, const glm::vec2& d2) {
    glm::vec2 n(d1.y, -d1.x);
    const float len = glm::length(n);
    if (!(len > 0.0f)) return p;
    n /= len;
    if (glm::dot(n, d2) > 0.0f) n = -n;  // the other vector of eq. 1
    const float r_px = focal_px * glm::max(section_rad(s, t), 0.0f) / -section_pos(s, t).z;
    return p + n * r_px;
}

}  // namespace

PositionConstraint1 position_constraint_1(const SectionCurve& s, float a, float b, float focal_px,
                                          float tol_theta_px) {
    PositionConstraint1 r;
    glm::vec2 pa, ta, ca, pb, tb, cb;
    project_path(s, a, focal_px, &pa, &ta, &ca);
    project_path(s, b, focal_px, &pb, &tb, &cb);
    const float la = glm::length(ta), lb = glm::length(tb);
    if (!(la > 0.0f) || !(lb > 0.0f)) return r;  // seen exactly along the path: no tangent
    r.defined = true;
    r.cos_theta = glm::dot(ta, tb) / (la * lb);
    const glm::vec2 oa = outside_point(s, a, focal_px, pa, ta, ca),
                    ob = outside_point(s, b, focal_px, pb, tb, cb);
    const float d2 = glm::dot(ob - oa, ob - oa);
    r.d = std::sqrt(d2);
    const float tol2 = tol_theta_px * tol_theta_px;
    r.cos2_max = d2 + tol2 > 0.0f ? d2 / (d2 + tol2) : 1.0f;
    // theta > theta_max  <=>  cos^2(theta) < cos^2(theta_max) for theta in [0, 90 deg];
    // a negative cosine means theta exceeds any theta_max < 90 deg.
    r.split = r.cos_theta < 0.0f || r.cos_theta * r.cos_theta < r.cos2_max;
    return r;
}

float z_nonlinearity_px(const SectionCurve& s, float a, float b, float focal_px) {
    // GI'98 §4.2.2: (d_proj / pos_z(a)) |avg pos_z - (pos_z(a) + pos_z(b)) / 2|.
    const float za = section_pos(s, a).z, zb = section_pos(s, b).z;
    const float avg = cubic_average(s.pos[2], a, b);
    return focal_px / std::fabs(za) * std::fabs(avg - 0.5f * (za + zb));
}

float rad_nonlinearity_px(const SectionCurve& s, float a, float b, float focal_px) {
    // GI'98 §4.2.2 radius constraint: the same measure on rad(t).
    const float za = section_pos(s, a).z;
    const float ra = section_rad(s, a), rb = section_rad(s, b);
    const float avg = cubic_average(s.rad, a, b);
    return focal_px / std::fabs(za) * std::fabs(avg - 0.5f * (ra + rb));
}

bool segment_needs_split(const SectionCurve& s, float a, float b, const StrokeCamera& camera,
                         const TessellationParams& params) {
    // Both ends in front of the eye's near plane or not drawn at all: a piece wholly behind it
    // is not refined (its projection is meaningless and it would split to the depth limit).
    if (-section_pos(s, a).z < camera.near_z && -section_pos(s, b).z < camera.near_z) return false;
    const float f = camera.focal_px;
    if (position_constraint_1(s, a, b, f, params.tol_theta_px).split) return true;
    if (!(z_nonlinearity_px(s, a, b, f) < params.tol_z_px)) return true;
    return !(rad_nonlinearity_px(s, a, b, f) < params.tol_z_px);
}

namespace {

// How far (in pixels, perspective-scaled at the section's nearer end) a cubic with second
// derivative q'' can stray from its chord over the whole section: |f - linear| <= max|f''| / 8
// on [0, 1], and f'' is linear in t, so its largest magnitude is at an end.
float deviation_bound_px(float d2_at_0, float d2_at_1, float scale) {
    return scale * 0.125f * std::max(std::fabs(d2_at_0), std::fabs(d2_at_1));
}

}  // namespace

int section_inflection_points(const SectionCurve& s, const StrokeCamera& camera,
                              const TessellationParams& params, float* t) {
    // GI'98 §4.2.3 splits at inflections because Constraint II and the radius constraint
    // compare averages, which an S-shaped piece can balance out. A piece whose function
    // cannot stray from its chord by the tolerance anywhere needs no split for that (its
    // nonlinearity is below tol everywhere): skipping those keeps sub-pixel strokes (fur) at
    // one segment per section. Likewise the projected path (orthographic, as §4.2.3 does):
    // Constraint I tolerates a sagitta of about tol_theta / 8 pixels on any segment.
    const float z_near = std::max(std::min(-s.p0.z, -s.p1.z), camera.near_z);
    const float scale = camera.focal_px / z_near;
    const glm::vec3 d2a = section_pos_d2(s, 0.0f), d2b = section_pos_d2(s, 1.0f);
    float c[kMaxInflectionSplits];
    int n = 0;
    if (deviation_bound_px(d2a.z, d2b.z, scale) >= params.tol_z_px)
        n += cubic_inflection(s.pos[2], 0.0f, 1.0f, c + n);  // pos_z'' = 0
    if (deviation_bound_px(section_rad_d2(s, 0.0f), section_rad_d2(s, 1.0f), scale) >=
        params.tol_z_px)
        n += cubic_inflection(s.rad, 0.0f, 1.0f, c + n);  // rad'' = 0
    const float screen_d2a = glm::length(glm::vec2(d2a)), screen_d2b = glm::length(glm::vec2(d2b));
    if (deviation_bound_px(screen_d2a, screen_d2b, scale) >= 0.125f * params.tol_theta_px)
        n += screen_inflections(s, 0.0f, 1.0f, c + n);  // projected path curvature = 0
    // Insertion sort, dropping duplicates.
    int out = 0;
    for (int i = 0; i < n; ++i) {
        int j = out;
        bool dup = false;
        for (int k = 0; k < out; ++k) dup = dup || t[k] == c[i];
        if (dup) continue;
        while (j > 0 && t[j - 1] > c[i]) {
            t[j] = t[j - 1];
            --j;
        }
        t[j] = c[i];
        ++out;
    }
    return out;
}

void lengthwise_begin(LengthwiseState* st, const SectionCurve& s, const StrokeCamera& camera,
                      const TessellationParams& params) {
    st->curve = &s;
    st->camera = camera;
    st->params = params;
    st->depth_limit = lengthwise_depth_limit(params);
    // GI'98 §4.2.3: split at the inflection points first; push the pieces last-first so they
    // pop in increasing t.
    float t[kMaxInflectionSplits + 2];
    const int n = section_inflection_points(s, camera, params, t + 1);
    t[0] = 0.0f;
    t[n + 1] = 1.0f;
    st->inflection_splits = uint32_t(n);
    st->top = 0;
    for (int i = n; i >= 0; --i) {
        st->a[st->top] = t[i];
        st->b[st->top] = t[i + 1];
        st->depth[st->top] = 0;
        ++st->top;
    }
}

bool lengthwise_next(LengthwiseState* st, float* a, float* b) {
    while (st->top > 0) {
        --st->top;
        const float ta = st->a[st->top], tb = st->b[st->top];
        const int d = st->depth[st->top];
        const float tm = 0.5f * (ta + tb);
        // GI'98 §4.2: split at the parametric midpoint while a constraint fails.
        if (d < st->depth_limit && tm > ta && tm < tb &&
            segment_needs_split(*st->curve, ta, tb, st->camera, st->params)) {
            st->a[st->top] = tm;
            st->b[st->top] = tb;
            st->depth[st->top] = uint8_t(d + 1);
            ++st->top;
            st->a[st->top] = ta;
            st->b[st->top] = tm;
            st->depth[st->top] = uint8_t(d + 1);
            ++st->top;
            continue;
        }
        *a = ta;
        *b = tb;
        return true;
    }
    return false;
}

}  // namespace stipple
