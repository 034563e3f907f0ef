#pragma once
// bench/ab_kernels: the frame state both trees' kernels read.
#include <cstdint>
// Raw frame state, namespace-free; params points at a stipple::SizeParams (same layout both sides).
struct AbState {
    const void* points;  // PointsView
    const void* params;  // SizeParams
    const uint32_t* indices;
    const void* hosts;  // PointHost
    const float* pairs;
    const uint32_t* quads;
    const float* scale;
    const float* fallback;
    const uint32_t* run;
    uint32_t run_count;
    const uint32_t* placed;
    uint32_t placed_count;
    float* positions;
    float* normals;
    float* radius;
    float* size;
};
void old_stages(const AbState& s, int part);
void new_stages(const AbState& s, int part);
