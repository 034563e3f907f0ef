// The mesh posed with the runtime's own animation jobs (anim/: sampling, local-to-model,
// morph targets, LBS skinning, as runtime/frame_pipeline.cpp does with the default skinning),
// for bake-side measures that must hold in every pose a clip passes through: the clips'
// framing bounds (bake/scene_bounds.h) and the occluder's deviation (bake/occluder.h).
#pragma once
#include <functional>
#include <vector>

#include "anim/anim.h"
#include "bake/raw_scene.h"

namespace stipple::bake {

struct PoseSampling {
    float samples_per_second = 60.0f;  // uniform samples over [0, duration], plus key times
    size_t max_samples_per_clip = 20000;
};

// The sample times of `clip`: 0, duration and `samples_per_second` between, merged with every
// channel's key times (where a LINEAR or STEP clip's extremes lie), thinned evenly to the cap.
std::vector<float> pose_sample_times(const anim::Clip& clip, const PoseSampling& sampling);

// Calls `visit(clip, positions)` with the skinned (and morphed) vertex positions, 3 floats per
// vertex: first the rest pose (clip -1), then every sample time of every clip. A static scene
// has its rest pose only. Posing allocates nothing after the first call.
void for_each_pose(const RawScene& scene, const PoseSampling& sampling,
                   const std::function<void(int clip, const float* positions)>& visit);

}  // namespace stipple::bake
