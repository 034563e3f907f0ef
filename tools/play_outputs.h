// stipple-play's per-frame side outputs: dot lists, object masks and stroke roots (the CSVs
// and PNGs the frame checks read).
#pragma once
#include <cstdint>
#include <string>

#include "runtime/frame_pipeline.h"

namespace stipple::play {

// Writes the dots the last frame shows (pipeline_visible_dots) as CSV: id,x,y,size.
bool write_dots(const Pipeline& p, const float* depth, VisibleDot* scratch,
                const std::string& path);

// Writes the dots the last frame sized but the mesh in front hides (pipeline_hidden_dots) in
// the same CSV form.
bool write_hidden_dots(const Pipeline& p, const float* depth, VisibleDot* scratch,
                       const std::string& path);

// Writes the object mask of the last frame from the mesh pass's depth (bottom row first, 1 =
// background): white where depth < 1, black elsewhere, top row first like the frame PNGs.
// `rgba` is scratch of width * height * 4 bytes.
bool write_mask(const float* depth, int w, int h, uint8_t* rgba, const std::string& path,
                std::string* error);

// Writes every stroke's root as drawn and its host surface point (pipeline_stroke_roots) as
// CSV: stroke,x,y,surface_x,surface_y (pixels, origin top-left). `scratch` holds the asset's
// stroke count.
bool write_roots(const Pipeline& p, StrokeRootSample* scratch, const std::string& path);

// Writes the particle strokes the last frame drew (a particle style, docs/particles.md) as
// CSV: id,x,y,angle,size,width,alpha,visible (the particle id; centre in pixels, origin
// top-left; direction in radians; length and width in pixels; opacity; 1 if the centre passes
// the depth test the stroke shader makes, against `depth`). Nothing is written for stipples.
bool write_strokes(const Pipeline& p, const float* depth, const std::string& path);

}  // namespace stipple::play
