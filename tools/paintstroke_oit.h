// The error of runtime/stroke_renderer.h's compositing (segments sorted back to front on the
// CPU, drawn with alpha blending and depth writes) against exact per-pixel sorting: depth
// peeling (layer k holds each pixel's k-th nearest fragment; layers are taken until one is
// empty, then composited back to front). For stipple-paintstroke-table.
#pragma once
#include <cstdint>
#include <vector>

#include "bench/paintstroke_scene.h"
#include "runtime/stroke_renderer.h"

namespace stipple::bench {

struct OitResult {
    double frames = 0, covered_px = 0;
    double abs_sum = 0;      // over covered pixels and RGB channels, in 1/255
    int max_diff = 0;        // largest channel difference, 1/255
    double bad_px = 0;       // covered pixels off by more than 8/255
    int max_layers = 0;      // deepest peel needed
    double mean_layers = 0;  // layers per frame
    // ms per frame (glFinish'd): the sorted draw (upload + one pass), and the peel (upload +
    // one pass per layer + its readback and CPU compositing)
    double sorted_ms = 0, peeled_ms = 0;
    // The same sorted order drawn without depth test and writes (every fragment blended):
    // mean difference from the peel, and covered pixels off by more than 8/255.
    double nowrite_abs_sum = 0, nowrite_covered_px = 0, nowrite_bad_px = 0;
};

// Draws `frames` frames of `scale` of a semi-transparent copy of the scene (opacity
// `opacity`) at paintstroke quality `quality` both ways. `renderer`'s buffers are reused;
// the peeling program and layer textures are made here and released. `images` (when not
// empty) receives the two frame-0 images (bottom-up RGBA), sorted then peeled.
bool measure_oit(const GlApi& gl, StrokeRenderer* renderer, int width, int height, int scale,
                 int frames, int quality, float opacity, OitResult* out,
                 std::vector<uint8_t>* sorted_image, std::vector<uint8_t>* peeled_image);

}  // namespace stipple::bench
