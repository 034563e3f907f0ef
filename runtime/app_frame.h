// Drawing into the application's own frame (issue 8): the application owns the context, the
// camera and the framebuffer; a pipeline poses its character for the application's matrices
// and draws it into the framebuffer bound at the call, depth-tested against the depth the
// application already drew there, so the character stands on its floor and behind its
// pillars. The headless player (pipeline_frame) keeps drawing into the pipeline's own image.
#pragma once
#include <cstdint>
#include <glm/glm.hpp>

#include "runtime/frame_pipeline.h"

namespace stipple {

struct AppView {
    glm::mat4 view = glm::mat4(1.0f);        // world to eye space
    glm::mat4 projection = glm::mat4(1.0f);  // eye to clip space (perspective, GL conventions)
    glm::mat4 model = glm::mat4(1.0f);       // the asset's space to world space
    int viewport[4] = {0, 0, 0, 0};          // x, y, width, height in pixels
    // The framebuffer to draw into: -1, the one bound for drawing at the call; else a GL
    // framebuffer name (0: the default framebuffer). The binding is restored afterwards.
    int64_t framebuffer = -1;
};

// Poses `state`, runs every stage for the application's camera and draws into the framebuffer
// bound for drawing, inside view.viewport:
//   1. the body's depth into the pipeline's own framebuffer (whole-dot visibility, as in
//      pipeline_frame; its size should be the viewport's: FrameConfig width and height);
//   2. into the application's framebuffer, depth-tested (GL_LESS) against what it holds: the
//      body in the paper colour, writing depth (pushed slightly behind its surface, so the
//      ink on it passes); then paintstrokes (writing depth), silhouettes and dots (tested
//      GL_LEQUAL, not writing depth). A dot is drawn whole or not at all against the body and
//      cut per pixel where the application's geometry is nearer.
// Changes no GL state the application can see afterwards: program, vertex array, array
// buffer, draw/read framebuffers, viewport, blend enable and functions, depth test, function
// and mask, colour mask, culling, line width, the active texture unit and unit 0's 2D texture
// are saved and restored (runtime/gl_state.h). The framebuffer's colour and depth are what
// change: the character is in them. Allocates nothing (the GL driver may, once: llvmpipe
// compiles its variants of these passes at the first call).
void pipeline_draw_into(Pipeline* p, const AnimationState& state, const AppView& view,
                        StageTimes* times);

}  // namespace stipple
