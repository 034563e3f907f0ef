// Internal to platform/: llvmpipe's rasterizer threads for one context's creation
// (HeadlessConfig::raster_threads, WindowConfig::raster_threads). Mesa reads LP_NUM_THREADS once,
// when the display is initialised, so this sets it for the life of the object where a count is
// asked for and the environment has none, and restores the environment after.
#pragma once
#include <cstdio>
#include <cstdlib>

#include "platform/headless_context.h"  // kMaxRasterThreads

namespace stipple::platform {

struct RasterThreads {
    bool set = false;
    explicit RasterThreads(int threads) {
        if (threads < 0 || std::getenv("LP_NUM_THREADS")) return;
        char value[16];
        std::snprintf(value, sizeof(value), "%d",
                      threads < kMaxRasterThreads ? threads : kMaxRasterThreads);
        set = setenv("LP_NUM_THREADS", value, 0) == 0;
    }
    ~RasterThreads() {
        if (set) unsetenv("LP_NUM_THREADS");
    }
    RasterThreads(const RasterThreads&) = delete;
    RasterThreads& operator=(const RasterThreads&) = delete;
};

}  // namespace stipple::platform
