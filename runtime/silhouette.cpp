#include "runtime/silhouette.h"

#include <cstring>
#include <glm/gtc/type_ptr.hpp>

#include "runtime/asset_format.h"

namespace stipple {

void triangle_facing(uint32_t triangle_count, const uint32_t* indices, const float* positions,
                     const glm::vec3& eye, uint8_t* front) {
    for (uint32_t t = 0; t < triangle_count; ++t) {
        const uint32_t* tri = indices + size_t(t) * 3;
        const glm::vec3 a = glm::make_vec3(positions + size_t(tri[0]) * 3);
        const glm::vec3 b = glm::make_vec3(positions + size_t(tri[1]) * 3);
        const glm::vec3 c = glm::make_vec3(positions + size_t(tri[2]) * 3);
        front[t] = glm::dot(glm::cross(b - a, c - a), eye - a) > 0.0f;
    }
}

uint32_t silhouette_lines(const EdgesView& edges, const uint8_t* front, const float* positions,
                          float* out_lines) {
    uint32_t count = 0;
    for (uint32_t i = 0; i < edges.edge_count; ++i) {
        const uint32_t* e = edges.edges + size_t(i) * 4;
        const bool f0 = front[e[2]];
        const bool f1 = e[3] == format::kNoFace ? false : front[e[3]];
        // The rim of a double-sided open surface is seen from both sides: always an outline.
        const bool rim = edges.double_sided_boundary && edges.double_sided_boundary[i];
        if (f0 == f1 && !rim) continue;
        std::memcpy(out_lines + size_t(count) * 6, positions + size_t(e[0]) * 3, 12);
        std::memcpy(out_lines + size_t(count) * 6 + 3, positions + size_t(e[1]) * 3, 12);
        ++count;
    }
    return count;
}

uint32_t crease_lines(const LooksView& looks, const uint8_t* front, const float* positions,
                      float* out_lines) {
    uint32_t count = 0;
    for (uint32_t i = 0; i < looks.crease_count; ++i) {
        const uint32_t* e = looks.creases + size_t(i) * 4;
        const bool f0 = front[e[2]];
        const bool f1 = e[3] != format::kNoFace && front[e[3]];
        if (!f0 && !f1) continue;  // both faces turned away: hidden behind the body
        std::memcpy(out_lines + size_t(count) * 6, positions + size_t(e[0]) * 3, 12);
        std::memcpy(out_lines + size_t(count) * 6 + 3, positions + size_t(e[1]) * 3, 12);
        ++count;
    }
    return count;
}

}  // namespace stipple
