// Load-time content checks for clips and morph targets (the asset loader calls these after
// checking that every array it hands over exists): everything the sampling and morph jobs
// assume about the data, so a bad asset is rejected with a named error instead of playing
// garbage.
#include <cmath>

#include "anim/anim.h"
#include "anim/finite.h"

namespace stipple::anim {
const char* data_error_name(DataError error) {
    switch (error) {
        case DataError::ok:
            return "ok";
        case DataError::bad_path:
            return "bad_path";
        case DataError::no_keys:
            return "no_keys";
        case DataError::node_out_of_range:
            return "node_out_of_range";
        case DataError::weights_out_of_range:
            return "weights_out_of_range";
        case DataError::times_not_increasing:
            return "times_not_increasing";
        case DataError::non_finite_value:
            return "non_finite_value";
        case DataError::parent_out_of_range:
            return "parent_out_of_range";
        case DataError::joint_out_of_range:
            return "joint_out_of_range";
        case DataError::target_out_of_range:
            return "target_out_of_range";
    }
    return "unknown";
}

DataError check_clip(const Clip& clip, uint32_t node_count, uint32_t morph_weight_count,
                     uint32_t* bad_channel) {
    if (!(clip.duration >= 0.0f) || !std::isfinite(clip.duration)) {
        if (bad_channel != nullptr) *bad_channel = 0;
        return DataError::non_finite_value;
    }
    for (uint32_t i = 0; i < clip.channel_count; ++i) {
        if (bad_channel != nullptr) *bad_channel = i;
        const Channel& c = clip.channels[i];
        if (static_cast<uint8_t>(c.path) > 3 || static_cast<uint8_t>(c.interp) > 2)
            return DataError::bad_path;
        if (c.key_count == 0) return DataError::no_keys;
        if (c.path == Path::weights) {
            if (c.weight_count == 0 || c.weight_begin > morph_weight_count ||
                c.weight_count > morph_weight_count - c.weight_begin)
                return DataError::weights_out_of_range;
        }
        if (c.node >= node_count) return DataError::node_out_of_range;
        if (!std::isfinite(c.times[0])) return DataError::times_not_increasing;
        for (uint32_t k = 1; k < c.key_count; ++k) {
            if (!(c.times[k] > c.times[k - 1]) || !std::isfinite(c.times[k]))
                return DataError::times_not_increasing;
        }
        if (!all_finite(c.values, channel_value_count(c))) return DataError::non_finite_value;
    }
    return DataError::ok;
}

DataError check_morph(const Morph& morph, uint32_t vertex_count) {
    if (morph.weight_count > 0 && !all_finite(morph.default_weights, morph.weight_count))
        return DataError::non_finite_value;
    for (uint32_t i = 0; i < morph.target_count; ++i) {
        const MorphTarget& t = morph.targets[i];
        if (t.weight >= morph.weight_count || t.vertex_begin > vertex_count ||
            t.vertex_count > vertex_count - t.vertex_begin || t.position_deltas == nullptr)
            return DataError::target_out_of_range;
        if (!all_finite(t.position_deltas, size_t{t.vertex_count} * 3) ||
            (t.normal_deltas != nullptr &&
             !all_finite(t.normal_deltas, size_t{t.vertex_count} * 3)))
            return DataError::non_finite_value;
    }
    return DataError::ok;
}

}  // namespace stipple::anim
