// Looks (thesis ch. 7-8): one set of style names shared by stipple-play (--style), the C API
// (stipple_player_desc::style, stipple_player_set_style) and the C++ API (FrameConfig::style),
// and the per-frame data the non-classic styles need beyond the classic frame (dot colours,
// the mesh's part colours, crease lines). docs/styles.md describes each look.
//   classic      black dots over a paper depth pass (thesis §3.2), the default.
//   toon         a 2-3 band toon ramp of the lights filled in the part colour (or the fill
//                colour), dots in a darker ink of the same colour (§7.2, the crocodile).
//   colour       dots in the surface colour (LOOK point colours) over the paper (§8.6,
//                pointillism); density still follows the tone alone.
//   transparent  parts flagged transparent (all of the mesh when none is) draw no fill: only
//                their dots and lines, which see through to what lies behind (§7.4).
// Stroke styles (issue 11: painterly-long, painterly-dab, sketch, cartoon, graftals, charcoal,
// two-tone, ink) are appended after `transparent`; kStyleTotal and kStyleNames grow with them.
#pragma once
#include <cstdint>

#include "runtime/asset.h"
#include "runtime/memory.h"
#include "runtime/status.h"

namespace stipple {

enum class Style : int { classic = 0, toon, colour, transparent };
inline constexpr int kStyleTotal = 4;

// "classic", "toon", "colour", "transparent"; "unknown" outside [0, kStyleTotal).
const char* style_name(Style style);
// The style named `name` (exact, lower case; "color" is accepted for "colour"), or -1.
int find_style(const char* name);
// "classic|toon|colour|transparent", for usage lines and one-line errors.
const char* style_name_list();

struct FrameConfig;

// What the styles take at init beyond the classic frame, from the asset's LooksView:
//   vertex_colours  RGBA8 per mesh vertex: the colour of the part of a triangle using it
//                   (alpha 0 when that part is transparent); only when the asset has parts.
//                   A vertex shared by parts takes the last triangle's part: the colours (and
//                   the transparent cut) blend across one triangle at such a border.
//   dot_colours     RGBA8 per drawn dot (point capacity); only when the asset has point or
//                   part colours. Refinement points take their host's colour: on the points'
//                   triangulation the mean of its three baked corners, on the mesh its part's.
//   crease_lines    6 floats per crease edge (LooksView::creases).
struct StyleBuffers {
    Buffer<uint8_t> vertex_colours;
    Buffer<uint8_t> dot_colours;
    Buffer<float> crease_lines;
    bool transparent_parts = false;  // some part has kPartTransparent
    uint32_t creases_drawn = 0;      // crease lines of the last frame
};

// Takes the buffers above for `asset` with `point_capacity` drawable points and fills the
// vertex colours. out_of_memory on failure.
[[nodiscard]] Status style_init(StyleBuffers* s, const Asset& asset, uint32_t point_capacity);

// RGBA8 base colour of baked point i: its LOOK colour, else its part's, else `fill`.
void point_base_colour(const LooksView& looks, const uint32_t* host_triangle, uint32_t i,
                       const float* fill, uint8_t* rgba);

// The colour style's dot colour for a surface colour (thesis §8.6): its hue, with its luminance
// (Rec. 709 weights) capped at kColourDotLuminance so light surfaces still show as dots on the
// white paper (a white surface gets mid-grey dots). In place, RGB in [0, 1].
inline constexpr float kColourDotLuminance = 0.5f;
void colour_dot_rgb(float* rgb);

// Where the frame's refinement points live (RefinedPoints::triangle of point_refinement.h).
struct RefinedHosts {
    uint32_t count = 0;
    const uint32_t* triangle = nullptr;  // per extra point: a triangle of `indices`
    const uint32_t* indices = nullptr;   // 3 per triangle
    bool on_points = false;              // indices name baked points (else mesh vertices)
};

// Fills dot_colours for the dots a frame draws: point j of the baked points and then the
// refinement's extra points goes to slot `drawn` when size[j] > 0, in order (the order of the
// pipeline's compaction). toon darkens the part colour by toon_ink; colour uses the point
// colour. Nothing when the style needs no per-dot colour or the buffer is absent. Returns
// whether the dots carry colours this frame.
bool style_dot_colours(StyleBuffers* s, const Asset& asset, const FrameConfig& config,
                       const float* size, const RefinedHosts& refined);

}  // namespace stipple
