// stipple-play's --help text: every default and range from the frame-settings table
// (runtime/frame_config.h) and the resolved zero config, never from literals.
#pragma once
#include <string>

namespace stipple::play {

std::string usage();

}  // namespace stipple::play
