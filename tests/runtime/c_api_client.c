/* A plain C client of runtime/stipple.h, compiled as C so the header stays C-clean; the
 * gtest in test_c_api.cpp calls it with a headless context's get-proc-address. */
#include <stdlib.h>
#include <string.h>

#include "runtime/stipple.h"

/* Loads `asset_path` and creates a player for it; 0 on success, -1 (nothing to free) if not. */
static int open_player(const char* asset_path, const stipple_player_desc* desc,
                       stipple_asset** asset, stipple_player** player) {
    *asset = NULL;
    *player = NULL;
    if (stipple_asset_load_file(asset_path, asset) != STIPPLE_OK) return -1;
    if (stipple_player_create(*asset, desc, player) != STIPPLE_OK) {
        stipple_asset_destroy(*asset);
        return -1;
    }
    return 0;
}

/* Renders frame `time` of clip 0 with the GL error checks on and returns the number of dark
 * pixels, or -1 on error (the message is in stipple_last_error()); *gl_errors gets
 * stipple_player_gl_errors. */
long c_api_render_dark_pixels(const char* asset_path, stipple_get_proc_fn get_proc, float time,
                              uint32_t* points_drawn, uint32_t* gl_errors) {
    stipple_asset* asset = NULL;
    stipple_player* player = NULL;
    stipple_player_desc desc;
    uint8_t* rgba;
    long dark = 0;
    size_t i;
    memset(&desc, 0, sizeof(desc));
    desc.width = 320;
    desc.height = 240;
    desc.check_gl_errors = 1;
    desc.get_proc_address = get_proc;
    if (open_player(asset_path, &desc, &asset, &player) != 0) return -1;
    rgba = (uint8_t*)malloc(320 * 240 * 4);
    stipple_player_draw(player, stipple_asset_clip_count(asset) > 0 ? 0 : -1, time);
    stipple_player_read_rgba(player, rgba);
    for (i = 0; i < 320 * 240; ++i) dark += rgba[i * 4] < 128;
    *points_drawn = stipple_player_points_drawn(player);
    *gl_errors = stipple_player_gl_errors(player);
    free(rgba);
    stipple_player_destroy(player);
    stipple_asset_destroy(asset);
    return dark;
}

/* Height in rows of the white object drawn with clip 0 blended 50/50 with clip 1 (the
 * stretch tube's "rest" and "stretch"), on a grey background; -1 on error. */
long c_api_blend_height(const char* asset_path, stipple_get_proc_fn get_proc, float weight) {
    stipple_asset* asset = NULL;
    stipple_player* player = NULL;
    stipple_player_desc desc;
    uint8_t* rgba;
    long top = -1, bottom = -1;
    int x, y;
    memset(&desc, 0, sizeof(desc));
    desc.width = 200;
    desc.height = 400;
    desc.zoom = 0.5f;
    desc.use_constant_tone = 1;
    desc.constant_tone = 0.0f;
    desc.no_silhouettes = 1;
    desc.dual_quaternion_skinning = 1;
    desc.background_set = 1;
    desc.background_rgb = 0x808080;
    desc.get_proc_address = get_proc;
    if (open_player(asset_path, &desc, &asset, &player) != 0) return -1;
    rgba = (uint8_t*)malloc(200 * 400 * 4);
    stipple_player_draw_blend(player, stipple_asset_find_clip(asset, "rest"), 1.0f,
                              stipple_asset_find_clip(asset, "stretch"), 1.0f, weight);
    stipple_player_read_rgba(player, rgba);
    for (y = 0; y < 400; ++y)
        for (x = 0; x < 200; ++x)
            if (rgba[(y * 200 + x) * 4] > 230) {
                if (top < 0) top = y;
                bottom = y;
            }
    free(rgba);
    stipple_player_destroy(player);
    stipple_asset_destroy(asset);
    return top < 0 ? 0 : bottom - top + 1;
}

/* Dark pixels of a close-up (zoom 8, constant tone 0.3) with the given refinement budget
 * (0: default, < 0: none); -1 on error. */
long c_api_closeup_dark_pixels(const char* asset_path, stipple_get_proc_fn get_proc,
                               int refinement_budget) {
    stipple_asset* asset = NULL;
    stipple_player* player = NULL;
    stipple_player_desc desc;
    uint8_t* rgba;
    long dark = 0;
    size_t i;
    memset(&desc, 0, sizeof(desc));
    desc.width = 320;
    desc.height = 240;
    desc.zoom = 8.0f;
    desc.use_constant_tone = 1;
    desc.constant_tone = 0.3f;
    desc.no_silhouettes = 1;
    desc.refinement_budget = refinement_budget;
    desc.get_proc_address = get_proc;
    if (open_player(asset_path, &desc, &asset, &player) != 0) return -1;
    rgba = (uint8_t*)malloc(320 * 240 * 4);
    stipple_player_draw(player, -1, 0.0f);
    stipple_player_read_rgba(player, rgba);
    for (i = 0; i < 320 * 240; ++i) dark += rgba[i * 4] < 128;
    free(rgba);
    stipple_player_destroy(player);
    stipple_asset_destroy(asset);
    return dark;
}

/* Draws frame `time` of clip 0 of a furry asset with the stroke settings given and returns the
 * strokes drawn (*triangles: their triangles), or -1 on error. */
long c_api_strokes_drawn(const char* asset_path, stipple_get_proc_fn get_proc, int no_strokes,
                         int quality, uint32_t* triangles) {
    stipple_asset* asset = NULL;
    stipple_player* player = NULL;
    stipple_player_desc desc;
    long drawn;
    memset(&desc, 0, sizeof(desc));
    desc.width = 320;
    desc.height = 240;
    desc.no_strokes = no_strokes;
    desc.stroke_quality = quality;
    desc.stroke_vertex_budget = 1 << 20; /* quality 2 fur needs more than the default */
    desc.check_gl_errors = 1;
    desc.get_proc_address = get_proc;
    if (open_player(asset_path, &desc, &asset, &player) != 0) return -1;
    stipple_player_draw(player, 0, 0.5f);
    drawn = (long)stipple_player_strokes_drawn(player);
    *triangles = stipple_player_stroke_triangles(player);
    if (stipple_player_gl_errors(player) != 0) drawn = -2;
    stipple_player_destroy(player);
    stipple_asset_destroy(asset);
    return drawn;
}
