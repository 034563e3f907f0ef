#include "runtime/frame_config.h"

#include <cmath>

namespace stipple {

namespace {

// Zero means the setting's default.
template <typename T>
T or_default(T value, const Setting<T>& s) {
    return value == T(0) ? s.fallback : value;
}

Status out_of_range(const char* field, double value, double min, double max) {
    return make_status(StatusCode::invalid_argument, "%s %g outside [%g, %g]", field, value, min,
                       max);
}

template <typename T>
Status check(const char* field, T value, const Setting<T>& s) {
    if (s.contains(value)) return {};
    return out_of_range(field, double(value), double(s.min), double(s.max));
}

// Light count, intensities, ambient, and directions that are finite and not zero.
Status check_lights(const FrameConfig& c) {
    const FrameSettings& s = kFrameSettings;
    Status st = check("light_count", c.light_count, s.light_count);
    if (st.ok()) st = check("ambient", c.ambient, s.ambient);
    for (int i = 0; st.ok() && i < c.light_count; ++i) {
        st = check("light intensity", c.lights[i].intensity, s.light_intensity);
        const float* d = c.lights[i].direction;
        const float len2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        if (st.ok() && !(len2 > 1e-12f && len2 < 1e30f))
            st = make_status(StatusCode::invalid_argument,
                             "light %d direction (%g, %g, %g) is zero or not finite", i,
                             double(d[0]), double(d[1]), double(d[2]));
    }
    return st;
}

// The first field outside its range, or ok.
Status check_limits(const FrameConfig& c) {
    const FrameSettings& s = kFrameSettings;
    const Status checks[] = {
        check("width", c.width, s.width),
        check("height", c.height, s.height),
        check("zoom", c.zoom, s.zoom),
        check("yaw_degrees", c.yaw_degrees, s.yaw_degrees),
        check("pitch_degrees", c.pitch_degrees, s.pitch_degrees),
        check("fov_degrees", c.fov_degrees, s.fov_degrees),
        c.constant_tone == kLightingTone ? Status()
                                         : check("constant_tone", c.constant_tone, s.constant_tone),
        check("max_point_size", c.max_point_size, s.max_point_size),
        check("smooth_slope", c.smooth_slope, s.smooth_slope),
        check("line_width", c.line_width, s.line_width),
        check("dark_tone", c.dark_tone, s.dark_tone),
        check("refinement_budget", c.refinement_budget, s.refinement_budget),
        check("stroke_quality", c.stroke_quality, s.stroke_quality),
        check("stroke_tol_theta", c.stroke_tol_theta, s.stroke_tol_theta),
        check("stroke_tol_z", c.stroke_tol_z, s.stroke_tol_z),
        check("stroke_vertex_budget", c.stroke_vertex_budget, s.stroke_vertex_budget),
        check("stroke_lod_px", c.stroke_lod_px, s.stroke_lod_px),
        check("stroke_nudge", c.stroke_nudge, s.stroke_nudge),
        check("style", int(c.style), s.style),
        check("toon_bands", c.toon_bands, s.toon_bands),
        check("toon_shade", c.toon_shade, s.toon_shade),
        check("toon_ink", c.toon_ink, s.toon_ink),
        check("tone_gamma", c.tone_gamma, s.tone_gamma),
        check("tone_contrast", c.tone_contrast, s.tone_contrast),
        check("threads", c.threads, s.threads),
        check("particle_budget", c.particle_budget, s.particle_budget),
    };
    for (const Status& st : checks)
        if (!st.ok()) return st;
    const float* colours[4] = {c.background, c.paper, c.ink, c.fill};
    const char* names[4] = {"background channel", "paper channel", "ink channel", "fill channel"};
    for (int k = 0; k < 4; ++k)
        for (int i = 0; i < 3; ++i)
            if (!(colours[k][i] >= 0.0f && colours[k][i] <= 1.0f))
                return out_of_range(names[k], double(colours[k][i]), 0.0, 1.0);
    if (c.path != FramePath::cpu && c.path != FramePath::gpu)
        return make_status(StatusCode::invalid_argument, "path %d is neither cpu (0) nor gpu (1)",
                           int(c.path));
    return check_lights(c);
}

}  // namespace

Status resolve_frame_config(const FrameConfig& in, FrameConfig* out) {
    const FrameSettings& s = kFrameSettings;
    FrameConfig c = in;
    c.width = or_default(c.width, s.width);
    c.height = or_default(c.height, s.height);
    c.zoom = or_default(c.zoom, s.zoom);
    c.fov_degrees = or_default(c.fov_degrees, s.fov_degrees);
    c.max_point_size = or_default(c.max_point_size, s.max_point_size);
    c.smooth_slope = or_default(c.smooth_slope, s.smooth_slope);
    c.line_width = or_default(c.line_width, s.line_width);
    c.stroke_tol_theta = or_default(c.stroke_tol_theta, s.stroke_tol_theta);
    c.stroke_tol_z = or_default(c.stroke_tol_z, s.stroke_tol_z);
    c.stroke_vertex_budget = or_default(c.stroke_vertex_budget, s.stroke_vertex_budget);
    c.toon_bands = or_default(c.toon_bands, s.toon_bands);
    c.tone_gamma = or_default(c.tone_gamma, s.tone_gamma);
    c.tone_contrast = or_default(c.tone_contrast, s.tone_contrast);
    Status st = check_limits(c);
    if (!st.ok()) return st;
    if (c.threads == 0) c.threads = thread_pool_auto_threads();
    for (int i = 0; i < c.light_count; ++i) {  // unit directions
        float* d = c.lights[i].direction;
        const float len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        for (int k = 0; k < 3; ++k) d[k] /= len;
    }
    *out = c;
    return st;
}

FrameConfig default_frame_config() {
    FrameConfig zero;
    zero.width = zero.height = 0;
    zero.zoom = zero.fov_degrees = zero.max_point_size = zero.smooth_slope = zero.line_width = 0;
    zero.stroke_tol_theta = zero.stroke_tol_z = 0;
    zero.stroke_vertex_budget = 0;
    zero.toon_bands = 0;
    zero.tone_gamma = zero.tone_contrast = 0;
    FrameConfig resolved;
    // The table's defaults lie inside its own ranges, so this cannot fail.
    if (!resolve_frame_config(zero, &resolved).ok()) return FrameConfig();
    return resolved;
}

}  // namespace stipple
