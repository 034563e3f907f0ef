// Pose blending over local TRS, after ozz-animation's BlendingJob: a weighted mean of the
// layers' translations and scales, a hemisphere-aligned normalised sum ("nlerp") of their
// rotations, and the rest pose filling in where the accumulated weight is below threshold.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "anim/anim.h"

namespace stipple::anim {
namespace {

bool layer_ok(const BlendLayer& layer, uint32_t node_count, size_t morph_count) {
    if (layer.locals.size < node_count || (node_count > 0 && layer.locals.data == nullptr))
        return false;
    if (!layer.node_weights.empty() &&
        (layer.node_weights.size < node_count || layer.node_weights.data == nullptr))
        return false;
    if (!layer.morph_weights.empty() &&
        (layer.morph_weights.size < morph_count || layer.morph_weights.data == nullptr))
        return false;
    return true;
}

// Accumulates w * pose into acc (10 floats: translation, rotation, scale). The rotation is
// negated when it lies in the other hemisphere from what has been accumulated so far, so
// q and -q (the same rotation) add up instead of cancelling (ozz BlendingJob).
void accumulate(const Trs& pose, float w, Trs* acc) {
    for (int c = 0; c < 3; ++c) {
        acc->translation[c] += w * pose.translation[c];
        acc->scale[c] += w * pose.scale[c];
    }
    const float* q = pose.rotation;
    float* a = acc->rotation;
    const float d = a[0] * q[0] + a[1] * q[1] + a[2] * q[2] + a[3] * q[3];
    const float wq = d < 0.0f ? -w : w;
    for (int c = 0; c < 4; ++c) a[c] += wq * q[c];
}

}  // namespace

bool BlendingJob::validate() const {
    if (skeleton == nullptr) return false;
    const uint32_t n = skeleton->node_count;
    if (n > 0 && skeleton->rest == nullptr) return false;
    if (out.size < n || (n > 0 && out.data == nullptr)) return false;
    if (!(threshold > 0.0f)) return false;
    if (layers.size > 0 && layers.data == nullptr) return false;
    if (out_morph_weights.size > 0 && out_morph_weights.data == nullptr) return false;
    if (!default_morph_weights.empty() && (default_morph_weights.size < out_morph_weights.size ||
                                           default_morph_weights.data == nullptr))
        return false;
    for (size_t l = 0; l < layers.size; ++l) {
        if (!layer_ok(layers[l], n, out_morph_weights.size)) return false;
    }
    return true;
}

bool BlendingJob::run() const {
    if (!validate()) return false;
    const uint32_t n = skeleton->node_count;
    for (uint32_t i = 0; i < n; ++i) {
        Trs acc;
        std::memset(&acc, 0, sizeof(acc));
        float total = 0.0f;
        for (size_t l = 0; l < layers.size; ++l) {
            const BlendLayer& layer = layers[l];
            if (!(layer.weight > 0.0f)) continue;
            float w = layer.weight;
            if (!layer.node_weights.empty()) {
                const float mask = layer.node_weights[i];
                w *= mask > 0.0f ? std::min(mask, 1.0f) : 0.0f;  // NaN mask counts as 0
            }
            if (!(w > 0.0f)) continue;
            accumulate(layer.locals[i], w, &acc);
            total += w;
        }
        // ozz: below the threshold the rest pose makes up the difference, so a node that
        // no layer drives (or drives weakly) eases back to its bind pose instead of being
        // divided by ~0.
        if (total < threshold) {
            accumulate(skeleton->rest[i], threshold - total, &acc);
            total = threshold;
        }
        const float inv = 1.0f / total;
        Trs& o = out[i];
        for (int c = 0; c < 3; ++c) {
            o.translation[c] = acc.translation[c] * inv;
            o.scale[c] = acc.scale[c] * inv;
        }
        const float* q = acc.rotation;
        const float len2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
        if (len2 > 0.0f && std::isfinite(len2)) {
            const float il = 1.0f / std::sqrt(len2);
            for (int c = 0; c < 4; ++c) o.rotation[c] = q[c] * il;
        } else {
            // Opposite rotations with equal weights cancel exactly: fall back to rest.
            std::memcpy(o.rotation, skeleton->rest[i].rotation, sizeof(o.rotation));
        }
    }

    // Morph weights: the same weighted mean, without masks (they are per node).
    const size_t m = out_morph_weights.size;
    if (m > 0) {
        float total = 0.0f;
        std::fill(out_morph_weights.data, out_morph_weights.data + m, 0.0f);
        for (size_t l = 0; l < layers.size; ++l) {
            const BlendLayer& layer = layers[l];
            if (!(layer.weight > 0.0f)) continue;
            total += layer.weight;
            if (layer.morph_weights.empty()) {
                // A layer without morph weights contributes the defaults.
                if (default_morph_weights.empty()) continue;
                for (size_t s = 0; s < m; ++s)
                    out_morph_weights[s] += layer.weight * default_morph_weights[s];
            } else {
                for (size_t s = 0; s < m; ++s)
                    out_morph_weights[s] += layer.weight * layer.morph_weights[s];
            }
        }
        if (total < threshold) {
            if (!default_morph_weights.empty()) {
                for (size_t s = 0; s < m; ++s)
                    out_morph_weights[s] += (threshold - total) * default_morph_weights[s];
            }
            total = threshold;
        }
        const float inv = 1.0f / total;
        for (size_t s = 0; s < m; ++s) out_morph_weights[s] *= inv;
    }
    return true;
}

bool crossfade(const Skeleton& skeleton, Span<const Trs> from, Span<const Trs> to, float alpha,
               Span<Trs> out) {
    const float a = alpha > 0.0f ? std::min(alpha, 1.0f) : 0.0f;  // NaN -> 0
    BlendLayer layers[2];
    layers[0].locals = from;
    layers[0].weight = 1.0f - a;
    layers[1].locals = to;
    layers[1].weight = a;
    BlendingJob job;
    job.skeleton = &skeleton;
    job.layers = Span<const BlendLayer>(layers, 2);
    // Weights always sum to 1 here; a tiny threshold keeps the rest pose out of it.
    job.threshold = 1e-6f;
    job.out = out;
    return job.run();
}

}  // namespace stipple::anim
