#include "runtime/style.h"

#include <cstring>

#include "runtime/frame_config.h"

namespace stipple {

namespace {

const char* const kStyleNames[kStyleTotal] = {"classic", "toon", "colour", "transparent"};

uint8_t to_byte(float v) {
    const float c = v < 0.0f ? 0.0f : (v > 1.0f ? 1.0f : v);
    return uint8_t(c * 255.0f + 0.5f);
}

bool has_dot_colours(const LooksView& looks) {
    return looks.point_colour || (looks.part_colour && looks.triangle_part);
}

// Part colour of mesh triangle t (RGBA8), or `fill` when the asset has no part colours.
void triangle_colour(const LooksView& looks, uint32_t t, const float* fill, uint8_t* rgba) {
    if (looks.part_colour && looks.triangle_part) {
        std::memcpy(rgba, looks.part_colour + size_t(looks.triangle_part[t]) * 4, 4);
        return;
    }
    for (int k = 0; k < 3; ++k) rgba[k] = to_byte(fill[k]);
    rgba[3] = 255;
}

// The colour of extra point k (after the baked points): its host triangle's.
void refined_colour(const LooksView& looks, const uint32_t* host_triangle, const RefinedHosts& r,
                    uint32_t k, const float* fill, uint8_t* rgba) {
    const uint32_t t = r.triangle[k];
    if (!r.on_points) {
        triangle_colour(looks, t, fill, rgba);
        return;
    }
    unsigned sum[4] = {};
    for (int c = 0; c < 3; ++c) {
        uint8_t corner[4];
        point_base_colour(looks, host_triangle, r.indices[size_t(t) * 3 + c], fill, corner);
        for (int i = 0; i < 4; ++i) sum[i] += corner[i];
    }
    for (int i = 0; i < 4; ++i) rgba[i] = uint8_t((sum[i] + 1) / 3);
}

}  // namespace

void colour_dot_rgb(float* rgb) {
    const float luminance = 0.2126f * rgb[0] + 0.7152f * rgb[1] + 0.0722f * rgb[2];
    if (luminance <= kColourDotLuminance) return;
    for (int k = 0; k < 3; ++k) rgb[k] *= kColourDotLuminance / luminance;
}

const char* style_name(Style style) {
    const int i = int(style);
    return i >= 0 && i < kStyleTotal ? kStyleNames[i] : "unknown";
}

int find_style(const char* name) {
    if (!name) return -1;
    if (std::strcmp(name, "color") == 0) return int(Style::colour);
    for (int i = 0; i < kStyleTotal; ++i)
        if (std::strcmp(name, kStyleNames[i]) == 0) return i;
    return -1;
}

const char* style_name_list() {
    return "classic|toon|colour|transparent";
}

void point_base_colour(const LooksView& looks, const uint32_t* host_triangle, uint32_t i,
                       const float* fill, uint8_t* rgba) {
    if (looks.point_colour) {
        std::memcpy(rgba, looks.point_colour + size_t(i) * 4, 4);
        return;
    }
    triangle_colour(looks, host_triangle[i], fill, rgba);
}

Status style_init(StyleBuffers* s, const Asset& asset, uint32_t point_capacity) {
    *s = StyleBuffers();
    const LooksView& looks = asset.looks;
    const MeshView& mesh = asset.mesh;
    bool ok = true;
    if (looks.triangle_part && looks.part_count > 0) {
        for (uint32_t p = 0; looks.part_flags && p < looks.part_count; ++p)
            s->transparent_parts |= (looks.part_flags[p] & kPartTransparent) != 0;
        ok = alloc(&s->vertex_colours, size_t(mesh.vertex_count) * 4);
        for (uint32_t t = 0; ok && t < mesh.triangle_count; ++t) {
            const uint16_t part = looks.triangle_part[t];
            uint8_t rgba[4] = {255, 255, 255, 255};
            if (looks.part_colour) std::memcpy(rgba, looks.part_colour + size_t(part) * 4, 3);
            const bool clear = looks.part_flags && (looks.part_flags[part] & kPartTransparent);
            rgba[3] = clear ? 0 : 255;
            for (int c = 0; c < 3; ++c)
                std::memcpy(s->vertex_colours.get() + size_t(mesh.indices[t * 3 + c]) * 4, rgba, 4);
        }
    }
    if (ok && has_dot_colours(looks)) ok = alloc(&s->dot_colours, size_t(point_capacity) * 4);
    if (ok && looks.crease_count > 0) ok = alloc(&s->crease_lines, size_t(looks.crease_count) * 6);
    if (!ok) return make_status(StatusCode::out_of_memory, "out of memory for the looks");
    return {};
}

bool style_dot_colours(StyleBuffers* s, const Asset& asset, const FrameConfig& config,
                       const float* size, const RefinedHosts& refined) {
    const bool toon = config.style == Style::toon, colour = config.style == Style::colour;
    if (!s->dot_colours || !(toon || colour)) return false;
    const LooksView& looks = asset.looks;
    // toon: the part colour (the fill under the dot) darkened; colour: the surface colour.
    LooksView parts = looks;
    if (toon) parts.point_colour = nullptr;
    const float darken = toon ? config.toon_ink : 1.0f;
    const uint32_t baked = asset.points.point_count;
    uint8_t* out = s->dot_colours.get();
    uint32_t drawn = 0;
    for (uint32_t j = 0; j < baked + refined.count; ++j) {
        if (!(size[j] > 0.0f)) continue;
        uint8_t* rgba = out + size_t(drawn) * 4;
        if (j < baked)
            point_base_colour(parts, asset.points.host_triangle, j, config.fill, rgba);
        else
            refined_colour(parts, asset.points.host_triangle, refined, j - baked, config.fill,
                           rgba);
        float rgb[3] = {rgba[0] / 255.0f, rgba[1] / 255.0f, rgba[2] / 255.0f};
        if (toon)
            for (float& c : rgb) c *= darken;
        else
            colour_dot_rgb(rgb);
        for (int k = 0; k < 3; ++k) rgba[k] = to_byte(rgb[k]);
        ++drawn;
    }
    return true;
}

}  // namespace stipple
