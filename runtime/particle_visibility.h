// Visibility fades for view-dependent particles (GI'01 §5's fades, applied to what the polygon
// pass hides): instead of the stroke shader's all-or-nothing depth test of each stroke's centre,
// the polygon pass's depth is read back once per frame, each stroke's centre is tested on the
// CPU, and a per-particle visibility opacity moves towards 1 (in view) or 0 (hidden) by one
// fade step per frame. A stroke that another part of the body covers fades out over a few
// frames, one that comes out from behind fades in; the strokes are then drawn without the
// shader's test. Costs a depth readback per frame (a GPU round trip), so it is opt-in
// (particle_stage_enable_visibility_fades) and needs FrameConfig::depth_readback.
// All memory is taken when enabled; a frame allocates nothing.
#pragma once
#include <cstdint>

#include "runtime/memory.h"
#include "runtime/particle_style.h"
#include "runtime/status.h"

namespace stipple {

struct ParticleVisibility {
    bool enabled = false;
    int width = 0, height = 0;
    float step = 0.25f;            // opacity gained or lost per frame
    Buffer<float> scratch, depth;  // the readback (RGBA float) and its depth, per pixel
    Buffer<float> alpha;           // per particle: visibility opacity in [0, 1]
    Buffer<uint32_t> last_frame;   // per particle: the frame its stroke was last drawn in
    uint32_t frame_index = 2;
    bool applied = false;  // the last frame's strokes carry their visibility (no shader test)
    // Of the last frame: strokes hidden at their centre, and strokes dropped (faded out).
    uint32_t hidden = 0, dropped = 0;
};

// Takes the memory for `particles` particles and a width x height depth readback.
// fade_frames in [1, 255]. Fails with out_of_memory or invalid_argument.
[[nodiscard]] Status particle_visibility_init(ParticleVisibility* v, uint32_t particles, int width,
                                              int height, int fade_frames);

// True when the stroke's centre is hidden by the polygon pass at `depth` (window depth per
// pixel, bottom row first, as renderer_read_depth writes it): the stroke shader's test.
bool stroke_hidden(const StrokeInstance& s, const float* depth, int width, int height);

// One frame: advances each stroke's particle's visibility fade against `v->depth` (already
// read back), multiplies the stroke's opacity by it and drops strokes that have faded out.
// strokes/ids[0 .. *count) are compacted in place.
void particle_visibility_apply(ParticleVisibility* v, StrokeInstance* strokes, uint32_t* ids,
                               uint32_t* count);

}  // namespace stipple
