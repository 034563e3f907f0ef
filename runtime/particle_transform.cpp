#include "runtime/particle_transform.h"

#include <cmath>

#include "runtime/stroke_anchor.h"

namespace stipple {

bool particle_samples_init(ParticleSamples* s, uint32_t capacity) {
    *s = ParticleSamples();
    s->id = make_buffer<uint32_t>(capacity);
    s->x = make_buffer<float>(capacity);
    s->y = make_buffer<float>(capacity);
    s->depth = make_buffer<float>(capacity);
    s->radius_px = make_buffer<float>(capacity);
    s->intensity = make_buffer<float>(capacity);
    s->facing = make_buffer<float>(capacity);
    s->angle = make_buffer<float>(capacity);
    s->foreshortening = make_buffer<float>(capacity);
    s->alpha = make_buffer<float>(capacity);
    s->unfolded = make_buffer<uint8_t>(capacity);
    if (!s->id || !s->x || !s->y || !s->depth || !s->radius_px || !s->intensity || !s->facing ||
        !s->angle || !s->foreshortening || !s->alpha || !s->unfolded)
        return false;
    s->capacity = capacity;
    return true;
}

float random_field_angle(uint32_t id) {
    // A 32-bit integer hash (lowbias32) of the id, to an angle.
    uint32_t h = id;
    h ^= h >> 16;
    h *= 0x7feb352du;
    h ^= h >> 15;
    h *= 0x846ca68bu;
    h ^= h >> 16;
    return float(h >> 8) * (6.28318530718f / 16777216.0f);
}

float curvature_field_angle(const PointsView& points, uint32_t id) {
    // Particles past the baked hierarchy (none stored) take the random field too.
    if (!points.curvature_angle || id >= points.curvature_count ||
        points.curvature_confidence[id] < kCurvatureConfident)
        return random_field_angle(id);
    return float(points.curvature_angle[id]) * format::kCurvatureAngleStep;
}

namespace {

glm::vec3 vertex(const float* v, uint32_t i) {
    return glm::vec3(v[size_t(i) * 3], v[size_t(i) * 3 + 1], v[size_t(i) * 3 + 2]);
}

// The particle's frame on its posed host triangle (origin = its position, z = its normal).
SurfaceFrame particle_frame(const ParticleFrame& f, uint32_t id) {
    const PointsView& pts = *f.points;
    const uint32_t* t = f.indices + size_t(pts.host_triangle[id]) * 3;
    return surface_frame(vertex(f.positions, t[0]), vertex(f.positions, t[1]),
                         vertex(f.positions, t[2]), vertex(f.normals, t[0]),
                         vertex(f.normals, t[1]), vertex(f.normals, t[2]), pts.bary_u[id],
                         pts.bary_v[id]);
}

// Clip space to pixels (origin top-left), y down.
glm::vec2 to_pixels(const ParticleFrame& f, const glm::vec4& clip) {
    const float inv_w = 1.0f / clip.w;
    return glm::vec2((clip.x * inv_w * 0.5f + 0.5f) * float(f.width),
                     (0.5f - clip.y * inv_w * 0.5f) * float(f.height));
}

// The screen direction of a surface vector `d` at the particle: the derivative of the
// projection along d (exact for any length of d, no offset point needed).
glm::vec2 screen_direction(const ParticleFrame& f, const glm::vec4& clip, const glm::vec3& d) {
    const glm::vec4 dc = f.view_projection * glm::vec4(d, 0.0f);
    const float inv_w = 1.0f / clip.w;
    const glm::vec2 ndc_d = (glm::vec2(dc) - glm::vec2(clip) * (dc.w * inv_w)) * inv_w;
    return glm::vec2(ndc_d.x * float(f.width), -ndc_d.y * float(f.height));
}

// The field's direction on screen (radians) and how much of it the projection keeps.
float field_angle(const ParticleFrame& f, const SurfaceFrame& s, const glm::vec4& clip, uint32_t id,
                  OrientationField field, float* foreshortening) {
    glm::vec3 d;
    if (field == OrientationField::random || field == OrientationField::curvature) {
        const float a = field == OrientationField::random ? random_field_angle(id)
                                                          : curvature_field_angle(*f.points, id);
        d = std::cos(a) * s.x + std::sin(a) * s.y;
    } else {
        d = s.z;
    }
    const glm::vec2 v = screen_direction(f, clip, d);
    // A unit vector in the image plane projects to focal / w pixels (d is unit length).
    const float full = f.focal_px / clip.w;
    *foreshortening = std::min(glm::length(v) * 0.5f / std::max(full, 1e-20f), 1.0f);
    float angle = std::atan2(v.y, v.x);
    if (field == OrientationField::normal_tangent) angle += 1.57079632679f;
    return angle;
}

}  // namespace

void transform_particles(const ParticleFrame& f, const uint32_t* ids, uint32_t count,
                         const float* alpha, OrientationField field, ParticleSamples* out) {
    if (count > out->capacity) count = out->capacity;
    for (uint32_t k = 0; k < count; ++k) {
        const uint32_t id = ids[k];
        const SurfaceFrame s = particle_frame(f, id);
        const glm::vec4 clip = f.view_projection * glm::vec4(s.origin, 1.0f);
        out->id[k] = id;
        out->alpha[k] = alpha ? alpha[id] : 1.0f;
        const glm::vec3 to_eye = f.eye - s.origin;
        const float distance = glm::length(to_eye);
        out->facing[k] = distance > 0.0f ? glm::dot(s.z, to_eye) / distance : 1.0f;
        out->intensity[k] = f.lights ? lighting(*f.lights, s.z) : 1.0f;
        if (!(clip.w > 1e-6f)) {  // behind the camera
            out->x[k] = out->y[k] = 0.0f;
            out->depth[k] = 2.0f;
            out->radius_px[k] = out->angle[k] = out->foreshortening[k] = 0.0f;
            continue;
        }
        const glm::vec2 px = to_pixels(f, clip);
        out->x[k] = px.x;
        out->y[k] = px.y;
        out->depth[k] = clip.z / clip.w * 0.5f + 0.5f;
        out->radius_px[k] = (f.radius ? f.radius : f.points->radius)[id] * f.focal_px / clip.w;
        out->angle[k] = field_angle(f, s, clip, id, field, &out->foreshortening[k]);
    }
    out->count = count;
}

}  // namespace stipple
