// A uniform grid over 3D points, hashed into buckets, for the load-time neighbour searches of
// the run-time refinement (refinement_order, point_triangulation). Built once with counting
// sort: no allocation per cell, and none at all after build().
#pragma once
#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>
#include <memory>

#include "runtime/memory.h"

namespace stipple {

struct SpatialGrid {
    float cell = 1.0f;
    uint32_t mask = 0;              // bucket count - 1
    Buffer<uint32_t> start;         // bucket -> first slot, bucket count + 1
    Buffer<uint32_t> items;         // slot -> point index, sorted by bucket
    Buffer<float> slot_points;      // slot -> its point's 3 floats (a copy, bucket order)
    Buffer<int32_t> slot_cells;     // slot -> its point's cell (3 coordinates)
    const float* points = nullptr;  // 3 floats per point

    // Cell coordinates saturate at +-2^30 (NaN: 0): a far point or a tiny cell must not
    // overflow the float-to-int conversion (undefined) nor near()'s loop counters.
    static int coord(float v) {
        constexpr float kLimit = 1073741824.0f;  // 2^30
        const float f = std::floor(v);
        if (f >= kLimit) return 1 << 30;
        if (f > -kLimit) return int(f);
        return f == f ? -(1 << 30) : 0;
    }
    glm::ivec3 at(const glm::vec3& p) const {
        return glm::ivec3(coord(p.x / cell), coord(p.y / cell), coord(p.z / cell));
    }
    uint32_t bucket(const glm::ivec3& c) const {
        return (uint32_t(c.x) * 73856093u ^ uint32_t(c.y) * 19349663u ^ uint32_t(c.z) * 83492791u) &
               mask;
    }
    glm::vec3 point(uint32_t i) const {
        return glm::vec3(points[i * 3], points[i * 3 + 1], points[i * 3 + 2]);
    }
    glm::vec3 slot_point(uint32_t k) const {
        const float* q = slot_points.get() + size_t(k) * 3;
        return glm::vec3(q[0], q[1], q[2]);
    }
    bool slot_in(uint32_t k, const glm::ivec3& c) const {
        const int32_t* q = slot_cells.get() + size_t(k) * 3;
        return q[0] == c.x && q[1] == c.y && q[2] == c.z;
    }

    // Indexes the points i < n with use[i] > 0 (all if use is null). False if out of memory.
    [[nodiscard]] bool build(const float* p, uint32_t n, float cell_size, const float* use);

    // Calls f(slot) for the points in the cells overlapping the cube of half-size r at p
    // (items[slot] is the point's index, slot_point(slot) its position: contiguous per cell).
    template <typename F>
    void near_slots(const glm::vec3& p, float r, F f) const {
        const glm::ivec3 lo = at(p - glm::vec3(r)), hi = at(p + glm::vec3(r));
        for (int z = lo.z; z <= hi.z; ++z)
            for (int y = lo.y; y <= hi.y; ++y)
                for (int x = lo.x; x <= hi.x; ++x) {
                    const glm::ivec3 c(x, y, z);
                    const uint32_t b = bucket(c);
                    for (uint32_t k = start[b]; k < start[b + 1]; ++k)
                        if (slot_in(k, c)) f(k);
                }
    }
    // Calls f(index) for the same points.
    template <typename F>
    void near(const glm::vec3& p, float r, F f) const {
        near_slots(p, r, [&](uint32_t k) { f(items[k]); });
    }
};

}  // namespace stipple
