// The paintstroke stage of a frame (GI'98): anchor every stroke to the posed mesh, tessellate
// the ones the LOD keeps in eye space, sort their segments back to front and draw them over the
// depth pass, before the stipples (which are then hidden behind strokes like behind the body).
// Every buffer is taken in stroke_stage_init from the asset's counts and the vertex budget.
#pragma once
#include <cstdint>
#include <glm/glm.hpp>
#include <memory>

#include "runtime/asset.h"
#include "runtime/frame_config.h"
#include "runtime/memory.h"
#include "runtime/paintstroke.h"
#include "runtime/stroke_renderer.h"

namespace stipple {

struct StrokeStage {
    bool enabled = false;  // the asset has strokes and FrameConfig::strokes is on
    TessellationParams params;
    Buffer<StrokePoint> points;  // eye space, per control point of the asset
    Buffer<StrokeVertex> vertices;
    Buffer<uint32_t> indices, sorted_indices;  // 3 per triangle
    Buffer<StrokeSegment> segments;
    Buffer<uint32_t> order, sort_scratch;  // segments, 2 * segments
    StrokeMesh mesh;
    TessellationStats stats;  // of the last frame
    uint32_t strokes_drawn = 0;
    StrokeRenderer renderer;
};

// This frame's camera and what the stage reads from the posed frame.
struct StrokeFrameInput {
    const float* positions = nullptr;  // posed mesh vertices, 3 floats each
    const float* normals = nullptr;
    const glm::mat4* skin_matrices = nullptr;  // posed joints, or null
    const float* point_radius = nullptr;       // the hierarchy's relevance radii (LOD)
    glm::mat4 view = glm::mat4(1.0f);          // posed space to eye space
    glm::mat4 projection = glm::mat4(1.0f);    // eye space to clip space
    float focal_px = 0.0f;                     // pixels per unit at unit distance
    glm::vec3 light_eye{0.0f, 0.0f, 1.0f};     // unit, toward the light
};

// Takes the stage's buffers (none when the asset has no strokes or config.strokes is off),
// from the current allocator (runtime/memory.h). Fails with out_of_memory.
[[nodiscard]] Status stroke_stage_init(StrokeStage* s, const Asset& asset,
                                       const FrameConfig& config);
// Then creates its renderer (when it has buffers) and turns the stage on. Fails with gl_error.
[[nodiscard]] Status stroke_stage_init_gl(StrokeStage* s, const GlApi& gl,
                                          const FrameConfig& config);

// Re-reads the settings pipeline_set_view may change (quality, tolerances, LOD).
void stroke_stage_configure(StrokeStage* s, const FrameConfig& config);

// CPU half: anchors, tessellates and sorts. Allocates nothing. When the vertex budget
// (FrameConfig::stroke_vertex_budget) binds, the stroke that does not fit and every stroke
// after it are left out of this frame (strokes are stored coarse to fine, so what is drawn is
// the coarser part of the fur) and mesh.overflow says so.
void stroke_stage_update(StrokeStage* s, const Asset& asset, const StrokeFrameInput& in,
                         float lod_px);

// GPU half: draws the sorted triangles into the bound framebuffer.
void stroke_stage_draw(StrokeStage* s, const StrokeFrameInput& in);

void stroke_stage_destroy(StrokeStage* s);

}  // namespace stipple
