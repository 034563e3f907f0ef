#pragma once
// What the in-process A/B tools (bench/ab_kernels, bench/ab_select) share: the asset from the
// command line, a 1280x720 headless context and the frame configuration they run pipelines in.
#include <cstdio>

#include "bench/bench_setup.h"
#include "runtime/frame_pipeline.h"

namespace stipple::bench {

// Loads argv[1] into *asset; prints `usage` and returns false without one.
inline bool ab_load(int argc, char** argv, const char* usage, Asset* asset) {
    if (argc >= 2 && load_asset_file(argv[1], asset).ok()) return true;
    std::fprintf(stderr, "usage: %s\n", usage);
    return false;
}

inline bool ab_context(HeadlessGl* context) {
    platform::HeadlessConfig hc;
    hc.width = 1280;
    hc.height = 720;
    return headless_gl(context, hc);
}

inline FrameConfig ab_config() {
    FrameConfig config;
    config.width = 1280;
    config.height = 720;
    config.relevance_update = true;
    return config;
}

}  // namespace stipple::bench
