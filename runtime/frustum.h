// The view frustum as planes in world space, and the least of a plane's linear function over an
// axis-aligned box: the level of detail's cluster test (runtime/point_clusters_select.cpp) and
// the refinement's (runtime/refinement_cull.cpp) both ask whether a box lies wholly beyond one
// plane, and what its nearest clip w is.
#pragma once
#include <glm/glm.hpp>

namespace stipple {

// a . (x, y, z, 1) > 0 beyond each plane, from the rows of the view-projection: x > w (1 +
// margin.x), x < -w (1 + margin.x), the same for y, then z > w and z < -w. `w` is clip w's row.
struct Frustum {
    glm::vec4 plane[6], w;
};

inline Frustum frustum_planes(const glm::mat4& view_projection, const glm::vec2& margin) {
    const glm::mat4 t = glm::transpose(view_projection);  // t[r]: row r
    Frustum f;
    f.w = t[3];
    f.plane[0] = t[0] - (1.0f + margin.x) * t[3];
    f.plane[1] = -t[0] - (1.0f + margin.x) * t[3];
    f.plane[2] = t[1] - (1.0f + margin.y) * t[3];
    f.plane[3] = -t[1] - (1.0f + margin.y) * t[3];
    f.plane[4] = t[2] - t[3];
    f.plane[5] = -t[2] - t[3];
    return f;
}

// The least of a . (p, 1) over the box [lo, hi]: at its centre less |a| . half its extent (a
// linear function's least over a box; the least over its 8 corners, up to rounding).
inline float least_over(const glm::vec4& a, const glm::vec3& lo, const glm::vec3& hi) {
    const glm::vec3 centre = 0.5f * (lo + hi), half = 0.5f * (hi - lo);
    return glm::dot(glm::vec3(a), centre) + a.w - glm::dot(glm::abs(glm::vec3(a)), half);
}

}  // namespace stipple
