// GI'98 paintstroke tessellation (runtime/paintstroke.h): per section, the lengthwise
// segments of runtime/paintstroke_lengthwise.h, each tiled breadthwise by
// runtime/paintstroke_breadthwise.h and appended as one StrokeSegment.
#include "runtime/paintstroke.h"

#include <cmath>

#include "runtime/paintstroke_breadthwise.h"
#include "runtime/paintstroke_curve.h"
#include "runtime/paintstroke_lengthwise.h"

namespace stipple {

namespace {

constexpr int kMaxRing = 8;    // quality 2 with the far side
constexpr int kCapSpokes = 8;  // end cap fan at quality 2 (4 below)

bool finite3(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

bool valid_input(const StrokePoint* p, uint32_t count, const StrokeCamera& camera) {
    if (p == nullptr || count < 2) return false;
    if (!std::isfinite(camera.focal_px) || !(camera.focal_px > 0.0f)) return false;
    if (!std::isfinite(camera.near_z)) return false;
    for (uint32_t i = 0; i < count; ++i) {
        const StrokePoint& q = p[i];
        if (!finite3(q.position) || !finite3(q.colour) || !finite3(q.global_normal)) return false;
        if (!std::isfinite(q.radius) || q.radius < 0.0f) return false;
        if (!std::isfinite(q.reflectance) || !std::isfinite(q.op_min) || !std::isfinite(q.op_max) ||
            !std::isfinite(q.global_depth))
            return false;
    }
    return true;
}

// GI'98 §4.3: quality chosen per stroke from its largest projected control-point radius.
int resolve_quality(const StrokePoint* p, uint32_t count, const StrokeCamera& camera,
                    const TessellationParams& params) {
    if (params.quality >= 0) return params.quality > 2 ? 2 : params.quality;
    float r_px = 0.0f;
    for (uint32_t i = 0; i < count; ++i) {
        const float w = -p[i].position.z;
        if (w >= camera.near_z && w > 0.0f)
            r_px = glm::max(r_px, camera.focal_px * p[i].radius / w);
    }
    return r_px < params.q1_radius_px ? 0 : (r_px < params.q2_radius_px ? 1 : 2);
}

// Everything a stroke's segments share.
struct StrokeContext {
    const StrokePoint* points;
    uint32_t count;
    const StrokeStyle* style;
    uint32_t stroke_id;
    StrokeCamera camera;
    const TessellationParams* params;
    int quality;
    glm::vec3 light;
    StrokeMesh* out;
    TessellationStats* stats;
};

// `shade` holds the §5.3 factors exp(-k p) of cp_m and cp_{m+1}.
RingAttributes attributes_at(const StrokeContext& c, uint32_t m, const float* shade, float t) {
    const StrokePoint& a = c.points[m];
    const StrokePoint& b = c.points[m + 1];
    RingAttributes r;
    r.colour =
        glm::vec3(lerp_exact(a.colour.r, b.colour.r, t), lerp_exact(a.colour.g, b.colour.g, t),
                  lerp_exact(a.colour.b, b.colour.b, t));
    r.op_min = lerp_exact(a.op_min, b.op_min, t);
    r.op_max = lerp_exact(a.op_max, b.op_max, t);
    r.reflectance = lerp_exact(a.reflectance, b.reflectance, t);
    r.shade = lerp_exact(shade[0], shade[1], t);
    return r;
}

bool in_front(const StrokeVertex* v, int n, float near_z) {
    for (int i = 0; i < n; ++i)
        if (!(-v[i].position[2] >= near_z)) return false;
    return true;
}

// Reserves room for a whole segment, or sets overflow (nothing written past a capacity).
bool reserve(StrokeMesh* out, uint32_t vertices, uint32_t indices) {
    if (uint64_t(out->vertex_count) + vertices > out->vertex_capacity ||
        uint64_t(out->index_count) + indices > out->index_capacity ||
        uint64_t(out->segment_count) + 1 > out->segment_capacity) {
        out->overflow = true;
        return false;
    }
    return true;
}

void append_segment(const StrokeContext& c, const StrokeVertex* v, uint32_t nv, const uint32_t* idx,
                    uint32_t ni, float depth) {
    StrokeMesh* out = c.out;
    for (uint32_t i = 0; i < nv; ++i) out->vertices[out->vertex_count + i] = v[i];
    for (uint32_t i = 0; i < ni; ++i) out->indices[out->index_count + i] = idx[i];
    out->segments[out->segment_count] = StrokeSegment{out->index_count, ni, depth, c.stroke_id};
    out->vertex_count += nv;
    out->index_count += ni;
    ++out->segment_count;
    if (c.stats != nullptr) {
        ++c.stats->segments;
        c.stats->triangles += ni / 3;
    }
}

// The ring frame at the end of the previous segment: consecutive segments share their
// boundary t exactly (lengthwise_next), and sections their joint, so it is computed once.
struct RingCarry {
    bool valid = false;
    float t = 0.0f;
    RingFrame frame;
};

// One lengthwise segment [a, b] of section m. False on overflow.
bool emit_segment(const StrokeContext& c, const SectionCurve& s, uint32_t m, const float* shade,
                  float a, float b, RingCarry* carry) {
    const RingFrame fa = carry->valid && carry->t == a ? carry->frame : ring_frame(s, a);
    const RingFrame fb = ring_frame(s, b);
    *carry = RingCarry{true, b, fb};
    // GI'98 §4.3: the far side only where it can show at either end.
    const bool back = c.quality > 0 && (back_side_visible(fa) || back_side_visible(fb));
    StrokeVertex v[2 * kMaxRing];
    const int na = build_ring(fa, c.quality, back, attributes_at(c, m, shade, a), *c.style,
                              c.params->nudge, v);
    build_ring(fb, c.quality, back, attributes_at(c, m, shade, b), *c.style, c.params->nudge,
               v + na);
    if (!in_front(v, 2 * na, c.camera.near_z)) return true;  // crosses the near plane: skipped
    uint32_t idx[6 * kMaxRing];
    const int ni = ring_indices(c.quality, back, c.out->vertex_count, idx);
    if (!reserve(c.out, uint32_t(2 * na), uint32_t(ni))) return false;
    if (c.stats != nullptr && c.quality > 0 && !back) ++c.stats->back_sides_suppressed;
    const float depth = glm::length(section_pos(s, 0.5f * (a + b)));
    append_segment(c, v, uint32_t(2 * na), idx, uint32_t(ni), depth);
    return true;
}

// A fan closing the stroke end at t (0 of the first section or 1 of the last) when its disc
// faces the viewer. `outward` is -1 at the start (disc normal -pos'), +1 at the end.
bool emit_cap(const StrokeContext& c, const SectionCurve& s, uint32_t m, const float* shade,
              float t, float outward) {
    const RingFrame f = ring_frame(s, t);
    if (!f.tangent_defined || !(f.rad > 0.0f)) return true;
    if (!(f.rad * c.camera.focal_px >= c.params->cap_min_radius_px * -f.pos.z)) return true;
    const glm::vec3 n = outward * glm::normalize(f.tangent);
    if (!(glm::dot(n, f.view) < 0.0f)) return true;  // disc faces away: hidden by the tube
    const int spokes = c.quality >= 2 ? kCapSpokes : kCapSpokes / 2;
    const RingAttributes attr = attributes_at(c, m, shade, t);
    const float op =
        lengthwise_opacity(attr.op_min, attr.op_max, f.view, f.tangent) * c.style->op_centre;
    StrokeVertex v[kCapSpokes + 1];
    for (int i = 0; i <= spokes; ++i) {
        const float ang = 6.28318531f * float(i) / float(spokes);
        const glm::vec3 p =
            i == spokes ? f.pos
                        : f.pos + f.rad * (std::cos(ang) * f.edge + std::sin(ang) * f.centre);
        v[i] = StrokeVertex{{p.x, p.y, p.z},
                            {n.x, n.y, n.z},
                            {attr.colour.r, attr.colour.g, attr.colour.b, op},
                            attr.reflectance * attr.shade,
                            attr.shade};
    }
    if (!in_front(v, spokes + 1, c.camera.near_z)) return true;
    uint32_t idx[3 * kCapSpokes];
    const uint32_t base = c.out->vertex_count;
    for (int i = 0; i < spokes; ++i) {
        idx[3 * i] = base + uint32_t(spokes);
        idx[3 * i + 1] = base + uint32_t(i);
        idx[3 * i + 2] = base + uint32_t((i + 1) % spokes);
    }
    if (!reserve(c.out, uint32_t(spokes + 1), uint32_t(3 * spokes))) return false;
    append_segment(c, v, uint32_t(spokes + 1), idx, uint32_t(3 * spokes), glm::length(f.pos));
    return true;
}

}  // namespace

void tessellate_stroke(const StrokePoint* points, uint32_t count, const StrokeStyle& style,
                       uint32_t stroke_id, const StrokeCamera& camera,
                       const TessellationParams& params, StrokeMesh* out,
                       TessellationStats* stats) {
    if (out == nullptr || out->overflow || !valid_input(points, count, camera)) return;
    const glm::vec3 light = params.light_eye;
    const StrokeContext c{points,
                          count,
                          &style,
                          stroke_id,
                          camera,
                          &params,
                          resolve_quality(points, count, camera, params),
                          light,
                          out,
                          stats};
    if (stats != nullptr) {
        ++stats->strokes;
        ++stats->quality_count[c.quality];
    }
    LengthwiseState st;
    RingCarry carry;
    for (uint32_t m = 0; m + 1 < count; ++m) {
        const SectionCurve s = make_section_curve(points, count, m);
        // §5.3: p is computed at the control points and its shading factor interpolated.
        const float shade[2] = {
            global_shade(points[m].global_normal, points[m].global_depth, light),
            global_shade(points[m + 1].global_normal, points[m + 1].global_depth, light)};
        if (m == 0 && params.end_caps && !emit_cap(c, s, m, shade, 0.0f, -1.0f)) return;
        lengthwise_begin(&st, s, camera, params);
        if (stats != nullptr) {
            ++stats->sections;
            stats->inflection_splits += st.inflection_splits;
        }
        float a = 0.0f, b = 0.0f;
        // Section m + 1 starts where section m ended (same point, tangent and radius, exactly:
        // runtime/paintstroke_curve.h), so the last ring carries over as t = 0.
        carry.valid = carry.valid && carry.t == 1.0f;
        carry.t = 0.0f;
        while (lengthwise_next(&st, &a, &b))
            if (!emit_segment(c, s, m, shade, a, b, &carry)) return;
        if (m + 2 == count && params.end_caps && !emit_cap(c, s, m, shade, 1.0f, 1.0f)) return;
    }
}

StrokeMeshBound stroke_mesh_bound(uint32_t count, const TessellationParams& params) {
    StrokeMeshBound b;
    if (count < 2) return b;
    const uint64_t segments = uint64_t(count - 1) * max_segments_per_section(params);
    b.segments = segments + (params.end_caps ? 2 : 0);
    b.vertices = segments * 2 * kMaxRing + (params.end_caps ? 2 * (kCapSpokes + 1) : 0);
    b.indices = segments * 6 * kMaxRing + (params.end_caps ? 2 * 3 * kCapSpokes : 0);
    return b;
}

}  // namespace stipple
