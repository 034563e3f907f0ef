// The C API (runtime/stipple.h) over the C++ runtime: no exceptions cross it (the runtime
// is built with -fno-exceptions and allocates with nothrow new).
#include <cstdio>
#include <cstring>
#include <new>

#include "runtime/asset.h"
#include "runtime/frame_pipeline.h"
#include "runtime/stipple.h"

struct stipple_asset {
    stipple::Asset asset;
};

struct stipple_player {
    stipple::Pipeline pipeline;
};

namespace {

thread_local char g_error[256] = "";

stipple_result fail(stipple_result result, const char* message) {
    std::snprintf(g_error, sizeof(g_error), "%s", message);
    return result;
}

stipple_result from_load(const stipple::LoadStatus& st) {
    switch (st.error) {
        case stipple::LoadError::ok:
            return STIPPLE_OK;
        case stipple::LoadError::io_error:
            return fail(STIPPLE_ERROR_IO, st.message);
        case stipple::LoadError::unsupported_version:
            return fail(STIPPLE_ERROR_UNSUPPORTED_VERSION, st.message);
        default:
            return fail(STIPPLE_ERROR_BAD_ASSET, st.message);
    }
}

template <typename Load>
stipple_result load(stipple_asset** out, Load&& load_into) {
    if (!out) return fail(STIPPLE_ERROR_INVALID_ARGUMENT, "out is NULL");
    *out = nullptr;
    stipple_asset* a = new (std::nothrow) stipple_asset();
    if (!a) return fail(STIPPLE_ERROR_OUT_OF_MEMORY, "out of memory");
    stipple_result r = from_load(load_into(&a->asset));
    if (r != STIPPLE_OK) {
        delete a;
        return r;
    }
    *out = a;
    return STIPPLE_OK;
}

}  // namespace

extern "C" {

const char* stipple_last_error(void) {
    return g_error;
}

stipple_result stipple_asset_load_file(const char* path, stipple_asset** out) {
    if (!path) return fail(STIPPLE_ERROR_INVALID_ARGUMENT, "path is NULL");
    return load(out, [&](stipple::Asset* a) { return stipple::load_asset_file(path, a); });
}

stipple_result stipple_asset_load_memory(const void* data, size_t size, stipple_asset** out) {
    if (!data) return fail(STIPPLE_ERROR_INVALID_ARGUMENT, "data is NULL");
    return load(out, [&](stipple::Asset* a) { return stipple::load_asset_memory(data, size, a); });
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

const char* stipple_asset_clip_name(const stipple_asset* a, uint32_t clip) {
    return a && clip < a->asset.clip_count ? a->asset.clips[clip].name : nullptr;
}

float stipple_asset_clip_duration(const stipple_asset* a, uint32_t clip) {
    return a && clip < a->asset.clip_count ? a->asset.clips[clip].duration : 0.0f;
}

int stipple_asset_find_clip(const stipple_asset* a, const char* name) {
    return a && name ? stipple::find_clip(a->asset, name) : -1;
}

stipple_result stipple_player_create(const stipple_asset* asset, const stipple_player_desc* desc,
                                     stipple_player** out) {
    if (!asset || !desc || !out) return fail(STIPPLE_ERROR_INVALID_ARGUMENT, "NULL argument");
    *out = nullptr;
    if (!desc->get_proc_address)
        return fail(STIPPLE_ERROR_INVALID_ARGUMENT, "desc.get_proc_address is required");
    // Defaults for zero fields, in one place.
    stipple::PipelineConfig c;
    c.width = desc->width > 0 ? desc->width : 640;
    c.height = desc->height > 0 ? desc->height : 480;
    c.zoom = desc->zoom > 0 ? desc->zoom : 1.0f;
    c.yaw_degrees = desc->yaw_degrees;
    c.pitch_degrees = desc->pitch_degrees;
    c.constant_tone = desc->use_constant_tone ? desc->constant_tone : -1.0f;
    c.max_point_size = desc->max_point_size > 0 ? desc->max_point_size : 3.0f;
    c.relevance_update = !desc->no_relevance_update;
    if (desc->dark_tone_set) c.dark_tone = desc->dark_tone;
    if (desc->refinement_budget != 0)
        c.refinement_budget = desc->refinement_budget < 0 ? 0u : uint32_t(desc->refinement_budget);
    c.silhouettes = !desc->no_silhouettes;
    c.skinning = desc->dual_quaternion_skinning ? stipple::anim::Skinning::dqs
                                                : stipple::anim::Skinning::lbs;
    if (desc->background_set)
        for (int k = 0; k < 3; ++k)
            c.background[k] = float((desc->background_rgb >> (16 - 8 * k)) & 0xFF) / 255.0f;
    if (c.width > 16384 || c.height > 16384 ||
        (desc->use_constant_tone && !(c.constant_tone >= 0 && c.constant_tone <= 1)))
        return fail(STIPPLE_ERROR_INVALID_ARGUMENT, "size or tone out of range");
    if (!(c.dark_tone >= 0 && c.dark_tone <= 1))
        return fail(STIPPLE_ERROR_INVALID_ARGUMENT, "dark_tone out of [0, 1]");
    if (desc->refinement_budget > (1 << 22))
        return fail(STIPPLE_ERROR_INVALID_ARGUMENT, "refinement_budget above 4194304");

    stipple::GlApi gl;
    if (const char* missing = stipple::load_gl_api(desc->get_proc_address, &gl)) {
        char message[96];
        std::snprintf(message, sizeof(message), "GL entry point %s unavailable", missing);
        return fail(STIPPLE_ERROR_GL, message);
    }
    stipple_player* p = new (std::nothrow) stipple_player();
    if (!p) return fail(STIPPLE_ERROR_OUT_OF_MEMORY, "out of memory");
    char message[256] = {};
    if (!stipple::pipeline_init(&p->pipeline, asset->asset, gl, c, message, sizeof(message))) {
        delete p;
        return fail(STIPPLE_ERROR_GL, message);
    }
    *out = p;
    return STIPPLE_OK;
}

void stipple_player_draw(stipple_player* p, int clip, float time_seconds) {
    if (p) stipple::pipeline_frame(&p->pipeline, clip, time_seconds, nullptr);
}

void stipple_player_draw_blend(stipple_player* p, int clip, float time, int clip2, float time2,
                               float weight2) {
    if (!p) return;
    stipple::AnimationState state;
    state.clip = clip;
    state.time = time;
    state.blend_clip = clip2;
    state.blend_time = time2;
    state.blend_weight = weight2 < 0 ? 0.0f : (weight2 > 1 ? 1.0f : weight2);
    stipple::pipeline_frame(&p->pipeline, state, nullptr);
}

void stipple_player_read_rgba(stipple_player* p, uint8_t* rgba) {
    if (p && rgba) stipple::renderer_read_color(&p->pipeline.renderer, rgba);
}

uint32_t stipple_player_points_drawn(const stipple_player* p) {
    return p ? p->pipeline.points_drawn : 0;
}

void stipple_player_destroy(stipple_player* p) {
    if (!p) return;
    stipple::pipeline_destroy(&p->pipeline);
    delete p;
}

}  // extern "C"
