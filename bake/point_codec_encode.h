// Encoder of the compact point hierarchy stream (runtime/point_codec.h, format v1).
#pragma once
#include <cstdint>
#include <vector>

#include "bake/point_hierarchy.h"

namespace stipple::bake {

struct EncodedPoints {
    std::vector<uint8_t> bytes;
    uint64_t bit_count = 0;
    float radius_max = 0.0f;
};

EncodedPoints encode_points(const PointHierarchy& points, uint32_t triangle_count);

}  // namespace stipple::bake
