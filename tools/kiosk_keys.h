// The kiosk player's key handler (stipple-play --window, tools/play_window.h): what each key
// does to the player's state, as a pure function with its limits, so it is unit-tested without
// a window (tests/tools/test_kiosk_keys.cpp).
//   space        pause / resume the clock
//   left, right  previous / next clip (wraps over the asset's clips)
//   Shift+left, Shift+right   orbit: yaw -/+ yaw_step degrees (wraps to (-180, 180])
//   up, down     orbit: pitch +/- pitch_step degrees (clamped to the pitch limits)
//   +, -         zoom in / out by zoom_step (clamped to the zoom limits)
//   L            next key-light preset (wraps over light_count)
//   S            save the next frame as a PNG (the player clears `save` once written)
//   Esc          quit
#pragma once
#include "platform/window_context.h"  // Key (no X11 or EGL in the header)
#include "runtime/frame_config.h"

namespace stipple::play {

struct KioskLimits {
    int clip_count = 0;   // the asset's clips; 0: only the rest pose, the clip keys do nothing
    int light_count = 1;  // key-light presets
    float zoom_min = kFrameSettings.zoom.min, zoom_max = kFrameSettings.zoom.max;
    float pitch_min = kFrameSettings.pitch_degrees.min,
          pitch_max = kFrameSettings.pitch_degrees.max;
    float zoom_step = 1.25f;   // factor per + or -
    float yaw_step = 15.0f;    // degrees per Shift+left/right
    float pitch_step = 10.0f;  // degrees per up/down
};

struct KioskState {
    bool paused = false;
    int clip = -1;  // -1: the rest pose
    float zoom = 1.0f, yaw = 0.0f, pitch = 0.0f;
    int light = 0;      // key-light preset index
    bool save = false;  // a PNG of the next frame was asked for
    bool quit = false;
};

// The state after `key` (with Shift held or not). Keys that do nothing return `s` unchanged.
KioskState apply_key(KioskState s, platform::Key key, const KioskLimits& limits,
                     bool shift = false);

}  // namespace stipple::play
