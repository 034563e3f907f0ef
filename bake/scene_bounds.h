// Framing bounds (issue 7, item 6): the axis-aligned box of the rest pose and of every pose
// each clip passes through, so the player frames the clip it plays, not the rest pose. Stored
// in the asset's BNDS section (docs/format.md); the runtime camera frames their union.
#pragma once
#include <vector>

#include "bake/raw_scene.h"

namespace stipple::bake {

struct SceneBounds {
    float rest[6] = {};        // min xyz, max xyz of the rest pose (static: the mesh)
    std::vector<float> clips;  // 6 per clip
};

struct BoundsConfig {
    float samples_per_second = 60.0f;  // uniform samples over [0, duration], plus every key time
    size_t max_samples_per_clip = 20000;
};

// Poses the mesh with the runtime's own animation jobs (anim/: sampling, local-to-model,
// morph targets, LBS skinning, as runtime/frame_pipeline.cpp does with the default skinning)
// at every sample time of every clip and takes the box around all skinned vertices. Samples:
// 0, duration and `samples_per_second` between, merged with every channel's key times (where a
// LINEAR or STEP clip's extremes lie), thinned evenly if there are more than the cap.
SceneBounds compute_scene_bounds(const RawScene& scene, const BoundsConfig& config = {});

}  // namespace stipple::bake
