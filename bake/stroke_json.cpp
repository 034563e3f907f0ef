#include "bake/stroke_json.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "runtime/asset_limits.h"

namespace stipple::bake {

namespace {

using nlohmann::json;

// A failure inside the parse: the message, already naming the field.
struct Fail {
    std::string message;
};

[[noreturn]] void fail(const std::string& where, const std::string& what) {
    throw Fail{where + ": " + what};
}

double number(const json& j, const std::string& where, double lo, double hi) {
    if (!j.is_number()) fail(where, "must be a number");
    const double x = j.get<double>();
    if (!std::isfinite(x) || x < lo || x > hi) {
        std::ostringstream s;
        s << "value " << x << " not in [" << lo << ", " << hi << "]";
        fail(where, s.str());
    }
    return x;
}

std::vector<float> numbers(const json& j, const std::string& where, size_t n, double lo,
                           double hi) {
    if (!j.is_array() || j.size() != n)
        fail(where, "must be an array of " + std::to_string(n) + " numbers");
    std::vector<float> out;
    for (size_t i = 0; i < n; ++i)
        out.push_back(float(number(j[i], where + "[" + std::to_string(i) + "]", lo, hi)));
    return out;
}

uint8_t unit_byte(float x) {
    return uint8_t(std::lround(std::min(std::max(x, 0.0f), 1.0f) * 255.0f));
}

// A per-stroke value or one per control point: `width` numbers (1: a bare number) or an
// array of `count` of them. Returns `count` * width floats.
std::vector<float> per_point(const json* j, const std::string& where, size_t count, size_t width,
                             double lo, double hi, const std::vector<float>& fallback) {
    std::vector<float> out;
    auto one = [&](const json& v, const std::string& at) {
        return width == 1 ? std::vector<float>{float(number(v, at, lo, hi))}
                          : numbers(v, at, width, lo, hi);
    };
    const bool each = j && j->is_array() && !j->empty() && (width > 1 ? (*j)[0].is_array() : true);
    if (!j) {
        for (size_t i = 0; i < count; ++i) out.insert(out.end(), fallback.begin(), fallback.end());
    } else if (each) {
        if (j->size() != count)
            fail(where, "has " + std::to_string(j->size()) + " entries for " +
                            std::to_string(count) + " points");
        for (size_t i = 0; i < count; ++i) {
            std::vector<float> v = one((*j)[i], where + "[" + std::to_string(i) + "]");
            out.insert(out.end(), v.begin(), v.end());
        }
    } else {
        const std::vector<float> v = one(*j, where);
        for (size_t i = 0; i < count; ++i) out.insert(out.end(), v.begin(), v.end());
    }
    return out;
}

const json* member(const json& object, const char* key) {
    auto it = object.find(key);
    return it == object.end() ? nullptr : &*it;
}

void check_keys(const json& object, const std::string& where,
                std::initializer_list<const char*> known) {
    if (!object.is_object()) fail(where, "must be an object");
    for (auto it = object.begin(); it != object.end(); ++it)
        if (std::none_of(known.begin(), known.end(), [&](const char* k) { return it.key() == k; }))
            fail(where, "unknown key '" + it.key() + "'");
}

uint32_t joint_index(const json& j, const std::string& where, const RawScene& scene) {
    if (j.is_number()) {  // a joint index, for skins whose joints have no names
        if (scene.joint_nodes.empty()) fail(where, "the scene has no skin");
        const double index = number(j, where, 0, double(scene.joint_nodes.size()) - 1);
        if (index != std::floor(index)) fail(where, "must be an integer");
        return uint32_t(index);
    }
    if (!j.is_string()) fail(where, "must be a joint name (a string) or index");
    const std::string name = j.get<std::string>();
    if (scene.joint_nodes.empty()) fail(where, "joint '" + name + "': the scene has no skin");
    int64_t found = -1;
    for (size_t i = 0; i < scene.joint_nodes.size(); ++i) {
        const uint32_t node = scene.joint_nodes[i];
        if (node >= scene.nodes.size() || scene.nodes[node].name != name) continue;
        if (found >= 0)
            fail(where, "joint name '" + name + "' names joints " + std::to_string(found) +
                            " and " + std::to_string(i));
        found = int64_t(i);
    }
    if (found < 0) fail(where, "no joint named '" + name + "'");
    return uint32_t(found);
}

// The anchor fields of a stroke: kind, joint or triangle + barycentrics.
void parse_anchor(const json& s, const std::string& where, const RawScene& scene,
                  format::StrokeRecord* r) {
    const json* anchor = member(s, "anchor");
    const std::string kind =
        anchor ? (anchor->is_string() ? anchor->get<std::string>() : "?") : std::string("object");
    if (kind == "object") {
        r->anchor = format::kAnchorObject;
    } else if (kind == "joint") {
        r->anchor = format::kAnchorJoint;
        const json* joint = member(s, "joint");
        if (!joint) fail(where, "joint anchor without a \"joint\" name");
        r->host = joint_index(*joint, where + ".joint", scene);
    } else if (kind == "surface") {
        r->anchor = format::kAnchorSurface;
        const json* t = member(s, "triangle");
        const json* b = member(s, "barycentric");
        if (!t || !b) fail(where, "surface anchor needs \"triangle\" and \"barycentric\"");
        const double tri_max = double(scene.triangle_count()) - 1;
        if (tri_max < 0) fail(where + ".triangle", "the mesh has no triangles");
        const double tri = number(*t, where + ".triangle", 0, tri_max);
        if (tri != std::floor(tri)) fail(where + ".triangle", "must be an integer");
        r->host = uint32_t(tri);
        const std::vector<float> uv = numbers(*b, where + ".barycentric", 2, 0, 1);
        if (uv[0] + uv[1] > 1.0f) fail(where + ".barycentric", "u + v above 1");
        r->bary_u = uv[0];
        r->bary_v = uv[1];
    } else {
        fail(where + ".anchor", "must be \"object\", \"joint\" or \"surface\"");
    }
    if (r->anchor != format::kAnchorJoint && member(s, "joint"))
        fail(where + ".joint", "only for joint anchors");
    if (r->anchor != format::kAnchorSurface && (member(s, "triangle") || member(s, "barycentric")))
        fail(where, "\"triangle\"/\"barycentric\" only for surface anchors");
}

// Breadthwise opacity of the stroke, and lengthwise (per point, or one for all).
void parse_opacity(const json* o, const std::string& where, format::StrokeRecord* r,
                   std::vector<format::StrokePointRecord>* points) {
    r->op_centre = r->op_edge = 255;
    if (!o) return;
    check_keys(*o, where, {"min", "max", "centre", "edge"});
    const size_t n = points->size();
    const std::vector<float> lo = per_point(member(*o, "min"), where + ".min", n, 1, 0, 1, {1});
    const std::vector<float> hi = per_point(member(*o, "max"), where + ".max", n, 1, 0, 1, {1});
    for (size_t i = 0; i < n; ++i) {
        (*points)[i].op_min = unit_byte(lo[i]);
        (*points)[i].op_max = unit_byte(hi[i]);
    }
    if (const json* c = member(*o, "centre"))
        r->op_centre = unit_byte(float(number(*c, where + ".centre", 0, 1)));
    if (const json* e = member(*o, "edge"))
        r->op_edge = unit_byte(float(number(*e, where + ".edge", 0, 1)));
}

// Control points: [x, y, z, r] each, finite, radius > 0.
std::vector<format::StrokePointRecord> parse_points(const json* p, const std::string& where) {
    if (!p) fail(where, "missing");
    if (!p->is_array()) fail(where, "must be an array of [x, y, z, radius]");
    if (p->size() < 2 || p->size() > limits::kMaxPointsPerStroke)
        fail(where, "has " + std::to_string(p->size()) + " points, not in [2, " +
                        std::to_string(limits::kMaxPointsPerStroke) + "]");
    const double max = limits::kMaxStrokeCoordinate;
    std::vector<format::StrokePointRecord> out(p->size());
    for (size_t i = 0; i < p->size(); ++i) {
        const std::string at = where + "[" + std::to_string(i) + "]";
        const std::vector<float> v = numbers((*p)[i], at, 4, -max, max);
        if (!(v[3] > 0.0f)) {
            std::ostringstream m;
            m << "radius " << v[3] << " not > 0";
            fail(at, m.str());
        }
        out[i] = {};
        std::copy(v.begin(), v.begin() + 3, out[i].position);
        out[i].radius = v[3];
        out[i].op_min = out[i].op_max = 255;
    }
    return out;
}

// Colour, reflectance, global normal and depth: per stroke or per point.
void parse_shading(const json& s, const std::string& where,
                   std::vector<format::StrokePointRecord>* points) {
    const size_t n = points->size();
    const std::vector<float> colour =
        per_point(member(s, "colour"), where + ".colour", n, 3, 0, 1, {0.5f, 0.5f, 0.5f});
    const std::vector<float> refl =
        per_point(member(s, "reflectance"), where + ".reflectance", n, 1, 0, 1, {0.3f});
    const std::vector<float> normal =
        per_point(member(s, "global_normal"), where + ".global_normal", n, 3, -1e6, 1e6, {0, 0, 0});
    const std::vector<float> depth =
        per_point(member(s, "global_depth"), where + ".global_depth", n, 1, 0, 1, {0});
    for (size_t i = 0; i < n; ++i) {
        format::StrokePointRecord& p = (*points)[i];
        for (int c = 0; c < 3; ++c) p.colour[c] = unit_byte(colour[i * 3 + size_t(c)]);
        p.reflectance = unit_byte(refl[i]);
        p.global_depth = unit_byte(depth[i]);
        const float x = normal[i * 3], y = normal[i * 3 + 1], z = normal[i * 3 + 2];
        const float len = std::sqrt(x * x + y * y + z * z);
        if (len == 0.0f) continue;
        if (!(len > 1e-6f) || !std::isfinite(len))
            fail(where + ".global_normal", "point " + std::to_string(i) + " has no direction");
        for (int c = 0; c < 3; ++c)
            p.global_normal[c] = int8_t(std::lround(normal[i * 3 + size_t(c)] / len * 127.0f));
    }
}

void parse_stroke(const json& s, size_t index, const RawScene& scene, BakedStrokes* out) {
    const std::string where = "strokes[" + std::to_string(index) + "]";
    check_keys(s, where,
               {"anchor", "joint", "triangle", "barycentric", "points", "colour", "reflectance",
                "opacity", "global_normal", "global_depth"});
    format::StrokeRecord r = {};
    r.root_point = format::kNoRootPoint;
    parse_anchor(s, where, scene, &r);
    std::vector<format::StrokePointRecord> points =
        parse_points(member(s, "points"), where + ".points");
    parse_shading(s, where, &points);
    parse_opacity(member(s, "opacity"), where + ".opacity", &r, &points);
    if (out->points.size() + points.size() > limits::kMaxStrokePoints)
        fail(where, "control points over the limit of " + std::to_string(limits::kMaxStrokePoints));
    r.first_point = uint32_t(out->points.size());
    r.point_count = uint32_t(points.size());
    out->strokes.push_back(r);
    out->points.insert(out->points.end(), points.begin(), points.end());
}

}  // namespace

BakeError parse_strokes_json(const std::string& text, const RawScene& scene, BakedStrokes* out) {
    const json doc = json::parse(text, nullptr, /*allow_exceptions=*/false);
    if (doc.is_discarded()) return malformed_input("not valid JSON");
    BakedStrokes parsed;
    try {
        check_keys(doc, "top level", {"strokes"});
        const json* strokes = member(doc, "strokes");
        if (!strokes || !strokes->is_array()) fail("strokes", "must be an array");
        if (strokes->size() > limits::kMaxStrokes)
            fail("strokes", std::to_string(strokes->size()) + " strokes, over the limit of " +
                                std::to_string(limits::kMaxStrokes));
        for (size_t i = 0; i < strokes->size(); ++i) parse_stroke((*strokes)[i], i, scene, &parsed);
    } catch (const Fail& f) {
        return malformed_input(f.message);
    } catch (const json::exception& e) {
        return malformed_input(std::string("JSON: ") + e.what());
    }
    append_strokes(parsed, out);
    return {};
}

BakeError load_strokes_json(const std::string& path, const RawScene& scene, BakedStrokes* out) {
    std::ifstream f(path, std::ios::binary);
    if (!f) return bake_error(BakeErrorCode::io, path + ": cannot open the strokes file");
    std::stringstream ss;
    ss << f.rdbuf();
    if (f.bad()) return bake_error(BakeErrorCode::io, path + ": cannot read the strokes file");
    return prefixed(path + ": ", parse_strokes_json(ss.str(), scene, out));
}

}  // namespace stipple::bake
