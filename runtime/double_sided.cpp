#include "runtime/double_sided.h"

namespace stipple {

uint32_t double_sided_point_flags(uint32_t count, const uint32_t* host_triangle,
                                  const uint8_t* triangle_double_sided, uint8_t* out_flags) {
    uint32_t flagged = 0;
    for (uint32_t i = 0; i < count; ++i) {
        out_flags[i] = triangle_double_sided ? triangle_double_sided[host_triangle[i]] : 0;
        flagged += out_flags[i];
    }
    return flagged;
}

namespace {

inline uint32_t face_point(const float* positions, float* normals, const glm::vec3& eye,
                           uint32_t i) {
    const float* p = positions + size_t(i) * 3;
    float* n = normals + size_t(i) * 3;
    const float facing = n[0] * (eye.x - p[0]) + n[1] * (eye.y - p[1]) + n[2] * (eye.z - p[2]);
    if (facing >= 0.0f) return 0;
    n[0] = -n[0];
    n[1] = -n[1];
    n[2] = -n[2];
    return 1;
}

}  // namespace

uint32_t face_double_sided_points(uint32_t count, const uint8_t* flags, const float* positions,
                                  float* normals, const glm::vec3& eye) {
    if (!flags) return 0;
    uint32_t turned = 0;
    for (uint32_t i = 0; i < count; ++i)
        if (flags[i]) turned += face_point(positions, normals, eye, i);
    return turned;
}

uint32_t face_listed_double_sided_points(const uint32_t* list, uint32_t list_count,
                                         const uint8_t* flags, const float* positions,
                                         float* normals, const glm::vec3& eye) {
    if (!flags) return 0;
    uint32_t turned = 0;
    for (uint32_t j = 0; j < list_count; ++j)
        if (flags[list[j]]) turned += face_point(positions, normals, eye, list[j]);
    return turned;
}

}  // namespace stipple
