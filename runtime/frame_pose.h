// Posing the mesh for a frame: sample the clip (and the blend clip), blend, local-to-model,
// joint matrices, morph, skin (anim/'s jobs), into the pipeline's vertex buffers.
#pragma once
#include <cassert>

#include "runtime/frame_pipeline.h"
#include "runtime/stage_clock.h"

namespace stipple {

// The jobs of a frame run on spans pipeline_init sized from the asset's counts, and the asset
// passed load validation, so a job that fails its own validation is a bug in the pipeline,
// not bad input. Debug builds stop on it; release builds skip that stage (its output keeps
// the previous frame's values) instead of failing a frame that has no way to report it.
inline void expect_ran(bool ran) {
    assert(ran && "a frame stage's job failed validation");
    (void)ran;
}

// The stages after the points: silhouette and crease lines (thesis §3.2, §8.2) and the
// paintstrokes (GI'98), for the CPU and the GPU path alike; times from *clock.
void pipeline_line_and_stroke_stages(Pipeline* p, StageTimes* t, StageClock::time_point* clock);

// Samples (and blends) the pose, then morphs and skins the mesh into
// p->vertex_positions/normals; static meshes are copied. Adds the sample and skin times to
// `t` (when not null), measured from *clock, which it moves on.
void pose_mesh(Pipeline* p, const AnimationState& state, StageTimes* t,
               StageClock::time_point* clock);

}  // namespace stipple
