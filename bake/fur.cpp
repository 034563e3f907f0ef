#include "bake/fur.h"

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>
#include <string>

#include "bake/bake_random.h"
#include "runtime/asset_limits.h"
#include "runtime/point_codec.h"
#include "runtime/stroke_anchor.h"

namespace stipple::bake {

namespace {

// The barycentrics the runtime decodes from the point stream (bake/point_codec_encode.cpp
// quantizes them to codec::kBaryBits), so a hair's root is its point to the last bit.
void decoded_barycentrics(float u, float v, float* du, float* dv) {
    constexpr uint32_t max = (1u << codec::kBaryBits) - 1;
    auto quantize = [](float x) {
        return uint32_t(std::lround(std::min(std::max(x, 0.0f), 1.0f) * float(max)));
    };
    const uint32_t qu = quantize(u), qv = std::min(quantize(v), max - qu);
    const float scale = 1.0f / float(max);
    *du = float(qu) * scale;
    *dv = float(qv) * scale;
}

uint8_t unit_byte(float x) {
    return uint8_t(std::lround(std::min(std::max(x, 0.0f), 1.0f) * 255.0f));
}

SurfaceFrame point_frame(const RawScene& s, uint32_t triangle, float u, float v) {
    auto at = [&](const std::vector<float>& a, int corner) {
        const size_t i = s.indices[size_t(triangle) * 3 + size_t(corner)];
        return glm::vec3(a[i * 3], a[i * 3 + 1], a[i * 3 + 2]);
    };
    return surface_frame(at(s.positions, 0), at(s.positions, 1), at(s.positions, 2),
                         at(s.normals, 0), at(s.normals, 1), at(s.normals, 2), u, v);
}

struct Hair {
    float length, radius, bend, curl, grey;
    glm::vec2 comb;  // unit direction of the bend in the frame's x-y plane (or zero)
};

// One hair in its frame: kFurControlPoints points from just below the surface (-0.1 radius,
// so the root is covered) along +z, turning toward the comb by up to hair.bend at the tip,
// the bend's direction twisting around z by curl per unit length.
void add_hair(const Hair& h, BakedStrokes* out) {
    const uint32_t n = kFurControlPoints;
    const float step = h.length / float(n - 1);
    glm::vec3 p(0.0f, 0.0f, -0.1f * h.radius);
    for (uint32_t k = 0; k < n; ++k) {
        const float t = float(k) / float(n - 1);
        format::StrokePointRecord r = {};
        r.position[0] = p.x;
        r.position[1] = p.y;
        r.position[2] = p.z;
        r.radius = h.radius * (1.0f - 0.8f * t);
        r.colour[0] = r.colour[1] = r.colour[2] = unit_byte(h.grey);
        r.reflectance = unit_byte(0.3f);
        r.op_min = r.op_max = 255;
        r.global_depth = unit_byte(t);
        r.global_normal[2] = 127;
        out->points.push_back(r);
        // The next section: its direction at the section's middle.
        const float mid = (float(k) + 0.5f) / float(n - 1);
        const float angle = h.bend * mid, twist = h.curl * h.length * mid;
        const glm::vec2 c(h.comb.x * std::cos(twist) - h.comb.y * std::sin(twist),
                          h.comb.x * std::sin(twist) + h.comb.y * std::cos(twist));
        p += step * glm::vec3(std::sin(angle) * c, std::cos(angle));
    }
}

BakeError check_config(const FurConfig& c, float length, float radius) {
    const float max = limits::kMaxStrokeCoordinate / 4;
    if (!std::isfinite(length) || !(length > 0.0f) || length > max)
        return bake_error(BakeErrorCode::invalid_option,
                          "fur length " + std::to_string(length) + " not in (0, 2.5e5]");
    if (!std::isfinite(radius) || !(radius > 0.0f) || radius > max)
        return bake_error(BakeErrorCode::invalid_option,
                          "fur radius " + std::to_string(radius) + " not in (0, 2.5e5]");
    if (!std::isfinite(c.comb[0]) || !std::isfinite(c.comb[1]) || !std::isfinite(c.comb[2]) ||
        !std::isfinite(c.curl))
        return bake_error(BakeErrorCode::invalid_option, "fur comb or curl not finite");
    if (c.count > limits::kMaxStrokes)
        return bake_error(BakeErrorCode::invalid_option, "fur count " + std::to_string(c.count) +
                                                             " over the limit of " +
                                                             std::to_string(limits::kMaxStrokes));
    return {};
}

}  // namespace

float default_fur_length(const RawScene& scene) {
    if (scene.positions.empty()) return 0.0f;
    glm::vec3 lo(scene.positions[0], scene.positions[1], scene.positions[2]), hi = lo;
    for (size_t i = 0; i + 2 < scene.positions.size(); i += 3) {
        const glm::vec3 p(scene.positions[i], scene.positions[i + 1], scene.positions[i + 2]);
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    return 0.03f * glm::length(hi - lo);
}

BakeError bake_fur(const RawScene& scene, const PointHierarchy& points, const FurConfig& config,
                   BakedStrokes* out) {
    const float length = config.length == 0.0f ? default_fur_length(scene) : config.length;
    const float radius = config.radius == 0.0f ? length / 25.0f : config.radius;
    BakeError e = check_config(config, length, radius);
    if (!e.ok()) return e;
    const glm::vec3 comb(config.comb[0], config.comb[1], config.comb[2]);
    const uint32_t count = uint32_t(std::min<size_t>(config.count, points.size()));
    BakedStrokes fur;
    for (uint32_t i = 0; i < count; ++i) {
        if (points.host_triangle[i] >= scene.triangle_count())
            return malformed_input("fur: point " + std::to_string(i) + " host triangle " +
                                   std::to_string(points.host_triangle[i]) + " outside the mesh");
        format::StrokeRecord s = {};
        s.first_point = uint32_t(fur.points.size());
        s.point_count = kFurControlPoints;
        s.anchor = format::kAnchorSurface;
        s.host = points.host_triangle[i];
        decoded_barycentrics(points.bary_u[i], points.bary_v[i], &s.bary_u, &s.bary_v);
        s.root_point = i;
        s.op_centre = s.op_edge = 255;
        fur.strokes.push_back(s);
        const SurfaceFrame f = point_frame(scene, s.host, s.bary_u, s.bary_v);
        const glm::vec2 c(glm::dot(comb, f.x), glm::dot(comb, f.y));
        const float c_len = glm::length(c);
        Rng rng{uint64_t(i) * 0x9E3779B97F4A7C15ull + 0x5EEDull};
        Hair h;
        h.length = length * float(0.85 + 0.3 * rng.uniform());
        h.radius = radius;
        h.bend = std::min(c_len, kMaxFurBend);
        h.comb = c_len > 1e-6f ? c / c_len : glm::vec2(0.0f);
        h.curl = config.curl;
        h.grey = float(0.22 + 0.08 * rng.uniform());
        add_hair(h, &fur);
    }
    append_strokes(fur, out);
    return {};
}

}  // namespace stipple::bake
