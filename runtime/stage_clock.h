// The clock the frame stages are timed with (StageTimes, milliseconds).
#pragma once
#include <chrono>

namespace stipple {

using StageClock = std::chrono::steady_clock;

// Milliseconds since *t; moves *t to now.
inline double ms_since(StageClock::time_point* t) {
    const StageClock::time_point now = StageClock::now();
    const double ms = std::chrono::duration<double, std::milli>(now - *t).count();
    *t = now;
    return ms;
}

}  // namespace stipple
