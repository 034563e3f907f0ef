// Clip sampling: glTF 2.0 §3.11 "Animation" and its samplers, with the interpolation
// formulas of Appendix C "Animation Sampler Interpolation Modes" (STEP and LINEAR; CUBICSPLINE
// is resolved to LINEAR by the importer).
#include <algorithm>
#include <cmath>
#include <cstring>

#include "anim/anim.h"

namespace stipple::anim {
namespace {

// Where `t` falls among a channel's keys: the value is key k0 blended towards k1 by alpha.
// glTF 2.0 §3.11 "Animation Samplers": times outside [first key, last key] clamp to the
// first or last key's value.
struct KeySpan {
    uint32_t k0;
    uint32_t k1;
    float alpha;  // in [0, 1]; 0 when k0 == k1
};

KeySpan find_keys(const Channel& channel, float t) {
    const float* first = channel.times;
    const float* last = channel.times + channel.key_count;
    // First key strictly after t, so t == times[k] gives exactly key k (alpha 0).
    const uint32_t upper = static_cast<uint32_t>(std::upper_bound(first, last, t) - first);
    if (upper == 0) return {0, 0, 0.0f};  // before the first key
    if (upper == channel.key_count) {     // at or after the last key
        return {channel.key_count - 1, channel.key_count - 1, 0.0f};
    }
    const uint32_t k0 = upper - 1;
    const float t0 = channel.times[k0];
    const float dt = channel.times[upper] - t0;
    // Times are strictly increasing; a malformed asset with equal times holds the earlier key
    // instead of dividing by zero.
    const float alpha = dt > 0.0f ? std::min((t - t0) / dt, 1.0f) : 0.0f;
    return {k0, upper, alpha};
}

void lerp3(const float* a, const float* b, float alpha, float* out) {
    for (int c = 0; c < 3; ++c) out[c] = a[c] + (b[c] - a[c]) * alpha;
}

// Appendix C, LINEAR on rotations: spherical linear interpolation on the shortest arc
// (negate the second key if the dot product is negative), then normalise. Quaternions are
// x, y, z, w (glTF order); the formula is the same for any component order.
void slerp_shortest(const float* a, const float* b, float alpha, float* out) {
    float d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
    float sign = 1.0f;
    if (d < 0.0f) {
        d = -d;
        sign = -1.0f;
    }
    float wa;
    float wb;
    if (d > 0.9995f) {
        // Keys almost equal: sin(theta) -> 0, and lerp is exact to float precision.
        wa = 1.0f - alpha;
        wb = alpha;
    } else {
        const float theta = std::acos(d);
        const float inv_sin = 1.0f / std::sin(theta);
        wa = std::sin((1.0f - alpha) * theta) * inv_sin;
        wb = std::sin(alpha * theta) * inv_sin;
    }
    wb *= sign;
    float q[4];
    for (int c = 0; c < 4; ++c) q[c] = wa * a[c] + wb * b[c];
    const float len2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
    if (len2 > 0.0f) {
        const float inv_len = 1.0f / std::sqrt(len2);
        for (int c = 0; c < 4; ++c) out[c] = q[c] * inv_len;
    } else {
        // Only reachable with zero-length keys (a malformed asset): fall back to identity.
        out[0] = out[1] = out[2] = 0.0f;
        out[3] = 1.0f;
    }
}

void sample_channel(const Channel& channel, float t, Trs& local) {
    const uint32_t width = channel.path == Path::rotation ? 4u : 3u;
    float* out = channel.path == Path::translation ? local.translation
                 : channel.path == Path::rotation  ? local.rotation
                                                   : local.scale;
    const KeySpan span = find_keys(channel, t);
    const float* v0 = channel.values + static_cast<size_t>(span.k0) * width;
    // Appendix C, STEP: the value of the key at or before t.
    if (channel.interp == Interp::step || span.k0 == span.k1) {
        std::memcpy(out, v0, width * sizeof(float));
        return;
    }
    const float* v1 = channel.values + static_cast<size_t>(span.k1) * width;
    if (channel.path == Path::rotation) {
        slerp_shortest(v0, v1, span.alpha, out);
    } else {
        lerp3(v0, v1, span.alpha, out);
    }
}

}  // namespace

void rest_pose(const Skeleton& skeleton, Trs* locals) {
    if (skeleton.node_count == 0) return;
    std::memcpy(locals, skeleton.rest, skeleton.node_count * sizeof(Trs));
}

void sample_clip(const Skeleton& skeleton, const Clip& clip, float time, Trs* locals) {
    rest_pose(skeleton, locals);
    // Clamp to [0, duration]; NaN samples the start. Each channel then clamps to its own keys.
    float t = time >= 0.0f ? time : 0.0f;
    if (t > clip.duration) t = clip.duration;
    for (uint32_t i = 0; i < clip.channel_count; ++i) {
        const Channel& channel = clip.channels[i];
        // A channel targeting a node outside the skeleton, or with no keys, is ignored.
        if (channel.node >= skeleton.node_count || channel.key_count == 0) continue;
        sample_channel(channel, t, locals[channel.node]);
    }
}

}  // namespace stipple::anim
