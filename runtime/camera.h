// The orbit camera: view and projection matrices that frame an asset (FrameConfig's zoom, yaw,
// pitch and field of view). The player uses it for every frame; an application that draws
// into its own frame (runtime/app_frame.h) passes its own matrices and may use this as a
// helper.
#pragma once
#include <glm/glm.hpp>

#include "runtime/asset.h"
#include "runtime/frame_config.h"

namespace stipple {

struct OrbitCamera {
    glm::mat4 view = glm::mat4(1.0f);        // the asset's space to eye space
    glm::mat4 projection = glm::mat4(1.0f);  // eye to clip space (GL conventions)
    glm::vec3 eye{0.0f};                     // in the asset's space
};

// Frames the bounding sphere of what config.frame_clip / frame_blend_clip play (the BNDS
// section's boxes), else the rest pose; for version-2 assets without BNDS the box of
// `posed_positions` (3 floats per mesh vertex, may be null: then the bind-pose mesh). The
// aspect ratio is config.width / config.height; zoom narrows the field of view, so zoom 2 is
// exactly twice as large on screen.
OrbitCamera orbit_camera(const Asset& asset, const FrameConfig& config,
                         const float* posed_positions);

}  // namespace stipple
