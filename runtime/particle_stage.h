// View-dependent particles (GI'01) on the point hierarchy, one frame at a time:
//   1. adjust: fold/unfold the persistent active set against the style's criterion
//      (runtime/particle_adjust.h), with fades;
//   2. polygon pass: the frame pipeline's depth pass (runtime/renderer.h), per the style's fill;
//   3. transform/light the listed particles (runtime/particle_transform.h);
//   4. strokes: the style's rule and screen-space binning (runtime/particle_style.h), drawn as
//      instanced brush quads (runtime/particle_renderer.h).
// Memory is taken at init from the asset's point count; a frame allocates nothing.
#pragma once
#include <cstdint>

#include "runtime/asset.h"
#include "runtime/particle_adjust.h"
#include "runtime/particle_renderer.h"
#include "runtime/particle_style.h"
#include "runtime/particle_temporary.h"
#include "runtime/particle_transform.h"
#include "runtime/particle_tree.h"
#include "runtime/particle_visibility.h"

namespace stipple {

struct ParticleStageStats {
    uint32_t active = 0, listed = 0;  // particles in the active set; drawn (fades included)
    uint32_t joined = 0, left = 0;    // changes of the active set this frame
    uint32_t asked = 0;               // adjust decisions made
    uint32_t strokes = 0;             // strokes drawn
};

struct ParticleStage {
    bool enabled = false;
    ParticleStyle style;
    Buffer<uint32_t> parent;  // the particle tree's parents (runtime/particle_tree.h)
    // The asset's points continued by temporary particles (runtime/particle_temporary.h):
    // ids [asset points, temporary.count) are slots that hold the run-time refinement's extra
    // points the view needs, generated per frame (not in the tree).
    TemporaryParticles temporary;
    ParticleTree tree;
    ParticleSet set;
    // Stage 1's scratch (a chunk of the particles asked, at most 4,096); stage 3's output
    // (every listed particle).
    ParticleSamples asked, samples;
    // Per particle: opacity of turning away (fades to 0 on the back, like a fold), and the
    // frame it was last drawn in (a particle back in the list starts at its target).
    Buffer<float> facing_alpha;
    Buffer<uint32_t> last_frame;
    uint32_t frame_index = 0;
    Buffer<uint16_t> bins;
    uint32_t bin_count = 0;
    Buffer<StrokeInstance> strokes;
    Buffer<uint32_t> stroke_id;  // the particle each stroke belongs to
    uint32_t stroke_count = 0;
    int width = 0, height = 0;
    ParticleFrame frame;  // this frame's input, while adjusting
    ParticleStageStats stats;
    ParticleVisibility visibility;  // off unless enabled (runtime/particle_visibility.h)
    ParticleRenderer renderer;
};

// Builds the particle tree from the asset's points (parents by particle_parents over the bind
// pose, or the asset's PTRE), with tree_points - the asset's points slots of temporary
// particles generated per view (GI'01 §5; none when tree_points <= the asset's points; ids
// tree_points in all), and takes every buffer for `style` and an image of width x height. Fails
// with out_of_memory, or invalid_argument for a style whose values are out of range. list_points:
// the most particles listed (drawn, fades included) at once, the per-frame budget that sizes stage
// 1's list, stage 3's samples and stage 4's strokes (0: every id). An id costs about 46 bytes, a
// listed particle about 106 more (docs/particles.md).
[[nodiscard]] Status particle_stage_init(ParticleStage* s, const Asset& asset,
                                         const ParticleStyle& style, int width, int height,
                                         uint32_t tree_points = kDefaultParticleTreePoints,
                                         uint32_t list_points = 0);
[[nodiscard]] Status particle_stage_init_gl(ParticleStage* s, const GlApi& gl);

// Stages 1, 3 and the CPU half of 4 for this frame's posed mesh and camera: the three calls
// below in order (separate for the benchmarks).
void particle_stage_update(ParticleStage* s, const ParticleFrame& frame);
void particle_stage_adjust(ParticleStage* s, const ParticleFrame& frame);  // stage 1
// Stage 1 in its three parts (particle_stage_adjust runs them in order): the baked tree's
// folds and unfolds, the temporary particles this view needs (runtime/particle_temporary.h),
// and the merge with every member's fade and the release of faded-out slots.
void particle_stage_adjust_tree(ParticleStage* s, const ParticleFrame& frame);
void particle_stage_adjust_temporaries(ParticleStage* s);
void particle_stage_adjust_finish(ParticleStage* s);
void particle_stage_transform(ParticleStage* s);      // stage 3
void particle_stage_build_strokes(ParticleStage* s);  // stage 4, CPU

// The GPU half of stage 4: draws the strokes into `framebuffer`, hidden by `depth_texture`.
void particle_stage_draw(ParticleStage* s, GLuint framebuffer, GLuint depth_texture);

// Opt-in, after particle_stage_init: strokes the polygon pass hides fade out and in instead of
// popping (runtime/particle_visibility.h). Takes its memory now; the frame pipeline must have
// FrameConfig::depth_readback, else frames draw as without. Fails with out_of_memory.
[[nodiscard]] Status particle_stage_enable_visibility_fades(ParticleStage* s);

void particle_stage_destroy(ParticleStage* s);

}  // namespace stipple
