// The C API (runtime/stipple.h) over the C++ runtime: no exceptions cross it (the runtime
// is built with -fno-exceptions and allocates with nothrow new).
#include <cmath>
#include <cstdio>
#include <cstring>
#include <glm/gtc/type_ptr.hpp>
#include <new>

#include "runtime/app_frame.h"
#include "runtime/asset.h"
#include "runtime/c_api_internal.h"
#include "runtime/camera.h"
#include "runtime/frame_pipeline.h"
#include "runtime/memory.h"
#include "runtime/particle_style.h"
#include "runtime/stipple.h"

struct stipple_asset {
    stipple::Asset asset;
};

struct stipple_player {
    stipple::Pipeline pipeline;
    stipple::Allocator allocator;  // what the player (and its buffers) came from
    stipple::BlockArena block;     // the caller's block, when desc.memory is given
    bool warned_gl = false, warned_strokes = false;  // each warning logged once
};

namespace {

// stipple::StatusCode maps 1:1 onto stipple_result.
static_assert(int(stipple::StatusCode::ok) == STIPPLE_OK, "");
static_assert(int(stipple::StatusCode::invalid_argument) == STIPPLE_ERROR_INVALID_ARGUMENT, "");
static_assert(int(stipple::StatusCode::io_error) == STIPPLE_ERROR_IO, "");
static_assert(int(stipple::StatusCode::bad_asset) == STIPPLE_ERROR_BAD_ASSET, "");
static_assert(int(stipple::StatusCode::unsupported_version) == STIPPLE_ERROR_UNSUPPORTED_VERSION,
              "");
static_assert(int(stipple::StatusCode::gl_error) == STIPPLE_ERROR_GL, "");
static_assert(int(stipple::StatusCode::out_of_memory) == STIPPLE_ERROR_OUT_OF_MEMORY, "");

thread_local char g_error[256] = "";
thread_local stipple_load_error g_load_error = STIPPLE_LOAD_OK;
stipple_log_fn g_log = nullptr;
void* g_log_user = nullptr;

// stipple::LoadError maps 1:1 onto stipple_load_error.
static_assert(int(stipple::LoadError::bad_radius) == STIPPLE_LOAD_BAD_RADIUS, "");
static_assert(int(stipple::LoadError::checksum_mismatch) == STIPPLE_LOAD_CHECKSUM_MISMATCH, "");

void log_message(int level, const char* message) {
    if (g_log) g_log(level, message, g_log_user);
}

stipple_result fail(stipple_result result, const char* message) {
    std::snprintf(g_error, sizeof(g_error), "%s", message);
    log_message(2, g_error);
    return result;
}

}  // namespace

stipple_result stipple::c_api_fail(stipple_result result, const char* message) {
    return fail(result, message);
}

namespace {

stipple_result from_status(const stipple::Status& st) {
    if (st.ok()) return STIPPLE_OK;
    return fail(stipple_result(st.code), st.message);
}

// Warnings after a draw, each once per player: the first GL error the checks saw, and
// strokes left out by a full stroke budget.
void warn_after_draw(stipple_player* p) {
    if (!g_log) return;
    const stipple::GlErrorLog& e = stipple::pipeline_gl_errors(p->pipeline);
    if (e.count > 0 && !p->warned_gl) {
        p->warned_gl = true;
        char m[160];
        std::snprintf(m, sizeof(m), "GL error %s after the %s pass",
                      stipple::gl_error_name(e.first_error), e.first_pass ? e.first_pass : "?");
        log_message(1, m);
    }
    if (p->pipeline.strokes.mesh.overflow && !p->warned_strokes) {
        p->warned_strokes = true;
        log_message(1, "stroke budget full: strokes left out (raise stroke_vertex_budget)");
    }
}

template <typename Load>
stipple_result load(stipple_asset** out, Load&& load_into) {
    if (!out) return fail(STIPPLE_ERROR_INVALID_ARGUMENT, "out is NULL");
    *out = nullptr;
    g_load_error = STIPPLE_LOAD_OK;
    stipple_asset* a = new (std::nothrow) stipple_asset();
    if (!a) return fail(STIPPLE_ERROR_OUT_OF_MEMORY, "out of memory");
    const stipple::Status st = load_into(&a->asset);
    g_load_error = stipple_load_error(st.error);
    stipple_result r = from_status(st);
    if (r != STIPPLE_OK) {
        delete a;
        return r;
    }
    *out = a;
    return STIPPLE_OK;
}

// A load description as LoadOptions; NULL: every default.
stipple::LoadOptions load_options_of(const stipple_load_desc* desc) {
    stipple::LoadOptions options;
    if (desc) options.max_decoded_bytes = desc->max_decoded_bytes;
    return options;
}

// The looks' fields of the description (runtime/style.h); an unknown style fails the check.
void look_config_of(const stipple_player_desc& d, stipple::FrameConfig* c) {
    c->style = stipple::Style(d.style);
    // Past the stipple looks: the particle styles (docs/particles.md), built-in then registered.
    const int particle = d.style - stipple::kStyleTotal;
    if (particle >= 0 && particle < stipple::particle_style_count()) {
        c->style = stipple::Style::classic;
        c->particle_style = &stipple::particle_style_at(particle);
    }
    c->toon_bands = d.toon_bands;
    if (d.fill_set)
        for (int k = 0; k < 3; ++k)
            c->fill[k] = float((d.fill_rgb >> (16 - 8 * k)) & 0xFF) / 255.0f;
    if (d.toon_ink != 0.0f) c->toon_ink = d.toon_ink < 0.0f ? 0.0f : d.toon_ink;
    c->tone_gamma = d.tone_gamma;
    c->tone_contrast = d.tone_contrast;
    c->creases = !d.no_creases;
}

void look_desc_of(const stipple::FrameConfig& c, stipple_player_desc* d) {
    d->style = c.particle_style
                   ? stipple::kStyleTotal + stipple::particle_style_index(c.particle_style)
                   : int(c.style);
    d->toon_bands = c.toon_bands;
    d->fill_rgb = 0;
    for (int k = 0; k < 3; ++k)
        d->fill_rgb |= uint32_t(std::lround(c.fill[k] * 255.0f)) << (16 - 8 * k);
    d->fill_set = 1;
    d->toon_ink = c.toon_ink > 0.0f ? c.toon_ink : -1.0f;
    d->tone_gamma = c.tone_gamma;
    d->tone_contrast = c.tone_contrast;
    d->no_creases = !c.creases;
}

// The description as frame settings: a zero field keeps FrameConfig's default (the table in
// runtime/frame_config.h); resolve_frame_config then fills zero sizes and checks limits.
stipple::FrameConfig frame_config_of(const stipple_player_desc& d) {
    stipple::FrameConfig c;
    c.width = d.width;
    c.height = d.height;
    c.zoom = d.zoom;
    c.yaw_degrees = d.yaw_degrees;
    c.pitch_degrees = d.pitch_degrees;
    c.constant_tone = d.use_constant_tone ? d.constant_tone : stipple::kLightingTone;
    c.max_point_size = d.max_point_size;
    c.relevance_update = !d.no_relevance_update;
    c.lod = !d.no_lod;
    if (d.threads != 0) c.threads = d.threads == -1 ? 0 : d.threads;  // FrameConfig: 0 = auto
    if (d.dark_tone_set) c.dark_tone = d.dark_tone;
    if (d.refinement_budget < 0) c.refinement_budget = 0;
    if (d.refinement_budget > 0) c.refinement_budget = uint32_t(d.refinement_budget);
    c.silhouettes = !d.no_silhouettes;
    c.skinning =
        d.dual_quaternion_skinning ? stipple::anim::Skinning::dqs : stipple::anim::Skinning::lbs;
    if (d.background_set)
        for (int k = 0; k < 3; ++k)
            c.background[k] = float((d.background_rgb >> (16 - 8 * k)) & 0xFF) / 255.0f;
    c.check_gl_errors = d.check_gl_errors != 0;
    c.strokes = !d.no_strokes;
    // AUTO (0) is -1 here; an unknown enum value maps outside [-1, 2] and fails the check.
    c.stroke_quality = d.stroke_quality >= 0 && d.stroke_quality <= 3 ? d.stroke_quality - 1 : 99;
    c.stroke_tol_theta = d.stroke_tol_theta;
    c.stroke_tol_z = d.stroke_tol_z;
    c.stroke_lod_px = d.stroke_lod_px;
    if (d.stroke_nudge != 0.0f) c.stroke_nudge = d.stroke_nudge < 0.0f ? 0.0f : d.stroke_nudge;
    c.stroke_vertex_budget = d.stroke_vertex_budget < 0 ? 1u : uint32_t(d.stroke_vertex_budget);
    look_config_of(d, &c);
    // An unknown path maps outside the enum and fails resolve_frame_config's check.
    c.path = d.path == STIPPLE_PATH_GPU
                 ? stipple::FramePath::gpu
                 : (d.path == STIPPLE_PATH_CPU ? stipple::FramePath::cpu : stipple::FramePath(99));
    return c;
}

// Clip `clip` at `time`, layered with clip2 at time2 by weight2 clamped to [0, 1].
// (look_config_of and look_desc_of are above frame_config_of.)
stipple::AnimationState animation_state(int clip, float time, int clip2, float time2,
                                        float weight2) {
    stipple::AnimationState state;
    state.clip = clip;
    state.time = time;
    state.blend_clip = clip2;
    state.blend_time = time2;
    state.blend_weight = weight2 < 0 ? 0.0f : (weight2 > 1 ? 1.0f : weight2);
    return state;
}

void rgb_to_floats(uint32_t rgb, float* out) {
    for (int k = 0; k < 3; ++k) out[k] = float((rgb >> (16 - 8 * k)) & 0xFF) / 255.0f;
}

// Applies per-frame settings: resolved and range-checked, all or nothing.
stipple_result set_view(stipple_player* p, const stipple::FrameConfig& c) {
    return from_status(stipple::pipeline_set_view(&p->pipeline, c));
}

// A player in memory from desc's allocator or block (or operator new), constructed, with its
// allocator set for its buffers; nullptr when that memory is not there.
stipple_player* new_player(const stipple_player_desc& d) {
    stipple::Allocator a;
    stipple::BlockArena block;
    if (d.memory) {
        block.base = static_cast<uint8_t*>(d.memory);
        block.size = d.memory_size;
    } else if (d.allocate) {
        a.allocate = d.allocate;
        a.release = d.release;
        a.user = d.allocator_user;
    }
    void* raw = nullptr;
    if (d.memory) {
        const stipple::Allocator bump = stipple::block_allocator(&block);
        raw = stipple::allocate_bytes(bump, sizeof(stipple_player));
    } else {
        raw = stipple::allocate_bytes(a, sizeof(stipple_player));
    }
    if (!raw) return nullptr;
    stipple_player* p = new (raw) stipple_player();
    p->block = block;  // what the player's own bytes left of the block
    p->allocator = d.memory ? stipple::block_allocator(&p->block) : a;
    return p;
}

// The inverse of frame_config_of for a resolved config: every field explicit.
void desc_of(const stipple::FrameConfig& c, stipple_player_desc* d) {
    d->width = c.width;
    d->height = c.height;
    d->zoom = c.zoom;
    d->yaw_degrees = c.yaw_degrees;
    d->pitch_degrees = c.pitch_degrees;
    d->use_constant_tone = c.constant_tone != stipple::kLightingTone;
    d->constant_tone = d->use_constant_tone ? c.constant_tone : 0.0f;
    d->max_point_size = c.max_point_size;
    d->no_relevance_update = !c.relevance_update;
    d->no_lod = !c.lod;
    d->no_silhouettes = !c.silhouettes;
    d->dual_quaternion_skinning = c.skinning == stipple::anim::Skinning::dqs;
    d->dark_tone_set = 1;
    d->dark_tone = c.dark_tone;
    d->refinement_budget = c.refinement_budget > 0 ? int(c.refinement_budget) : -1;
    d->background_rgb = 0;
    for (int k = 0; k < 3; ++k)
        d->background_rgb |= uint32_t(std::lround(c.background[k] * 255.0f)) << (16 - 8 * k);
    d->background_set = 1;
    d->check_gl_errors = c.check_gl_errors ? 1 : 0;
    d->no_strokes = !c.strokes;
    d->stroke_quality = c.stroke_quality + 1;
    d->stroke_tol_theta = c.stroke_tol_theta;
    d->stroke_tol_z = c.stroke_tol_z;
    d->stroke_lod_px = c.stroke_lod_px;
    d->stroke_nudge = c.stroke_nudge > 0.0f ? c.stroke_nudge : -1.0f;
    d->stroke_vertex_budget = int(c.stroke_vertex_budget);
    look_desc_of(c, d);
    d->path = c.path == stipple::FramePath::gpu ? STIPPLE_PATH_GPU : STIPPLE_PATH_CPU;
}

}  // namespace

extern "C" {

stipple_load_error stipple_last_load_error(void) {
    return g_load_error;
}

void stipple_set_logger(stipple_log_fn fn, void* user) {
    g_log = fn;
    g_log_user = user;
}

const char* stipple_last_error(void) {
    return g_error;
}

stipple_result stipple_asset_load_file(const char* path, stipple_asset** out) {
    return stipple_asset_load_file_ex(path, nullptr, out);
}

stipple_result stipple_asset_load_memory(const void* data, size_t size, stipple_asset** out) {
    return stipple_asset_load_memory_ex(data, size, nullptr, out);
}

stipple_result stipple_asset_load_file_ex(const char* path, const stipple_load_desc* desc,
                                          stipple_asset** out) {
    if (!path) return fail(STIPPLE_ERROR_INVALID_ARGUMENT, "path is NULL");
    const stipple::LoadOptions options = load_options_of(desc);
    return load(out, [&](stipple::Asset* a) { return stipple::load_asset_file(path, a, options); });
}

stipple_result stipple_asset_load_memory_ex(const void* data, size_t size,
                                            const stipple_load_desc* desc, stipple_asset** out) {
    if (!data) return fail(STIPPLE_ERROR_INVALID_ARGUMENT, "data is NULL");
    const stipple::LoadOptions options = load_options_of(desc);
    return load(
        out, [&](stipple::Asset* a) { return stipple::load_asset_memory(data, size, a, options); });
}

void stipple_asset_destroy(stipple_asset* asset) {
    delete asset;
}

uint32_t stipple_asset_point_count(const stipple_asset* a) {
    return a ? a->asset.points.point_count : 0;
}

uint32_t stipple_asset_clip_count(const stipple_asset* a) {
    return a ? a->asset.clip_count : 0;
}

uint32_t stipple_asset_stroke_count(const stipple_asset* a) {
    return a ? a->asset.strokes.stroke_count : 0;
}

const char* stipple_asset_clip_name(const stipple_asset* a, uint32_t clip) {
    return a && clip < a->asset.clip_count ? a->asset.clips[clip].name : nullptr;
}

float stipple_asset_clip_duration(const stipple_asset* a, uint32_t clip) {
    return a && clip < a->asset.clip_count ? a->asset.clips[clip].duration : 0.0f;
}

int stipple_asset_find_clip(const stipple_asset* a, const char* name) {
    return a && name ? stipple::find_clip(a->asset, name) : -1;
}

stipple_result stipple_player_desc_resolve(const stipple_player_desc* in,
                                           stipple_player_desc* out) {
    if (!in || !out) return fail(STIPPLE_ERROR_INVALID_ARGUMENT, "NULL argument");
    stipple::FrameConfig c;
    stipple_result r = from_status(stipple::resolve_frame_config(frame_config_of(*in), &c));
    if (r != STIPPLE_OK) return r;
    stipple_player_desc resolved = *in;  // get_proc_address and anything not a setting
    desc_of(c, &resolved);
    *out = resolved;
    return STIPPLE_OK;
}

stipple_result stipple_player_create(const stipple_asset* asset, const stipple_player_desc* desc,
                                     stipple_player** out) {
    if (!asset || !desc || !out) return fail(STIPPLE_ERROR_INVALID_ARGUMENT, "NULL argument");
    *out = nullptr;
    if (!desc->get_proc_address)
        return fail(STIPPLE_ERROR_INVALID_ARGUMENT, "desc.get_proc_address is required");
    stipple::FrameConfig c;  // checked before any GL call
    stipple_result r = from_status(stipple::resolve_frame_config(frame_config_of(*desc), &c));
    if (r != STIPPLE_OK) return r;
    stipple::GlApi gl;
    r = from_status(stipple::load_gl_api(desc->get_proc_address, &gl));
    if (r != STIPPLE_OK) return r;
    stipple_player* p = new_player(*desc);
    if (!p) return fail(STIPPLE_ERROR_OUT_OF_MEMORY, "no memory for the player");
    r = from_status(stipple::pipeline_init(&p->pipeline, asset->asset, gl, c, p->allocator));
    if (r != STIPPLE_OK) {
        stipple_player_destroy(p);
        return r;
    }
    *out = p;
    return STIPPLE_OK;
}

void stipple_player_draw(stipple_player* p, int clip, float time_seconds) {
    if (!p) return;
    stipple::pipeline_frame(&p->pipeline, clip, time_seconds, nullptr);
    warn_after_draw(p);
}

void stipple_player_draw_blend(stipple_player* p, int clip, float time, int clip2, float time2,
                               float weight2) {
    if (!p) return;
    stipple::pipeline_frame(&p->pipeline, animation_state(clip, time, clip2, time2, weight2),
                            nullptr);
    warn_after_draw(p);
}

void stipple_player_draw_into(stipple_player* p, const stipple_app_view* view, int clip, float time,
                              int clip2, float time2, float weight2) {
    if (!p || !view) {
        fail(STIPPLE_ERROR_INVALID_ARGUMENT, "NULL argument");
        return;
    }
    const int w = view->viewport[2], h = view->viewport[3];
    if (w < 1 || h < 1 || w > 16384 || h > 16384) {
        char message[96];
        std::snprintf(message, sizeof(message), "viewport %d x %d outside [1, 16384]", w, h);
        fail(STIPPLE_ERROR_INVALID_ARGUMENT, message);
        return;
    }
    stipple::AppView v;
    v.view = glm::make_mat4(view->view);
    v.projection = glm::make_mat4(view->projection);
    v.model = glm::make_mat4(view->model);
    for (int k = 0; k < 4; ++k) v.viewport[k] = view->viewport[k];
    if (view->framebuffer_set) v.framebuffer = int64_t(view->framebuffer);
    stipple::pipeline_draw_into(&p->pipeline, animation_state(clip, time, clip2, time2, weight2), v,
                                nullptr);
    warn_after_draw(p);
}

stipple_result stipple_orbit_camera(const stipple_asset* asset, const stipple_player_desc* desc,
                                    float view[16], float projection[16]) {
    if (!asset || !desc || !view || !projection)
        return fail(STIPPLE_ERROR_INVALID_ARGUMENT, "NULL argument");
    stipple::FrameConfig c;
    stipple_result r = from_status(stipple::resolve_frame_config(frame_config_of(*desc), &c));
    if (r != STIPPLE_OK) return r;
    const stipple::OrbitCamera cam = stipple::orbit_camera(asset->asset, c, nullptr);
    std::memcpy(view, glm::value_ptr(cam.view), 16 * sizeof(float));
    std::memcpy(projection, glm::value_ptr(cam.projection), 16 * sizeof(float));
    return STIPPLE_OK;
}

stipple_result stipple_player_set_lights(stipple_player* p, const stipple_light* lights, int count,
                                         float ambient) {
    if (!p || (count > 0 && !lights)) return fail(STIPPLE_ERROR_INVALID_ARGUMENT, "NULL argument");
    stipple::FrameConfig c = p->pipeline.config;
    if (count < 0 || count > stipple::kMaxLights)
        return fail(STIPPLE_ERROR_INVALID_ARGUMENT, "light count outside [0, 4]");
    c.light_count = count;
    c.ambient = ambient;
    for (int i = 0; i < count; ++i) {
        for (int k = 0; k < 3; ++k) c.lights[i].direction[k] = lights[i].direction[k];
        c.lights[i].intensity = lights[i].intensity;
        c.lights[i].camera_space = lights[i].world_space == 0;
    }
    return set_view(p, c);
}

stipple_result stipple_player_set_colours(stipple_player* p, uint32_t paper, uint32_t ink,
                                          uint32_t background) {
    if (!p) return fail(STIPPLE_ERROR_INVALID_ARGUMENT, "NULL argument");
    stipple::FrameConfig c = p->pipeline.config;
    rgb_to_floats(paper, c.paper);
    rgb_to_floats(ink, c.ink);
    rgb_to_floats(background, c.background);
    return set_view(p, c);
}

stipple_result stipple_player_set_silhouettes(stipple_player* p, int on, float width) {
    if (!p) return fail(STIPPLE_ERROR_INVALID_ARGUMENT, "NULL argument");
    stipple::FrameConfig c = p->pipeline.config;
    c.silhouettes = on != 0;
    if (width != 0.0f) c.line_width = width;
    return set_view(p, c);
}

stipple_result stipple_player_set_tone(stipple_player* p, int use_constant_tone, float tone,
                                       float max_point_size) {
    if (!p) return fail(STIPPLE_ERROR_INVALID_ARGUMENT, "NULL argument");
    stipple::FrameConfig c = p->pipeline.config;
    c.constant_tone = use_constant_tone ? tone : stipple::kLightingTone;
    if (max_point_size != 0.0f) c.max_point_size = max_point_size;
    return set_view(p, c);
}

const char* stipple_style_name(int style) {
    if (style >= 0 && style < stipple::kStyleTotal)
        return stipple::style_name(stipple::Style(style));
    const int particle = style - stipple::kStyleTotal;
    return particle >= 0 && particle < stipple::particle_style_count()
               ? stipple::particle_style_at(particle).name
               : nullptr;
}

int stipple_find_style(const char* name) {
    const int look = stipple::find_style(name);
    if (look >= 0) return look;
    const int particle = stipple::particle_style_index(stipple::find_particle_style(name));
    return particle >= 0 ? stipple::kStyleTotal + particle : -1;
}

stipple_result stipple_player_set_style(stipple_player* p, int style, float tone_gamma,
                                        float tone_contrast, int creases) {
    if (!p) return fail(STIPPLE_ERROR_INVALID_ARGUMENT, "NULL argument");
    stipple::FrameConfig c = p->pipeline.config;
    if (style >= stipple::kStyleTotal || c.particle_style)
        return fail(STIPPLE_ERROR_INVALID_ARGUMENT,
                    "particle styles are chosen at stipple_player_create");
    c.style = stipple::Style(style);
    c.tone_gamma = tone_gamma;
    c.tone_contrast = tone_contrast;
    c.creases = creases != 0;
    return set_view(p, c);
}

void stipple_player_read_rgba(stipple_player* p, uint8_t* rgba) {
    if (p && rgba) stipple::renderer_read_color(&p->pipeline.renderer, rgba);
}

uint32_t stipple_player_points_drawn(const stipple_player* p) {
    return p ? p->pipeline.points_drawn : 0;
}

uint32_t stipple_player_strokes_drawn(const stipple_player* p) {
    return p ? p->pipeline.strokes.strokes_drawn : 0;
}

uint32_t stipple_player_stroke_triangles(const stipple_player* p) {
    return p ? p->pipeline.strokes.stats.triangles : 0;
}

uint32_t stipple_player_gl_errors(const stipple_player* p) {
    return p ? stipple::pipeline_gl_errors(p->pipeline).count : 0;
}

void stipple_player_destroy(stipple_player* p) {
    if (!p) return;
    stipple::pipeline_destroy(&p->pipeline);
    const stipple::Allocator a = p->allocator;
    p->~stipple_player();
    if (!a.allocate || a.release) stipple::release_bytes(a, p);  // a block is the caller's
}

size_t stipple_player_memory_bytes(const stipple_asset* asset, const stipple_player_desc* desc) {
    if (!asset || !desc) return 0;
    stipple::FrameConfig c;
    if (stipple::resolve_frame_config(frame_config_of(*desc), &c).code != stipple::StatusCode::ok)
        return 0;
    const size_t pipeline = stipple::pipeline_memory_bytes(asset->asset, c);
    return pipeline ? stipple::rounded_allocation(sizeof(stipple_player)) + pipeline : 0;
}

}  // extern "C"
