// Output buffers for the run-time refinement's extra points (runtime/point_refinement.h), owned
// by a test: `out` points into them.
#pragma once
#include <cstdint>
#include <vector>

#include "runtime/point_refinement.h"

namespace stipple::test {

struct RefinedPointsBuffer {
    std::vector<float> positions, normals, radius;
    std::vector<uint32_t> triangle, index;
    RefinedPoints out;
    RefinementStats stats;
    explicit RefinedPointsBuffer(uint32_t capacity)
        : positions(size_t(capacity) * 3),
          normals(size_t(capacity) * 3),
          radius(capacity),
          triangle(capacity),
          index(capacity) {
        out.capacity = capacity;
        out.positions = positions.data();
        out.normals = normals.data();
        out.radius = radius.data();
        out.triangle = triangle.data();
        out.index = index.data();
    }
};

}  // namespace stipple::test
