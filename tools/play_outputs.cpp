#include "tools/play_outputs.h"

#include <cmath>
#include <cstdio>

#include "tools/image_write.h"

namespace stipple::play {

namespace {

bool write_dot_list(const Pipeline& p, const float* depth, VisibleDot* scratch,
                    const std::string& path, bool hidden) {
    FILE* f = std::fopen(path.c_str(), "w");
    if (!f) return false;
    std::fputs("id,x,y,size\n", f);
    const uint32_t n = hidden ? pipeline_hidden_dots(p, depth, scratch, p.point_capacity)
                              : pipeline_visible_dots(p, depth, scratch, p.point_capacity);
    for (uint32_t i = 0; i < n; ++i)
        std::fprintf(f, "%llu,%.2f,%.2f,%.3f\n", static_cast<unsigned long long>(scratch[i].id),
                     double(scratch[i].x), double(scratch[i].y), double(scratch[i].size));
    return std::fclose(f) == 0;
}

}  // namespace

// Writes the dots the last frame shows (pipeline_visible_dots) as CSV.
bool write_dots(const Pipeline& p, const float* depth, VisibleDot* scratch,
                const std::string& path) {
    return write_dot_list(p, depth, scratch, path, false);
}

bool write_hidden_dots(const Pipeline& p, const float* depth, VisibleDot* scratch,
                       const std::string& path) {
    return write_dot_list(p, depth, scratch, path, true);
}

// Writes the object mask of the last frame from the mesh pass's depth (bottom row first, 1 =
// background): white where depth < 1, black elsewhere, top row first like the frame PNGs.
// `rgba` is scratch of width * height * 4 bytes.
bool write_mask(const float* depth, int w, int h, uint8_t* rgba, const std::string& path,
                std::string* error) {
    const size_t pixels = size_t(w) * size_t(h);
    for (size_t i = 0; i < pixels; ++i) {
        const uint8_t v = depth[i] < 1.0f ? 255 : 0;
        rgba[i * 4] = rgba[i * 4 + 1] = rgba[i * 4 + 2] = v;
        rgba[i * 4 + 3] = 255;
    }
    return image::write_png(path.c_str(), w, h, rgba, /*bottom_up=*/true, error);
}

bool write_roots(const Pipeline& p, StrokeRootSample* scratch, const std::string& path) {
    FILE* f = std::fopen(path.c_str(), "w");
    if (!f) return false;
    std::fputs("stroke,x,y,surface_x,surface_y\n", f);
    const uint32_t n = pipeline_stroke_roots(p, scratch, p.asset->strokes.stroke_count);
    for (uint32_t i = 0; i < n; ++i)
        std::fprintf(f, "%u,%.3f,%.3f,%.3f,%.3f\n", scratch[i].stroke, double(scratch[i].x),
                     double(scratch[i].y), double(scratch[i].surface_x),
                     double(scratch[i].surface_y));
    return std::fclose(f) == 0;
}

bool write_strokes(const Pipeline& p, const float* depth, const std::string& path) {
    FILE* f = std::fopen(path.c_str(), "w");
    if (!f) return false;
    std::fputs("id,x,y,angle,size,width,alpha,visible\n", f);
    const ParticleStage& s = p.particles;
    const int w = p.config.width, h = p.config.height;
    for (uint32_t k = 0; k < s.stroke_count; ++k) {
        const StrokeInstance& st = s.strokes[k];
        const int px = int(std::floor(st.x)), py = int(std::floor(st.y));
        bool visible = px >= 0 && py >= 0 && px < w && py < h && st.depth <= 1.0f;
        // As particle_visible_strokes and the stroke shader test it; with visibility fades the
        // strokes were drawn untested, their visibility in their opacity.
        if (visible && !s.visibility.applied) {
            const float mesh = depth[size_t(h - 1 - py) * size_t(w) + size_t(px)];
            visible = !(mesh < 1.0f && st.depth > mesh + 1e-5f);
        }
        std::fprintf(f, "%u,%.2f,%.2f,%.4f,%.2f,%.2f,%.3f,%d\n", s.stroke_id[k], double(st.x),
                     double(st.y), double(st.angle), double(st.length), double(st.width),
                     double(st.alpha), visible ? 1 : 0);
    }
    return std::fclose(f) == 0;
}

}  // namespace stipple::play
