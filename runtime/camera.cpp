#include "runtime/camera.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace stipple {
namespace {

// The box to frame: the union of the framed clips' boxes, else the rest pose's.
void framed_box(const Asset& a, const FrameConfig& c, const float* posed, glm::vec3* lo,
                glm::vec3* hi) {
    *lo = glm::vec3(1e30f);
    *hi = glm::vec3(-1e30f);
    for (int clip : {c.frame_clip, c.frame_blend_clip}) {
        if (!a.bounds.present || clip < 0 || uint32_t(clip) >= a.clip_count) continue;
        const float* box = a.bounds.clips + size_t(clip) * 6;
        *lo = glm::min(*lo, glm::vec3(box[0], box[1], box[2]));
        *hi = glm::max(*hi, glm::vec3(box[3], box[4], box[5]));
    }
    if (lo->x > hi->x && a.bounds.present) {  // no clip framed: the rest pose's box
        *lo = glm::vec3(a.bounds.rest[0], a.bounds.rest[1], a.bounds.rest[2]);
        *hi = glm::vec3(a.bounds.rest[3], a.bounds.rest[4], a.bounds.rest[5]);
    }
    if (lo->x <= hi->x) return;
    const float* v = posed ? posed : a.mesh.positions;  // version-2 asset: the mesh itself
    for (uint32_t i = 0; i < a.mesh.vertex_count; ++i) {
        const glm::vec3 p(v[i * 3], v[i * 3 + 1], v[i * 3 + 2]);
        *lo = glm::min(*lo, p);
        *hi = glm::max(*hi, p);
    }
}

}  // namespace

OrbitCamera orbit_camera(const Asset& a, const FrameConfig& c, const float* posed_positions) {
    glm::vec3 lo, hi;
    framed_box(a, c, posed_positions, &lo, &hi);
    const glm::vec3 center = 0.5f * (lo + hi);
    const float radius = std::max(0.5f * glm::length(hi - lo), 1e-6f);
    const float aspect = float(c.width) / float(c.height);
    const float half_fov = glm::radians(c.fov_degrees) * 0.5f;
    const float half_fov_min = aspect < 1.0f ? std::atan(std::tan(half_fov) * aspect) : half_fov;
    const float distance = radius / std::sin(half_fov_min);
    // resolve_frame_config keeps the pitch in [-90, 90].
    const float yaw = glm::radians(c.yaw_degrees), pitch = glm::radians(c.pitch_degrees);
    const glm::vec3 dir(std::sin(yaw) * std::cos(pitch), std::sin(pitch),
                        std::cos(yaw) * std::cos(pitch));
    // Screen up = d(dir)/d(pitch): perpendicular to the view direction at every pitch, +Y at
    // pitch 0; looking straight down (pitch 90) the side away from the camera's heading is
    // up, as if the camera had tilted over. lookAt never gets an up parallel to the view.
    const glm::vec3 up(-std::sin(yaw) * std::sin(pitch), std::cos(pitch),
                       -std::cos(yaw) * std::sin(pitch));
    OrbitCamera cam;
    cam.eye = center + dir * distance;
    cam.view = glm::lookAt(cam.eye, center, up);
    const float zoomed_half_fov = std::atan(std::tan(half_fov) / c.zoom);
    const float near_plane = std::max(distance - 3.0f * radius, 0.02f * distance);
    cam.projection =
        glm::perspective(2.0f * zoomed_half_fov, aspect, near_plane, distance + 3.0f * radius);
    return cam;
}

}  // namespace stipple
