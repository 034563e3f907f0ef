#include "bake/scene_bounds.h"

#include <algorithm>
#include <cmath>

namespace stipple::bake {

namespace {

void box_of(const float* positions, size_t vertex_count, float* box) {
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < vertex_count; ++i)
        for (int k = 0; k < 3; ++k) {
            lo[k] = std::min(lo[k], positions[i * 3 + size_t(k)]);
            hi[k] = std::max(hi[k], positions[i * 3 + size_t(k)]);
        }
    for (int k = 0; k < 3; ++k) {
        box[k] = vertex_count ? lo[k] : 0.0f;
        box[k + 3] = vertex_count ? hi[k] : 0.0f;
    }
}

void grow(float* box, const float* other) {
    for (int k = 0; k < 3; ++k) {
        box[k] = std::min(box[k], other[k]);
        box[k + 3] = std::max(box[k + 3], other[k + 3]);
    }
}

}  // namespace

SceneBounds compute_scene_bounds(const RawScene& scene, const BoundsConfig& config) {
    SceneBounds out;
    std::vector<uint8_t> sampled(scene.clips.size(), 0);
    out.clips.assign(scene.clips.size() * 6, 0.0f);
    for_each_pose(scene, config, [&](int clip, const float* positions) {
        float pose[6];
        box_of(positions, scene.vertex_count(), pose);
        if (clip < 0) {
            std::copy(pose, pose + 6, out.rest);
            return;
        }
        float* box = out.clips.data() + size_t(clip) * 6;
        if (sampled[size_t(clip)])
            grow(box, pose);
        else
            std::copy(pose, pose + 6, box);
        sampled[size_t(clip)] = 1;
    });
    for (size_t c = 0; c < scene.clips.size(); ++c)  // a clip without samples: the rest box
        if (!sampled[c]) std::copy(out.rest, out.rest + 6, out.clips.begin() + long(c) * 6);
    return out;
}

}  // namespace stipple::bake
