// The renderer's GLSL ES 3.0 sources: the mesh (depth) pass, whose fragment shaders the
// occluder's depth pass (runtime/renderer_occluder.cpp) shares, the dots and the lines
// (runtime/renderer.cpp).
#pragma once

namespace stipple::shaders {

inline constexpr const char* kMeshVs = R"(#version 300 es
layout(location = 0) in vec3 a_position;
uniform mat4 u_view_projection;
uniform float u_depth_bias;
void main() {
    gl_Position = u_view_projection * vec4(a_position, 1.0);
    gl_Position.z += u_depth_bias * gl_Position.w;
}
)";

// The mesh pass's fragment shader with the depth copy (RendererConfig::depth_copy) and
// without it: no second output to compute when there is nowhere to write it.
inline constexpr const char* kMeshFs = R"(#version 300 es
precision highp float;
uniform vec4 u_paper;
layout(location = 0) out vec4 o_color;
layout(location = 1) out vec4 o_depth;
void main() {
    o_color = vec4(u_paper.rgb, 1.0);
    o_depth = vec4(gl_FragCoord.z);
}
)";

inline constexpr const char* kMeshFsNoCopy = R"(#version 300 es
precision highp float;
uniform vec4 u_paper;
layout(location = 0) out vec4 o_color;
void main() { o_color = vec4(u_paper.rgb, 1.0); }
)";

// Each dot is a disc with a one-pixel linear antialiasing ramp centred on its edge; such a
// disc of radius R lays down pi (R^2 + 1/12) of ink, not pi R^2. So the disc is drawn with
// R^2 = r^2 - 1/12 for the wanted radius r, and dots too small for that are drawn with
// R = 0.5 and proportionally less ink: every diameter d lays down exactly pi (d/2)^2, and tone
// is not quantised (or inflated, by up to 33% for sub-pixel dots) by pixels.
// Visibility is decided once per dot against the mesh pass's depth (read from the depth
// texture in the vertex shader): a dot is drawn whole or not at all. A per-fragment depth
// test would clip each sprite by the surface curving toward the viewer around it and lose up
// to 16% of the ink on small objects (measured: teapot at 2,200 px, tone 0.3). The pass is
// sampled at pixel centres while a dot lies anywhere in its pixel, so testing the centre
// pixel alone dropped dots within half a pixel of the outline (centre off the coverage) and
// dots on slopes whose surface at the pixel centre lies nearer than the dot by more than the
// pass's constant offset (thesis §3.2: the model is drawn "slightly behind the particles ...
// using constant offset values"). Both grow as a pixel spans more surface: at zoom 0.25 they
// cost 3-11% of the ink zoom 1 draws. So a dot that fails at its centre pixel is also tested
// against the depth interpolated bilinearly from the 2x2 texels around its centre (exact on a
// plane; texels off the object count as the far plane), one of them on the object. Taking
// any of the 2x2 texels instead recovered as much but let dots through thin nearer things
// such as paintstroke hairs (docs/tone.md, "Small objects").
inline constexpr const char* kPointVs = R"(#version 300 es
layout(location = 0) in vec3 a_position;
layout(location = 1) in float a_size;
layout(location = 2) in vec4 a_colour;
uniform mat4 u_view_projection;
uniform highp sampler2D u_depth;
uniform int u_see_through;
out float v_radius;
out float v_ink_scale;
flat out vec3 v_colour;
void cull() {
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);  // outside the clip volume: not rasterised
    gl_PointSize = 1.0;
    v_radius = 0.0;
    v_ink_scale = 0.0;
    v_colour = vec3(0.0);
}
void main() {
    if (a_size <= 0.0) {
        cull();
        return;
    }
    gl_Position = u_view_projection * vec4(a_position, 1.0);
    vec3 ndc = gl_Position.xyz / gl_Position.w;
    ivec2 size = textureSize(u_depth, 0);
    ivec2 pixel = ivec2(floor((ndc.xy * 0.5 + 0.5) * vec2(size)));
    if (gl_Position.w <= 0.0 || any(lessThan(pixel, ivec2(0))) || any(greaterThanEqual(pixel, size))) {
        cull();
        return;
    }
    // Seen when the mesh pass is not in front of the dot at its centre pixel, or at the dot's
    // centre as interpolated (bilinearly) from the 2x2 texels around it, one of them on the
    // object; texels off the object count as the far plane there.
    float z = ndc.z * 0.5 + 0.5;
    float centre = texelFetch(u_depth, pixel, 0).r;
    bool seen = (centre < 1.0 || u_see_through != 0) && z <= centre + 1e-5;
    vec2 at = (ndc.xy * 0.5 + 0.5) * vec2(size) - 0.5;
    ivec2 corner = ivec2(floor(at));
    vec2 f = at - vec2(corner);
    float d[4];
    float nearest = 1.0;
    for (int i = 0; i < 4; ++i) {
        d[i] = texelFetch(u_depth, clamp(corner + ivec2(i & 1, i >> 1), ivec2(0), size - 1), 0).r;
        nearest = min(nearest, d[i]);
    }
    float between = mix(mix(d[0], d[1], f.x), mix(d[2], d[3], f.x), f.y);
    seen = seen || ((nearest < 1.0 || u_see_through != 0) && z <= between + 1e-5);
    if (!seen) {
        cull();
        return;
    }
    float wanted = 0.25 * a_size * a_size;  // r^2
    float r = sqrt(max(wanted - 1.0 / 12.0, 0.25));
    v_radius = r;
    v_ink_scale = min(wanted / (r * r + 1.0 / 12.0), 1.0);
    gl_PointSize = 2.0 * r + 1.0;
    v_colour = a_colour.rgb;
}
)";

inline constexpr const char* kPointFs = R"(#version 300 es
precision highp float;
in float v_radius;
in float v_ink_scale;
flat in vec3 v_colour;
uniform vec4 u_ink;
uniform int u_use_colour;
layout(location = 0) out vec4 o_color;
void main() {
    float d = length(gl_PointCoord - vec2(0.5)) * (2.0 * v_radius + 1.0);
    float coverage = clamp(v_radius + 0.5 - d, 0.0, 1.0) * v_ink_scale;
    if (coverage <= 0.0) discard;
    o_color = vec4(u_use_colour == 1 ? v_colour : u_ink.rgb, coverage);
}
)";

inline constexpr const char* kLineVs = R"(#version 300 es
layout(location = 0) in vec3 a_position;
uniform mat4 u_view_projection;
void main() { gl_Position = u_view_projection * vec4(a_position, 1.0); }
)";

inline constexpr const char* kLineFs = R"(#version 300 es
precision highp float;
uniform vec4 u_ink;
layout(location = 0) out vec4 o_color;
void main() { o_color = vec4(u_ink.rgb, 1.0); }
)";

}  // namespace stipple::shaders
