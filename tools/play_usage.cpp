#include "tools/play_usage.h"

#include <cmath>
#include <cstdio>

#include "platform/headless_context.h"
#include "runtime/frame_config.h"
#include "tools/play_window.h"

namespace stipple::play {
namespace {

const FrameSettings& kLimits = kFrameSettings;
// The resolved defaults, made on first use: usage() runs while other files' statics are
// initialised (stipple-play's parser), so this must not be a namespace-scope object.
const FrameConfig& defaults() {
    static const FrameConfig d = default_frame_config();
    return d;
}

std::string g(double v) {
    char text[32];
    std::snprintf(text, sizeof(text), "%g", v);
    return text;
}

std::string range(const stipple::Setting<float>& s) {
    return "in [" + g(s.min) + ", " + g(s.max) + "]";
}

unsigned rgb_of(const float* c) {
    unsigned rgb = 0;
    for (int k = 0; k < 3; ++k) rgb |= unsigned(std::lround(c[k] * 255.0f)) << (16 - 8 * k);
    return rgb;
}

std::string background_default() {
    char text[8];
    std::snprintf(text, sizeof(text), "%06x", rgb_of(defaults().background));
    return text;
}

// The view: what is played and how the camera sees it.
std::string view_usage() {
    return "usage: stipple-play ASSET.stip --out DIR [options]\n"
           "       stipple-play ASSET.stip --window [options]   (a kiosk window; keys below)\n"
           "  --out DIR               where frame_NNNN.png and anim.png go (created if missing)\n"
           "  --clip NAME|INDEX       animation clip (default 0; the rest pose if the asset has "
           "none)\n"
           "  --blend CLIP2:W         layer a second clip with weight W in [0,1] (same clock)\n"
           "  --crossfade CLIP2:S     fade from --clip to CLIP2 over S in [0.001, 10000] seconds,\n"
           "                          starting at --time (default: no second clip)\n"
           "  --skinning lbs|dqs      linear blend (default) or dual-quaternion skinning\n"
           "  --path cpu|gpu          where place, relevance and size run (default cpu; gpu: a\n"
           "                          GLES 3 vertex shader with transform feedback, no refinement\n"
           "                          past the baked points, no --dots-out; docs/gpu-path.md)\n"
           "  --frames N              frames to render (default 30, in [1, 100000])\n"
           "  --fps F                 frames per second of animation time (default 30, in [0.001, "
           "1000])\n"
           "  --time T0               start time in seconds (default 0, |T0| <= 1e6); clips loop\n"
           "  --size WxH              image size (default " +
           std::to_string(defaults().width) + "x" + std::to_string(defaults().height) + ", " +
           std::to_string(kLimits.width.min) + " <= W, H <= " + std::to_string(kLimits.width.max) +
           ")\n"
           "  --zoom Z                1 = every pose of the played clip(s) fits the view (no "
           "clip:\n"
           "                          the rest pose), 2 = twice as large (default " +
           g(defaults().zoom) + ", " + range(kLimits.zoom) +
           ")\n"
           "  --zoom-to Z2            zoom from Z to Z2 (geometrically) over the frames (default: "
           "no\n"
           "                          zoom change; " +
           range(kLimits.zoom) +
           ")\n"
           "  --zoom-period N         with --zoom-to: go Z -> Z2 -> Z every N frames, again and "
           "again\n"
           "                          (default: once, Z -> Z2 over all frames)\n"
           "  --yaw DEG, --pitch DEG  camera orbit (default " +
           g(defaults().yaw_degrees) + ", " + g(defaults().pitch_degrees) +
           ": looking down -Z);\n                          yaw " + range(kLimits.yaw_degrees) +
           ", pitch " + range(kLimits.pitch_degrees) + "\n";
}

// The point stages' options: relevance, level of detail, threads, tone cap, refinement.
std::string stage_usage() {
    return "  --no-relevance-update   keep rest-pose relevance radii (thesis Alg. 6.3 without "
           "6.4)\n"
           "  --no-lod                run place, relevance and size on every point (default: only\n"
           "                          clusters in view, cut where no dot can draw; docs/lod.md)\n"
           "  --threads N             point stages on a worker beside the mesh pass from 2 on,\n"
           "                          byte-identical output (default " +
           std::to_string(defaults().threads) + ", 0 = the hardware's up to " +
           std::to_string(stipple::kMaxAutoThreads) + ", max " +
           std::to_string(kLimits.threads.max) +
           ")\n"
           "  --raster-threads N      llvmpipe's rasterizer threads, headless and --window\n"
           "                          (default: the driver's, one per core; 0 = on the calling\n"
           "                          thread, which with --threads 2 leaves a 2-core machine's\n"
           "                          other core to the point stages; max " +
           std::to_string(stipple::platform::kMaxRasterThreads) +
           ")\n"
           "  --dark-tone T           darkest tone lighting asks for, thesis §8.4 (default " +
           g(defaults().dark_tone) + ", " + range(kLimits.dark_tone) +
           ")\n"
           "  --refinement-budget N   extra points per frame where the baked hierarchy runs out\n"
           "                          (close-ups, stretch; default " +
           std::to_string(defaults().refinement_budget) + ", 0 = off, max " +
           std::to_string(kLimits.refinement_budget.max) + ")\n";
}

// The tone, look, paintstroke, output and debugging options.
std::string render_usage() {
    return "  --tone T                constant target tone " + range(kLimits.constant_tone) +
           " instead of lighting (default:\n"
           "                          lighting)\n"
           "  --point-size PX         maximum stipple diameter (default " +
           g(defaults().max_point_size) + ", " + range(kLimits.max_point_size) +
           ")\n"
           "  --background RRGGBB     background colour (default " +
           background_default() + ")\n" + stage_usage() +
           "  --no-silhouettes        do not draw silhouette lines\n"
           "  --line-width PX         silhouette line width (default " +
           g(defaults().line_width) + ", " + range(kLimits.line_width) +
           ")\n"
           "  --light X,Y,Z[,I]       a directional light toward X,Y,Z with intensity I (default "
           "1,\n"
           "                          " +
           range(kLimits.light_intensity) +
           "); repeat for up to 4; replaces the\n"
           "                          default key light (camera space -0.5,0.6,0.6)\n"
           "  --light-space S         camera (default: lights turn with the camera) or world\n"
           "  --ambient A             light every point gets, " +
           range(kLimits.ambient) +
           " (default 0)\n"
           "  --no-strokes            do not draw the asset's paintstrokes (STRK section)\n"
           "  --stroke-quality Q      paintstroke breadthwise quality 0, 1, 2 or auto (GI'98 "
           "§4.3;\n"
           "                          default auto: by projected radius)\n"
           "  --stroke-tolerance T[,Z]  lengthwise tolerances in pixels: tol_theta (Position\n"
           "                          Constraint I) and tol_z (II and radius; default " +
           g(defaults().stroke_tol_theta) + "," + g(defaults().stroke_tol_z) + ", each " +
           range(kLimits.stroke_tol_theta) +
           ")\n"
           "  --stroke-lod PX         draw a stroke only where its root point's relevance radius\n"
           "                          projects to >= PX pixels (default 0: all; " +
           range(kLimits.stroke_lod_px) +
           ")\n"
           "  --stroke-budget N       tessellated stroke vertices per frame (default " +
           std::to_string(defaults().stroke_vertex_budget) + ", " +
           std::to_string(kLimits.stroke_vertex_budget.min) + ".." +
           std::to_string(kLimits.stroke_vertex_budget.max) +
           "; 48 bytes each);\n"
           "                          strokes past it are left out (--stats: stroke_budget_full)\n"
           "  --roots-out             also write roots_NNNN.csv (stroke,x,y,surface_x,surface_y:\n"
           "                          each stroke's drawn root and its host surface point, "
           "pixels)\n"
           "  --dots-out              also write dots_NNNN.csv (id,x,y,size per drawn dot)\n"
           "  --hidden-out            with --dots-out: hidden_NNNN.csv, sized dots the mesh hides\n"
           "  --strokes-out           particle styles: also write strokes_NNNN.csv\n"
           "                          (id,x,y,angle,size,width,alpha,visible per stroke)\n"
           "  --mask-out              also write mask_NNNN.png: white where the mesh covers the\n"
           "                          pixel, black elsewhere (the object mask of stipple-measure)\n"
           "  --no-png                do not write per-frame PNGs\n"
           "  --no-apng               do not write anim.png\n"
           "  --stats                 print a JSON object of counts and timings to stdout\n"
           "  --check-gl              check glGetError after every pass and readback; a GL error\n"
           "                          fails the run (exit 1) naming the pass; --stats counts them\n"
           "  --rss-every N           every N frames append frame,rss_kb,ms_per_frame (resident\n"
           "                          memory, mean frame time since the last row) to DIR/rss.csv\n"
           "  --backend egl|osmesa    force a context backend (default: EGL, then OSMesa)\n" +
           std::string(stipple::play::kWindowUsage) + "  -h, --help              this text\n";
}

// The looks (runtime/style.h, docs/styles.md).
std::string look_usage() {
    char fill[8];
    std::snprintf(fill, sizeof(fill), "%06x", rgb_of(defaults().fill));
    return std::string("  --style S               ") + style_name_list() + " (default " +
           style_name(defaults().style) +
           "; docs/styles.md):\n"
           "                          toon: banded fill + darker dots (thesis §7.2); colour: dots\n"
           "                          in the surface colour (§8.6); transparent: parts marked\n"
           "                          transparent (all without LOOK) draw only dots and lines\n"
           "  --style P               or a particle style (GI'01, docs/particles.md): strokes\n"
           "                          instead of dots: painterly-long|painterly-dab|sketch|\n"
           "                          cartoon|graftals|charcoal|two-tone|ink\n"
           "  --particle-fades        particle styles: strokes the body hides fade (a depth\n"
           "                          readback per frame) instead of popping\n"
           "  --particle-budget N     particle styles: particles of the tree, baked + temporary\n"
           "                          (default " +
           std::to_string(defaults().particle_budget) + ", max " +
           std::to_string(kLimits.particle_budget.max) +
           "; about 220 bytes each)\n"
           "  --toon-bands N          toon ramp bands, 2 or 3 (default " +
           std::to_string(defaults().toon_bands) +
           ")\n"
           "  --toon-ink F            toon dots: the fill colour times F (default " +
           g(defaults().toon_ink) + ", " + range(kLimits.toon_ink) +
           ")\n"
           "  --fill RRGGBB           toon fill / colour dots where the asset has no colour\n"
           "                          (default " +
           fill +
           ")\n"
           "  --tone-gamma G          tone curve T -> T^G before the size rule (> 1: lighter;\n"
           "                          default 1, " +
           range(kLimits.tone_gamma) +
           ")\n"
           "  --tone-contrast C       then 0.5 + (T - 0.5) C (default 1, " +
           range(kLimits.tone_contrast) +
           ")\n"
           "  --no-creases            do not draw the asset's crease lines (LOOK, thesis §8.2)\n"
           "  --no-occluder           depth pass over the full mesh, not the asset's occluder\n"
           "                          (OCCL, stipple-bake --occluder)\n";
}

}  // namespace

std::string usage() {
    return view_usage() + look_usage() + render_usage();
}

}  // namespace stipple::play
