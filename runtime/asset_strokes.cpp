// The STRK section: paintstroke records and their control points (runtime/asset_format.h),
// validated in place and exposed as StrokesView. Split from asset.cpp.
#include <cmath>
#include <cstring>

#include "anim/finite.h"
#include "runtime/asset_limits.h"
#include "runtime/asset_parse.h"

namespace stipple::detail {

namespace {

bool all_zero(const uint8_t* bytes, size_t count) {
    for (size_t i = 0; i < count; ++i)
        if (bytes[i] != 0) return false;
    return true;
}

// The stroke's anchor: kind known, host inside its array, barycentrics inside the triangle
// (surface), the unused fields 0 (object and joint anchors).
Status check_anchor(const format::StrokeRecord& s, uint32_t i, const Asset& a) {
    const float tol = limits::kStrokeBaryTolerance;
    switch (s.anchor) {
        case format::kAnchorSurface:
            if (s.host >= a.mesh.triangle_count)
                return load_failure(LoadError::out_of_range,
                                    "STRK: stroke %u host triangle %u >= triangle count %u", i,
                                    s.host, a.mesh.triangle_count);
            if (!std::isfinite(s.bary_u) || !std::isfinite(s.bary_v) || s.bary_u < -tol ||
                s.bary_v < -tol || s.bary_u + s.bary_v > 1.0f + tol)
                return load_failure(LoadError::bad_value,
                                    "STRK: stroke %u barycentrics (%g, %g) outside the triangle", i,
                                    double(s.bary_u), double(s.bary_v));
            return {};
        case format::kAnchorJoint:
            if (!a.skinned)
                return load_failure(LoadError::missing_section,
                                    "STRK: stroke %u is joint-anchored but the asset has no SKIN",
                                    i);
            if (s.host >= a.skin.skeleton.joint_count)
                return load_failure(LoadError::out_of_range,
                                    "STRK: stroke %u joint %u >= joint count %u", i, s.host,
                                    a.skin.skeleton.joint_count);
            break;
        case format::kAnchorObject:
            if (s.host != 0)
                return load_failure(LoadError::bad_value,
                                    "STRK: stroke %u object anchor with host %u (must be 0)", i,
                                    s.host);
            break;
        default:
            return load_failure(LoadError::bad_value, "STRK: stroke %u anchor kind %u unknown", i,
                                unsigned(s.anchor));
    }
    if (s.bary_u != 0.0f || s.bary_v != 0.0f)
        return load_failure(LoadError::bad_value,
                            "STRK: stroke %u barycentrics (%g, %g) on a non-surface anchor "
                            "(must be 0)",
                            i, double(s.bary_u), double(s.bary_v));
    return {};
}

// Stroke i: its run of control points after `*end` (ascending, non-overlapping) and inside
// the array, its anchor, its root point and reserved bytes.
Status check_stroke(const format::StrokeRecord& s, uint32_t i, uint32_t point_count, const Asset& a,
                    uint64_t* end) {
    if (s.point_count < 2)
        return load_failure(LoadError::bad_value, "STRK: stroke %u has %u control points (< 2)", i,
                            s.point_count);
    if (s.point_count > limits::kMaxPointsPerStroke)
        return load_failure(LoadError::count_over_limit,
                            "STRK: stroke %u point count %u over the limit of %u", i, s.point_count,
                            limits::kMaxPointsPerStroke);
    const uint64_t first = s.first_point, last = first + s.point_count;
    if (first < *end || last > point_count)
        return load_failure(LoadError::out_of_range,
                            "STRK: stroke %u points [%u, +%u) overlap the previous stroke or pass "
                            "%u points",
                            i, s.first_point, s.point_count, point_count);
    *end = last;
    if (!all_zero(s.reserved, sizeof(s.reserved)) || s.reserved2 != 0)
        return load_failure(LoadError::bad_value, "STRK: stroke %u reserved bytes not 0", i);
    if (s.root_point != format::kNoRootPoint && s.root_point >= a.points.point_count)
        return load_failure(LoadError::out_of_range,
                            "STRK: stroke %u root point %u >= point count %u", i, s.root_point,
                            a.points.point_count);
    return check_anchor(s, i, a);
}

// Control point i: finite position within the coordinate limit, radius > 0, global normal
// zero or unit (snorm8), reserved bytes 0.
Status check_point(const format::StrokePointRecord& p, uint32_t i) {
    const float max = limits::kMaxStrokeCoordinate;
    if (!all_finite(p.position, 3) || std::fabs(p.position[0]) > max ||
        std::fabs(p.position[1]) > max || std::fabs(p.position[2]) > max)
        return load_failure(LoadError::bad_value,
                            "STRK: point %u position not finite or beyond +-%g", i, double(max));
    if (!std::isfinite(p.radius) || !(p.radius > 0.0f) || p.radius > max)
        return load_failure(LoadError::bad_radius, "STRK: point %u radius %g not in (0, %g]", i,
                            double(p.radius), double(max));
    if (p.reserved != 0 || p.reserved2 != 0)
        return load_failure(LoadError::bad_value, "STRK: point %u reserved bytes not 0", i);
    const int8_t* n = p.global_normal;
    if (n[0] == 0 && n[1] == 0 && n[2] == 0) return {};
    const float x = n[0] / 127.0f, y = n[1] / 127.0f, z = n[2] / 127.0f;
    const float len = std::sqrt(x * x + y * y + z * z), tol = limits::kStrokeNormalTolerance;
    if (!(len >= 1.0f - tol && len <= 1.0f + tol))
        return load_failure(LoadError::bad_normal,
                            "STRK: point %u global normal length %g is neither 0 nor 1 (+-%g)", i,
                            double(len), double(tol));
    return {};
}

}  // namespace

Status parse_strokes(Reader r, Asset* a) {
    const uint32_t stroke_count = r.u32(), point_count = r.u32();
    Status st = check_limit("STRK", "stroke count", stroke_count, limits::kMaxStrokes);
    if (st.ok()) st = check_limit("STRK", "point count", point_count, limits::kMaxStrokePoints);
    if (!st.ok()) return st;
    const auto* strokes = r.take<format::StrokeRecord>(stroke_count);
    const auto* points = r.take<format::StrokePointRecord>(point_count);
    if (!r.ok || r.at != r.size)
        return load_failure(LoadError::malformed_section,
                            "STRK: size does not match %u strokes, %u points", stroke_count,
                            point_count);
    if (stroke_count == 0) return load_failure(LoadError::zero_count, "STRK: no strokes");
    uint64_t end = 0;
    uint32_t longest = 0;
    for (uint32_t i = 0; i < stroke_count; ++i) {
        st = check_stroke(strokes[i], i, point_count, *a, &end);
        if (!st.ok()) return st;
        if (strokes[i].point_count > longest) longest = strokes[i].point_count;
    }
    for (uint32_t i = 0; i < point_count; ++i) {
        st = check_point(points[i], i);
        if (!st.ok()) return st;
    }
    StrokesView& v = a->strokes;
    v.stroke_count = stroke_count;
    v.point_count = point_count;
    v.strokes = strokes;
    v.points = points;
    v.max_points_per_stroke = longest;
    return {};
}

}  // namespace stipple::detail
