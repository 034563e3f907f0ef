// A frame of view-dependent particles (runtime/particle_stage.h) drawn with a frame pipeline's
// posing, camera and polygon pass (GI'01 §2 stage 2), instead of its stipples.
#pragma once
#include "runtime/frame_pipeline.h"
#include "runtime/particle_stage.h"

namespace stipple {

// What the particle stage reads from the pipeline's last update: the posed mesh, the camera,
// the lights.
ParticleFrame pipeline_particle_input(const Pipeline& p);

// The frame settings a particle style draws with: its background, its fill as the polygon
// pass's paper, no stipples (constant tone 0), no silhouette lines (the strokes draw them), and
// the depth copy for particle_visible_strokes when `depth_readback`.
void particle_style_frame_config(const ParticleStyle& style, FrameConfig* config);

// Poses and updates the pipeline (pipeline_update), draws the polygon pass, then runs the
// particle stage over it and draws its strokes. Stage times go to `times` (strokes: stages
// 1, 3 and 4's CPU half; draw: the polygon pass and the strokes).
void pipeline_particle_frame(Pipeline* p, ParticleStage* s, const AnimationState& state,
                             StageTimes* times);

// A stroke of the last frame as seen (the strokes CSV): particle id, centre in pixels (origin
// top-left), direction (radians), length and width in pixels, and opacity.
struct VisibleStroke {
    uint32_t id;
    float x, y, angle, size, width, alpha;
};

// The strokes the last frame drew where they show: centre inside the image and not hidden by
// the polygon pass (the test the stroke shader makes; `depth` as renderer_read_depth writes
// it). Writes at most `capacity`, returns the count.
uint32_t particle_visible_strokes(const Pipeline& p, const ParticleStage& s, const float* depth,
                                  VisibleStroke* out, uint32_t capacity);

}  // namespace stipple
