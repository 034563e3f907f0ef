#include "runtime/normal_bounds.h"

#include <algorithm>
#include <cmath>

#include "runtime/memory.h"

namespace stipple {

namespace {

glm::vec3 normal(const float* normals, uint32_t v) {
    const float* n = normals + size_t(v) * 3;
    return glm::vec3(n[0], n[1], n[2]);
}

// sin of an angle in [0, pi] from its cosine.
float sine_of(float cosine) {
    return std::sqrt(std::max(0.0f, 1.0f - cosine * cosine));
}

// N.V at most for normals within angle t = acos(cos_t) of the unit `axis`, on points in the
// box: cos(angle - spread), angle the axis' to the eye, spread = t + f (sin f = box radius /
// distance), when angle > spread. By the angle-sum identities, with square roots and no
// acos / asin / cos (8% of the clusters' tests on CesiumMan, measured): t and f are below 90
// degrees, so spread lies in [0, 180) and angle > spread exactly when cos(angle) <
// cos(spread). The float error of either form is some 1e-4 where a cosine nears 1; the 1e-3
// of slack covers it.
float cone_slope_bound(const glm::vec3& axis, float cos_t, const glm::vec3& lo, const glm::vec3& hi,
                       const glm::vec3& eye) {
    const glm::vec3 centre = 0.5f * (lo + hi), to_eye = eye - centre;
    const float radius = 0.5f * glm::length(hi - lo), distance = glm::length(to_eye);
    if (!(cos_t > 0.0f) || !(distance > radius * 1.01f)) return 1.0f;
    const float cos_a = std::max(-1.0f, std::min(1.0f, glm::dot(axis, to_eye) / distance));
    const float ct = std::min(cos_t, 1.0f), st = sine_of(ct);
    const float sf = radius / distance, cf = sine_of(sf);
    const float cos_spread = ct * cf - st * sf, sin_spread = st * cf + ct * sf;
    const float bound =
        cos_a < cos_spread ? cos_a * cos_spread + sine_of(cos_a) * sin_spread : 1.0f;
    return std::min(bound + 1e-3f, 1.0f);
}

constexpr uint32_t kAhead = 8;

// lighting() at least, from each light's least N.L (<= 0 gives that light nothing).
float lighting_from_least(const float* least, const SizeParams& params) {
    float lit = params.ambient;
    for (int l = 0; l < params.light_count; ++l)
        lit += params.light_intensity[l] * std::max(least[l] - 1e-4f, 0.0f);
    return std::min(lit, 1.0f);
}

}  // namespace

float normal_cone_slope_bound(const float* normals, const uint32_t* vertices, uint32_t count,
                              const glm::vec3& lo, const glm::vec3& hi, const glm::vec3& eye) {
    glm::vec3 axis(0.0f);
    for (uint32_t j = 0; j < count; ++j) {
        const glm::vec3 n = normal(normals, vertices[j]);
        const float len = glm::length(n);
        if (!(len > 0.0f)) return 1.0f;
        axis += n / len;
    }
    const float axis_len = glm::length(axis);
    if (!(axis_len > 0.0f)) return 1.0f;
    axis /= axis_len;
    float cos_t = 1.0f;  // the widest normal's angle to the axis
    for (uint32_t j = 0; j < count; ++j) {
        const glm::vec3 n = normal(normals, vertices[j]);
        cos_t = std::min(cos_t, glm::dot(axis, n) / glm::length(n));
    }
    return cone_slope_bound(axis, cos_t, lo, hi, eye);
}

float least_lighting(const float* normals, const uint32_t* vertices, uint32_t count,
                     const SizeParams& params) {
    float least[kMaxLights];
    for (int l = 0; l < params.light_count; ++l) {
        least[l] = 1.0f;
        for (uint32_t j = 0; j < count && least[l] > 0.0f; ++j) {
            const glm::vec3 n = normal(normals, vertices[j]);
            const float len = glm::length(n);
            least[l] = len > 0.0f ? std::min(least[l], glm::dot(n, params.light_direction[l]) / len)
                                  : 0.0f;
        }
    }
    return lighting_from_least(least, params);
}

namespace {

// part_bounds for `Lights` lights: the least N.L of each in a local the compiler keeps in a
// register (a loop over a run-time light count kept them in memory, a chain through store
// forwarding per vertex: 1.3x the time on the horse).
template <int Lights>
void part_bounds_lights(const float* pairs, const uint32_t* vertices, uint32_t count,
                        const SizeParams& params, PartBounds* out) {
    PartBounds b;
    float least[Lights > 0 ? Lights : 1];
    for (int l = 0; l < Lights; ++l) least[l] = 1.0f;
    for (uint32_t j = 0; j < count; ++j) {
        // The vertices lie scattered over the mesh (the horse: 1.5 MB of pairs): fetch ahead.
        if (j + kAhead < count) prefetch_read(pairs + size_t(vertices[j + kAhead]) * 8);
        const float* v = pairs + size_t(vertices[j]) * 8;
        const glm::vec3 p(v[0], v[1], v[2]), n(v[4], v[5], v[6]);
        b.lo = glm::min(b.lo, p);
        b.hi = glm::max(b.hi, p);
        if (!(v[3] > 0.0f)) {  // |n|: no direction, no cone, and no light it is sure to get
            b.cone = false;
            for (int l = 0; l < Lights; ++l) least[l] = std::min(least[l], 0.0f);
            continue;
        }
        const float inv = v[7];  // 1 / |n|, once per vertex (pair_vertices)
        b.axis += n * inv;
        for (int l = 0; l < Lights; ++l)
            least[l] = std::min(least[l], glm::dot(n, params.light_direction[l]) * inv);
    }
    for (int l = 0; l < Lights; ++l) b.least[l] = least[l];
    *out = b;
}

}  // namespace

void part_bounds(const float* pairs, const uint32_t* vertices, uint32_t count,
                 const SizeParams& params, PartBounds* out) {
    static_assert(kMaxLights == 4, "one instance per light count");
    switch (params.light_count) {
        case 0:
            return part_bounds_lights<0>(pairs, vertices, count, params, out);
        case 1:
            return part_bounds_lights<1>(pairs, vertices, count, params, out);
        case 2:
            return part_bounds_lights<2>(pairs, vertices, count, params, out);
        case 3:
            return part_bounds_lights<3>(pairs, vertices, count, params, out);
        case 4:
            return part_bounds_lights<4>(pairs, vertices, count, params, out);
        default:
            return part_bounds_lights<0>(pairs, vertices, count, params, out);
    }
}

float part_least_lighting(const PartBounds& b, const SizeParams& params) {
    return lighting_from_least(b.least, params);
}

PartFacing part_facing(const float* pairs, const uint32_t* vertices, uint32_t count,
                       const PartBounds& b, const glm::vec3& eye, bool cone_wanted) {
    const float scale = glm::length(eye - 0.5f * (b.lo + b.hi)) + glm::length(b.hi - b.lo);
    const float axis_len = glm::length(b.axis);
    cone_wanted = cone_wanted && b.cone && axis_len > 0.0f;
    const glm::vec3 axis = cone_wanted ? b.axis / axis_len : glm::vec3(0.0f);
    PartFacing f;
    float cos_t = 1.0f;
    for (uint32_t j = 0; j < count; ++j) {
        const float* v = pairs + size_t(vertices[j]) * 8;
        const glm::vec3 n(v[4], v[5], v[6]);
        const float len = v[3];  // |n| (pair_vertices)
        if (f.away) {            // faces_away: n . (eye - the box corner nearest along n) < 0
            const glm::vec3 nearest(n.x >= 0.0f ? b.lo.x : b.hi.x, n.y >= 0.0f ? b.lo.y : b.hi.y,
                                    n.z >= 0.0f ? b.lo.z : b.hi.z);
            f.away = glm::dot(n, eye - nearest) < -1e-5f * len * scale;
        }
        if (cone_wanted) cos_t = std::min(cos_t, glm::dot(axis, n) * v[7]);  // v[7]: 1 / |n|
    }
    if (cone_wanted) f.slope = cone_slope_bound(axis, cos_t, b.lo, b.hi, eye);
    return f;
}

InkBound::InkBound(const SizeParams& params) {
    const InkTable table(params);
    from[InkTable::kSteps + 1] = 0.0f;
    for (int i = InkTable::kSteps; i >= 0; --i) from[i] = std::max(from[i + 1], table.ink[i]);
}

float need_bound(const float* normals, const uint32_t* vertices, uint32_t count,
                 const glm::vec3& lo, const glm::vec3& hi, const SizeParams& params,
                 const InkBound& ink) {
    return normal_cone_slope_bound(normals, vertices, count, lo, hi, params.eye) *
           ink.at(least_lighting(normals, vertices, count, params));
}

}  // namespace stipple
