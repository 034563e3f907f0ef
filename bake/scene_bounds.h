// Framing bounds (issue 7, item 6): the axis-aligned box of the rest pose and of every pose
// each clip passes through, so the player frames the clip it plays, not the rest pose. Stored
// in the asset's BNDS section (docs/format.md); the runtime camera frames their union.
#pragma once
#include <vector>

#include "bake/raw_scene.h"
#include "bake/scene_poser.h"

namespace stipple::bake {

struct SceneBounds {
    float rest[6] = {};        // min xyz, max xyz of the rest pose (static: the mesh)
    std::vector<float> clips;  // 6 per clip
};

using BoundsConfig = PoseSampling;  // bake/scene_poser.h

// Poses the mesh with the runtime's own animation jobs at every sample time of every clip
// (bake/scene_poser.h) and takes the box around all skinned vertices.
SceneBounds compute_scene_bounds(const RawScene& scene, const BoundsConfig& config = {});

}  // namespace stipple::bake
