#include "tools/kiosk_keys.h"

#include <algorithm>

namespace stipple::play {

namespace {

int wrap_index(int i, int count) {
    return ((i % count) + count) % count;
}

float wrap_degrees(float yaw) {  // to (-180, 180]
    while (yaw > 180.0f) yaw -= 360.0f;
    while (yaw <= -180.0f) yaw += 360.0f;
    return yaw;
}

// Left/right step the clip; from the rest pose (-1) right goes to the first clip and left to
// the last.
int step_clip(int clip, int step, int count) {
    if (count <= 0) return clip;
    if (clip < 0) return step > 0 ? 0 : count - 1;
    return wrap_index(clip + step, count);
}

}  // namespace

KioskState apply_key(KioskState s, platform::Key key, const KioskLimits& limits, bool shift) {
    using platform::Key;
    switch (key) {
        case Key::space:
            s.paused = !s.paused;
            break;
        case Key::left:
        case Key::right: {
            const int step = key == Key::right ? 1 : -1;
            if (shift)
                s.yaw = wrap_degrees(s.yaw + float(step) * limits.yaw_step);
            else
                s.clip = step_clip(s.clip, step, limits.clip_count);
            break;
        }
        case Key::up:
        case Key::down: {
            const float step = key == Key::up ? limits.pitch_step : -limits.pitch_step;
            s.pitch = std::clamp(s.pitch + step, limits.pitch_min, limits.pitch_max);
            break;
        }
        case Key::plus:
            s.zoom = std::clamp(s.zoom * limits.zoom_step, limits.zoom_min, limits.zoom_max);
            break;
        case Key::minus:
            s.zoom = std::clamp(s.zoom / limits.zoom_step, limits.zoom_min, limits.zoom_max);
            break;
        case Key::l:
            if (limits.light_count > 0) s.light = wrap_index(s.light + 1, limits.light_count);
            break;
        case Key::s:
            s.save = true;
            break;
        case Key::escape:
            s.quit = true;
            break;
        case Key::other:
            break;
    }
    return s;
}

}  // namespace stipple::play
