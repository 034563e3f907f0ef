// glTF 2.0 animations, §3.11: every animation becomes a clip of channels (target node,
// path, sampler keys). A malformed channel only drops that channel (with a warning), so one
// bad track does not cost the whole asset.
#include <algorithm>
#include <cmath>

#include "anim/finite.h"
#include "bake/gltf_parts.h"

namespace stipple::bake::gltf {

namespace {

// Why a channel is skipped (the message of a malformed_input BakeError).
BakeError skip(std::string why) {
    return malformed_input(std::move(why));
}

// The channel's target: the output node and the path, with its value width in
// *components (a weights channel: the node's morph weight slots).
BakeError read_target(const Model& model, const tinygltf::AnimationChannel& ch,
                      const NodeTable& nodes, const std::vector<MorphSlots>& slots, RawChannel* out,
                      size_t* components) {
    if (ch.target_node < 0) return skip("no target node");
    if (size_t(ch.target_node) >= model.nodes.size()) {
        return skip("target node " + str(ch.target_node) + " out of range (node count " +
                    str(model.nodes.size()) + ")");
    }
    if (nodes.out_index[size_t(ch.target_node)] < 0) {
        return skip("target node " + str(ch.target_node) + " is not in the scene");
    }
    out->node = uint32_t(nodes.out_index[size_t(ch.target_node)]);
    *components = 3;
    if (ch.target_path == "translation") {
        out->path = RawPath::translation;
    } else if (ch.target_path == "rotation") {
        out->path = RawPath::rotation;
        *components = 4;
    } else if (ch.target_path == "scale") {
        out->path = RawPath::scale;
    } else if (ch.target_path == "weights") {
        // §3.11: the node's mesh instance's morph weights, one per target.
        const MorphSlots& s = slots[out->node];
        if (s.count == 0) {
            return skip("target node " + str(ch.target_node) + " has no mesh with morph targets");
        }
        out->path = RawPath::weights;
        out->weight_begin = s.begin;
        out->weight_count = s.count;
        *components = s.count;
    } else {
        return skip("unknown target path '" + ch.target_path + "'");
    }
    return BakeError();
}

BakeError read_interpolation(const tinygltf::AnimationSampler& sampler, RawInterp* out) {
    if (sampler.interpolation == "LINEAR" || sampler.interpolation.empty()) {
        *out = RawInterp::linear;
    } else if (sampler.interpolation == "STEP") {
        *out = RawInterp::step;
    } else if (sampler.interpolation == "CUBICSPLINE") {
        *out = RawInterp::cubic_spline;
    } else {
        return skip("unknown interpolation '" + sampler.interpolation + "'");
    }
    return BakeError();
}

// The sampler's key times and values as written, checked for count and finiteness.
BakeError read_keys(const Model& model, const tinygltf::AnimationSampler& sampler,
                    const RawChannel& channel, size_t components, size_t per_key,
                    std::vector<float>* times, std::vector<float>* values) {
    BakeError read = read_accessor(model, sampler.input, TINYGLTF_TYPE_SCALAR, kF32, times);
    if (!read.ok()) return prefixed("input: ", read);
    // Rotations and weights may be normalized integers (§3.11 "Animations", accessor
    // table); translation and scale are float. Weights outputs are SCALAR, N per key.
    const unsigned formats = channel.path == RawPath::rotation || channel.path == RawPath::weights
                                 ? (kF32 | kI8N | kU8N | kI16N | kU16N)
                                 : kF32;
    const int type = channel.path == RawPath::weights ? TINYGLTF_TYPE_SCALAR
                     : components == 4                ? TINYGLTF_TYPE_VEC4
                                                      : TINYGLTF_TYPE_VEC3;
    read = read_accessor(model, sampler.output, type, formats, values);
    if (!read.ok()) return prefixed("output: ", read);
    if (values->size() != times->size() * per_key) {
        return skip("output count " + str(values->size()) + " floats does not match input count " +
                    str(times->size()) + " x " + str(per_key));
    }
    if (!all_finite(*times) || !all_finite(*values)) return skip("non-finite key time or value");
    return BakeError();
}

// Copies the keys into the channel. §3.11: times are non-negative and strictly increasing.
// Equal neighbours (a common exporter encoding of a jump) keep the later key, which is the
// value after the jump. Rotation keys must be quaternions of non-zero length.
BakeError store_keys(const std::vector<float>& times, std::vector<float>* values, size_t components,
                     size_t per_key, RawChannel* out, std::vector<std::string>* notes) {
    const bool cubic = out->interp == RawInterp::cubic_spline;
    if (times[0] < 0.0f) return skip("negative key time " + std::to_string(times[0]));
    size_t dropped = 0;
    for (size_t k = 0; k < times.size(); ++k) {
        if (k + 1 < times.size() && times[k + 1] < times[k]) {
            return skip("key times decrease at key " + str(k + 1));
        }
        if (k + 1 < times.size() && times[k + 1] == times[k]) {
            ++dropped;
            continue;
        }
        float* value = &(*values)[k * per_key];
        if (components == 4 && out->path == RawPath::rotation) {
            float* q = cubic ? value + 4 : value;  // the value, not the tangents
            const double len = std::sqrt(double(q[0]) * q[0] + double(q[1]) * q[1] +
                                         double(q[2]) * q[2] + double(q[3]) * q[3]);
            if (!(len > 1e-6)) return skip("rotation key " + str(k) + " is not a unit quaternion");
            // LINEAR/STEP keys are normalised; CUBICSPLINE values stay as written, since
            // scaling a value without its tangents would change the curve (the sampler
            // normalises the interpolated result, Appendix C).
            if (!cubic) {
                for (size_t c = 0; c < 4; ++c) q[c] = float(q[c] / len);
            }
        }
        out->times.push_back(times[k]);
        out->values.insert(out->values.end(), value, value + per_key);
    }
    if (dropped) notes->push_back(str(dropped) + " keys with duplicate times dropped");
    return BakeError();
}

// Reads one channel; an error's message says why the channel is skipped.
BakeError read_channel(const Model& model, const tinygltf::Animation& anim,
                       const tinygltf::AnimationChannel& ch, const NodeTable& nodes,
                       const std::vector<MorphSlots>& slots, RawChannel* out,
                       std::vector<std::string>* notes) {
    if (ch.sampler < 0 || size_t(ch.sampler) >= anim.samplers.size()) {
        return skip("sampler " + str(ch.sampler) + " out of range (sampler count " +
                    str(anim.samplers.size()) + ")");
    }
    size_t components = 0;
    BakeError error = read_target(model, ch, nodes, slots, out, &components);
    const tinygltf::AnimationSampler& sampler = anim.samplers[size_t(ch.sampler)];
    if (error.ok()) error = read_interpolation(sampler, &out->interp);
    if (!error.ok()) return error;
    // Appendix C: a CUBICSPLINE key is (in-tangent, value, out-tangent).
    const size_t per_key = components * (out->interp == RawInterp::cubic_spline ? 3 : 1);
    std::vector<float> times;
    std::vector<float> values;
    error = read_keys(model, sampler, *out, components, per_key, &times, &values);
    if (!error.ok()) return error;
    return store_keys(times, &values, components, per_key, out, notes);
}

// One animation as a clip. §3.11: each (node, path) target is used at most once per
// animation; later channels on a target already animated are skipped.
RawClip read_clip(const Model& model, size_t a, const NodeTable& nodes,
                  const std::vector<MorphSlots>& slots, std::vector<std::string>* warnings) {
    const tinygltf::Animation& anim = model.animations[a];
    RawClip clip;
    clip.name = anim.name.empty() ? "clip" + str(a) : anim.name;
    const std::string label = "animation '" + clip.name + "'";
    std::vector<std::pair<uint32_t, RawPath>> targets;
    for (size_t c = 0; c < anim.channels.size(); ++c) {
        const std::string channel_label = label + " channel " + str(c);
        RawChannel channel;
        std::vector<std::string> notes;
        const BakeError read =
            read_channel(model, anim, anim.channels[c], nodes, slots, &channel, &notes);
        if (!read.ok()) {
            warnings->push_back(channel_label + ": " + read.message + "; channel skipped");
            continue;
        }
        const std::pair<uint32_t, RawPath> target(channel.node, channel.path);
        if (std::find(targets.begin(), targets.end(), target) != targets.end()) {
            warnings->push_back(
                channel_label + ": target node " + str(anim.channels[c].target_node) + " '" +
                anim.channels[c].target_path + "' is already animated; channel skipped");
            continue;
        }
        targets.push_back(target);
        for (const std::string& note : notes) warnings->push_back(channel_label + ": " + note);
        clip.duration = std::max(clip.duration, channel.times.back());
        clip.channels.push_back(std::move(channel));
    }
    return clip;
}

}  // namespace

std::vector<RawClip> read_clips(const Model& model, const NodeTable& nodes,
                                const std::vector<MorphSlots>& slots,
                                std::vector<std::string>* warnings) {
    std::vector<RawClip> clips;
    for (size_t a = 0; a < model.animations.size(); ++a) {
        RawClip clip = read_clip(model, a, nodes, slots, warnings);
        if (clip.channels.empty()) {
            warnings->push_back("animation '" + clip.name + "': no usable channels; clip dropped");
            continue;
        }
        clips.push_back(std::move(clip));
    }
    return clips;
}

}  // namespace stipple::bake::gltf
