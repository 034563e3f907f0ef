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
// the depth copy for particle_visible_strokes when `depth_readback` (turned on by
// particle_fades: the visibility fades read the depth back every frame).
void particle_style_frame_config(const ParticleStyle& style, FrameConfig* config);

// The pipeline's particle stage for config.particle_style (resolved): the particle tree at
// config.particle_budget particles (runtime/particle_temporary.h), and visibility fades when
// config.particle_fades. Takes all its memory now. Fails as particle_stage_init does.
[[nodiscard]] Status pipeline_particle_init(ParticleStage* s, const Asset& asset,
                                            const FrameConfig& config);

// Poses and updates the pipeline (pipeline_update), draws the polygon pass, then runs the
// particle stage over it (with visibility fades when enabled and the pipeline has
// depth_readback: the pass's depth is read back before the strokes) and draws its strokes. Stage
// times go to `times` (strokes: stages 1, 3 and 4's CPU half; draw: the polygon pass and the
// strokes).
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
// it). With visibility fades (runtime/particle_visibility.h) the strokes were drawn untested,
// their visibility in their opacity, so all inside the image count. Writes at most
// `capacity`, returns the count.
uint32_t particle_visible_strokes(const Pipeline& p, const ParticleStage& s, const float* depth,
                                  VisibleStroke* out, uint32_t capacity);

}  // namespace stipple
