// Clip sampling: glTF 2.0 §3.11 "Animation" and its samplers, with the interpolation
// formulas of Appendix C "Animation Sampler Interpolation Modes" (STEP, LINEAR,
// CUBICSPLINE), for translation, rotation, scale and morph weights.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "anim/anim.h"

namespace stipple::anim {
namespace {

// Linear scan length before a cursor falls back to binary search. Forward playback at any
// frame rate above the key rate moves 0 or 1 keys per frame.
constexpr uint32_t kCursorScan = 4;

// Index k of the key interval holding t: times[k] <= t < times[k + 1]; 0 when t is before
// the first key, key_count - 1 at or after the last. `k` is the cursor from the previous
// sample (any value; out-of-range cursors restart at 0).
inline uint32_t seek(const float* times, uint32_t n, float t, uint32_t k) {
    if (k >= n) k = 0;
    if (t >= times[k]) {
        for (uint32_t step = 0; step < kCursorScan; ++step) {
            if (k + 1 >= n || t < times[k + 1]) return k;
            ++k;
        }
        // First key strictly after t, so t == times[k] gives exactly key k.
        return static_cast<uint32_t>(std::upper_bound(times + k, times + n, t) - times) - 1;
    }
    for (uint32_t step = 0; step < kCursorScan; ++step) {
        if (k == 0) return 0;
        --k;
        if (t >= times[k]) return k;
    }
    const uint32_t upper = static_cast<uint32_t>(std::upper_bound(times, times + k, t) - times);
    return upper == 0 ? 0 : upper - 1;
}

void lerp(const float* a, const float* b, float alpha, uint32_t width, float* out) {
    for (uint32_t c = 0; c < width; ++c) out[c] = a[c] + (b[c] - a[c]) * alpha;
}

void normalise_quat(float* q) {
    const float len2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
    if (len2 > 0.0f && std::isfinite(len2)) {
        const float inv_len = 1.0f / std::sqrt(len2);
        for (int c = 0; c < 4; ++c) q[c] *= inv_len;
    } else {
        // Only reachable with zero-length or non-finite keys (a malformed asset): identity.
        q[0] = q[1] = q[2] = 0.0f;
        q[3] = 1.0f;
    }
}

// Appendix C, LINEAR on rotations: spherical linear interpolation on the shortest arc
// (the second key is negated when the dot product is negative), then normalised.
// slerp(a, b, t) = sin((1-t) theta)/sin(theta) a + sin(t theta)/sin(theta) b is evaluated
// with D. Eberly's polynomial form ("A Fast and Accurate Algorithm for Computing SLERP",
// J. Graphics, GPU, and Game Tools 15(3), 2011): the two coefficients as degree-8
// polynomials in (cos theta - 1) and t^2, no trigonometry, no division, no branch for
// nearly equal keys. After normalisation the result's angle differs from exact slerp by at
// most 7.3e-6 rad for keys 180 degrees apart (the worst case on the shortest arc; measured
// in float 1.5e-5), 2.5e-7 rad for keys up to 120 degrees apart and < 1e-8 rad below 90:
// float rounding dominates for real clips (tests/anim/test_sampling_job.cpp checks it against
// double-precision slerp).
void slerp_shortest(const float* a, const float* b, float t, float* out) {
    // Series terms u_i = 1 / (i (2i + 1)), v_i = i / (2i + 1), i = 1..8. kU/kV carry Eberly's
    // factor on the last term, balancing the truncation error of the full 8-term series;
    // 1.87 minimises the worst angular error over the shortest arc (fitted in double).
    static constexpr float kMu = 1.87f;
    static constexpr float kUp[8] = {1.0f / (1 * 3),  1.0f / (2 * 5),  1.0f / (3 * 7),
                                     1.0f / (4 * 9),  1.0f / (5 * 11), 1.0f / (6 * 13),
                                     1.0f / (7 * 15), 1.0f / (8 * 17)};
    static constexpr float kVp[8] = {1.0f / 3,  2.0f / 5,  3.0f / 7,  4.0f / 9,
                                     5.0f / 11, 6.0f / 13, 7.0f / 15, 8.0f / 17};
    static constexpr float kU[8] = {kUp[0], kUp[1], kUp[2], kUp[3],
                                    kUp[4], kUp[5], kUp[6], kMu * kUp[7]};
    static constexpr float kV[8] = {kVp[0], kVp[1], kVp[2], kVp[3],
                                    kVp[4], kVp[5], kVp[6], kMu * kVp[7]};
    float x = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
    const float sign = x < 0.0f ? -1.0f : 1.0f;
    x *= sign;
    // The series' terms shrink like (1 - x)^i, so nearby keys need fewer of them; the Horner
    // chain below is latency-bound, so this is most of the cost. Truncation error (angle, in
    // double): 4 terms for x >= 0.98 (keys up to 23 degrees apart) < 1e-12 rad, 6 terms for
    // x >= 0.85 < 3e-10, 7 terms for x >= 0.7 < 1e-8; below that all 8 with kMu.
    const int terms = x >= 0.98f ? 4 : x >= 0.85f ? 6 : x >= 0.7f ? 7 : 8;
    const float* u = terms == 8 ? kU : kUp;
    const float* v = terms == 8 ? kV : kVp;
    const float xm1 = x - 1.0f;
    const float d = 1.0f - t;
    const float t2 = t * t;
    const float d2 = d * d;
    float ct = 1.0f;
    float cd = 1.0f;
    for (int i = terms - 1; i >= 0; --i) {
        ct = 1.0f + (u[i] * t2 - v[i]) * xm1 * ct;
        cd = 1.0f + (u[i] * d2 - v[i]) * xm1 * cd;
    }
    ct *= t * sign;
    cd *= d;
    for (int c = 0; c < 4; ++c) out[c] = cd * a[c] + ct * b[c];
    normalise_quat(out);
}

// Appendix C, CUBICSPLINE: with s in [0, 1] the normalised time in the key interval and
// td its length in seconds,
//   p(s) = (2s^3 - 3s^2 + 1) v_k + td (s^3 - 2s^2 + s) b_k + (-2s^3 + 3s^2) v_k+1
//          + td (s^3 - s^2) a_k+1
// where b_k is key k's out-tangent and a_k+1 key k+1's in-tangent. Key k's triple is
// (a_k, v_k, b_k), each `width` floats.
void cubic(const float* values, uint32_t k, uint32_t width, float s, float td, float* out) {
    const float* v0 = values + (3 * static_cast<size_t>(k) + 1) * width;
    const float* b0 = v0 + width;
    const float* a1 = b0 + width;
    const float* v1 = a1 + width;
    const float s2 = s * s;
    const float s3 = s2 * s;
    const float h00 = 2.0f * s3 - 3.0f * s2 + 1.0f;
    const float h10 = td * (s3 - 2.0f * s2 + s);
    const float h01 = -2.0f * s3 + 3.0f * s2;
    const float h11 = td * (s3 - s2);
    for (uint32_t c = 0; c < width; ++c) {
        out[c] = h00 * v0[c] + h10 * b0[c] + h01 * v1[c] + h11 * a1[c];
    }
}

// Samples one channel at t into `out` (width floats). Returns the new cursor.
inline uint32_t sample_channel(const Channel& channel, uint32_t width, float t, uint32_t cursor,
                               float* out) {
    const uint32_t n = channel.key_count;
    const uint32_t k = seek(channel.times, n, t, cursor);
    const bool cubic_spline = channel.interp == Interp::cubic_spline;
    const size_t stride = cubic_spline ? 3 * size_t{width} : width;
    // The value of key k: for CUBICSPLINE the middle of its (in, value, out) triple.
    const float* vk = channel.values + k * stride + (cubic_spline ? width : 0);
    if (k + 1 >= n || channel.interp == Interp::step) {
        // Appendix C, STEP: the key at or before t; after the last key (§3.11) the last value.
        std::memcpy(out, vk, width * sizeof(float));
        return k;
    }
    const float t0 = channel.times[k];
    const float td = channel.times[k + 1] - t0;
    // Before the first key t < t0: alpha clamps to 0, which is key 0's value (§3.11).
    // Times are strictly increasing; equal times (malformed) hold key k.
    float alpha = td > 0.0f ? (t - t0) / td : 0.0f;
    alpha = std::min(std::max(alpha, 0.0f), 1.0f);
    if (cubic_spline) {
        cubic(channel.values, k, width, alpha, td, out);
        if (channel.path == Path::rotation) normalise_quat(out);
    } else if (channel.path == Path::rotation) {
        slerp_shortest(vk, vk + 4, alpha, out);
    } else {
        lerp(vk, vk + width, alpha, width, out);
    }
    return k;
}

float wrap_time(float time, float duration, Wrap wrap) {
    if (wrap == Wrap::loop) {
        if (!(duration > 0.0f) || !std::isfinite(time)) return 0.0f;
        float t = std::fmod(time, duration);
        if (t < 0.0f) t += duration;
        // fmod of a tiny negative time can round up to exactly `duration`.
        return t < duration ? t : 0.0f;
    }
    // Clamp; NaN samples the start.
    float t = time >= 0.0f ? time : 0.0f;
    if (t > duration) t = duration;
    return t;
}

}  // namespace

uint32_t channel_width(const Channel& channel) {
    switch (channel.path) {
        case Path::translation:
        case Path::scale:
            return 3;
        case Path::rotation:
            return 4;
        case Path::weights:
            return channel.weight_count;
    }
    return 0;
}

size_t channel_value_count(const Channel& channel) {
    const size_t per_key =
        size_t{channel_width(channel)} * (channel.interp == Interp::cubic_spline ? 3u : 1u);
    return per_key * channel.key_count;
}

bool SamplingJob::validate() const {
    if (skeleton == nullptr || clip == nullptr) return false;
    if (locals.size < skeleton->node_count || (skeleton->node_count > 0 && locals.data == nullptr))
        return false;
    if (skeleton->node_count > 0 && skeleton->rest == nullptr) return false;
    if (clip->channel_count > 0 && clip->channels == nullptr) return false;
    if (context != nullptr) {
        if (context->cursors.size < clip->channel_count) return false;
        if (clip->channel_count > 0 && context->cursors.data == nullptr) return false;
    }
    if (morph_weights.size > 0 && morph_weights.data == nullptr) return false;
    if (!default_morph_weights.empty() &&
        (default_morph_weights.size < morph_weights.size || default_morph_weights.data == nullptr))
        return false;
    return true;
}

bool SamplingJob::run() const {
    if (!validate()) return false;
    const uint32_t node_count = skeleton->node_count;
    if (node_count > 0) std::memcpy(locals.data, skeleton->rest, node_count * sizeof(Trs));
    if (!morph_weights.empty()) {
        if (default_morph_weights.empty()) {
            std::fill(morph_weights.data, morph_weights.data + morph_weights.size, 0.0f);
        } else {
            std::memcpy(morph_weights.data, default_morph_weights.data,
                        morph_weights.size * sizeof(float));
        }
    }
    uint32_t* cursors = nullptr;
    if (context != nullptr) {
        cursors = context->cursors.data;
        if (context->clip != clip) {
            std::fill(cursors, cursors + clip->channel_count, 0u);
            context->clip = clip;
        }
    }
    const float t = wrap_time(time, clip->duration, wrap);
    for (uint32_t i = 0; i < clip->channel_count; ++i) {
        const Channel& channel = clip->channels[i];
        // Channels with no keys, or aimed outside the outputs, are ignored (check_clip
        // rejects them at load; this keeps sampling memory-safe regardless).
        if (channel.key_count == 0 || static_cast<uint8_t>(channel.interp) > 2) continue;
        float* out = nullptr;
        uint32_t width = 0;
        switch (channel.path) {
            case Path::translation:
                if (channel.node < node_count) out = locals.data[channel.node].translation;
                width = 3;
                break;
            case Path::rotation:
                if (channel.node < node_count) out = locals.data[channel.node].rotation;
                width = 4;
                break;
            case Path::scale:
                if (channel.node < node_count) out = locals.data[channel.node].scale;
                width = 3;
                break;
            case Path::weights:
                width = channel.weight_count;
                if (width > 0 && channel.weight_begin <= morph_weights.size &&
                    width <= morph_weights.size - channel.weight_begin) {
                    out = morph_weights.data + channel.weight_begin;
                }
                break;
        }
        if (out == nullptr) continue;
        const uint32_t cursor = cursors != nullptr ? cursors[i] : 0u;
        const uint32_t next = sample_channel(channel, width, t, cursor, out);
        if (cursors != nullptr) cursors[i] = next;
    }
    return true;
}

}  // namespace stipple::anim
