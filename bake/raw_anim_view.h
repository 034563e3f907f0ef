// anim/ views over a RawScene, so bake-side code (tests, benchmarks, tools) can run the
// runtime's animation jobs on an imported scene without writing and loading a .stip file.
// The views point into the RawScene, which must outlive them and stay unchanged.
#pragma once
#include <vector>

#include "anim/anim.h"
#include "bake/raw_scene.h"

namespace stipple::bake {

struct RawAnimView {
    std::vector<int32_t> parents;
    std::vector<anim::Trs> rest;
    std::vector<anim::Channel> channels;  // all clips' channels, clip after clip
    std::vector<anim::Clip> clips;
    std::vector<anim::MorphTarget> morph_targets;
    anim::Skeleton skeleton = {};
    anim::Morph morph = {};
};

// Fills `view` from `scene` (an animated scene: scene.animated()).
void make_anim_view(const RawScene& scene, RawAnimView* view);

}  // namespace stipple::bake
