#include "runtime/silhouette.h"

#include <cstring>

#include "runtime/asset_format.h"
#include "runtime/point_simd.h"

namespace stipple {

void triangle_facing(uint32_t triangle_count, const uint32_t* indices, const float* positions,
                     const glm::vec3& eye, uint8_t* front, bool padded) {
    // Nearly edge-on back faces (within about 0.9 degrees: cos < 1/64) are marked
    // kFacingEdgeOn: the depth pass keeps them (runtime/renderer_front.cpp), since the GPU's
    // snapped vertices can still turn them toward the eye by a sub-pixel area.
    constexpr float kEdgeOn2 = 1.0f / (64.0f * 64.0f);
    uint32_t t = 0;  // runtime/point_simd.h: the same flags 8 triangles at a time
    if (padded && has_avx2(point_simd()))
        t = triangle_facing_avx2(indices, positions, &eye.x, triangle_count, front);
    for (; t < triangle_count; ++t) {
        const uint32_t* tri = indices + size_t(t) * 3;
        const float* a = positions + size_t(tri[0]) * 3;
        const float* b = positions + size_t(tri[1]) * 3;
        const float* c = positions + size_t(tri[2]) * 3;
        const float ux = b[0] - a[0], uy = b[1] - a[1], uz = b[2] - a[2];
        const float vx = c[0] - a[0], vy = c[1] - a[1], vz = c[2] - a[2];
        const float nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
        const float ex = eye.x - a[0], ey = eye.y - a[1], ez = eye.z - a[2];
        const float d = nx * ex + ny * ey + nz * ez;
        // Without branches: the facing of consecutive triangles is not predictable (2.3x
        // slower with a branch on the horse).
        const float n2 = nx * nx + ny * ny + nz * nz, e2 = ex * ex + ey * ey + ez * ez;
        const uint32_t is_front = d > 0.0f, edge_on = d * d <= kEdgeOn2 * n2 * e2;
        front[t] = uint8_t(is_front * kFacingFront + (edge_on & (is_front ^ 1u)) * kFacingEdgeOn);
    }
}

uint32_t silhouette_lines(const EdgesView& edges, const uint8_t* front, const float* positions,
                          float* out_lines) {
    uint32_t count = 0;
    for (uint32_t i = 0; i < edges.edge_count; ++i) {
        const uint32_t* e = edges.edges + size_t(i) * 4;
        const bool f0 = front[e[2]] == kFacingFront;
        const bool f1 = e[3] != format::kNoFace && front[e[3]] == kFacingFront;
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
        const bool f0 = front[e[2]] == kFacingFront;
        const bool f1 = e[3] != format::kNoFace && front[e[3]] == kFacingFront;
        if (!f0 && !f1) continue;  // both faces turned away: hidden behind the body
        std::memcpy(out_lines + size_t(count) * 6, positions + size_t(e[0]) * 3, 12);
        std::memcpy(out_lines + size_t(count) * 6 + 3, positions + size_t(e[1]) * 3, 12);
        ++count;
    }
    return count;
}

}  // namespace stipple
