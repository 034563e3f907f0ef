// Morph targets, glTF 2.0 §3.7.2.2 "Morph Targets": the morphed attribute is the base
// attribute plus the weighted sum of the targets' deltas, applied in bind space before
// skinning (§3.7.3: "morph targets are applied before skinning").
#include <cstring>

#include "anim/anim.h"

namespace stipple::anim {
namespace {

// out[0, 3n) += w * delta[0, 3n): a flat loop the compiler vectorises (SSE2/NEON).
void add_scaled(float* out, const float* delta, float w, size_t n3) {
    for (size_t i = 0; i < n3; ++i) out[i] += w * delta[i];
}

bool span_ok(const float* data, size_t size, size_t need) {
    return size >= need && (need == 0 || data != nullptr);
}

// Exact aliasing (in place) is allowed; any other overlap is not.
bool overlap_ok(const float* in, const float* out, size_t n) {
    if (n == 0 || in == out) return true;
    return in + n <= out || out + n <= in;
}

}  // namespace

bool MorphJob::validate() const {
    if (morph == nullptr) return false;
    const size_t n3 = size_t{vertex_count} * 3;
    if (!span_ok(in_positions.data, in_positions.size, n3) ||
        !span_ok(out_positions.data, out_positions.size, n3))
        return false;
    if (in_normals.empty() != out_normals.empty()) return false;
    if (!in_normals.empty() && (!span_ok(in_normals.data, in_normals.size, n3) ||
                                !span_ok(out_normals.data, out_normals.size, n3)))
        return false;
    if (!overlap_ok(in_positions.data, out_positions.data, n3) ||
        !overlap_ok(in_normals.data, out_normals.data, in_normals.empty() ? 0 : n3))
        return false;
    if (!span_ok(weights.data, weights.size, morph->weight_count)) return false;
    if (morph->target_count > 0 && morph->targets == nullptr) return false;
    for (uint32_t i = 0; i < morph->target_count; ++i) {
        const MorphTarget& t = morph->targets[i];
        if (t.weight >= morph->weight_count || t.vertex_begin > vertex_count ||
            t.vertex_count > vertex_count - t.vertex_begin ||
            (t.vertex_count > 0 && t.position_deltas == nullptr))
            return false;
    }
    return true;
}

bool MorphJob::run() const {
    if (!validate()) return false;
    const size_t n3 = size_t{vertex_count} * 3;
    if (out_positions.data != in_positions.data && n3 > 0)
        std::memcpy(out_positions.data, in_positions.data, n3 * sizeof(float));
    const bool normals = !in_normals.empty();
    if (normals && out_normals.data != in_normals.data && n3 > 0)
        std::memcpy(out_normals.data, in_normals.data, n3 * sizeof(float));
    for (uint32_t i = 0; i < morph->target_count; ++i) {
        const MorphTarget& t = morph->targets[i];
        const float w = weights[t.weight];
        // Zero weights (the common case for most targets) cost nothing.
        if (w == 0.0f) continue;
        const size_t begin = size_t{t.vertex_begin} * 3;
        const size_t count = size_t{t.vertex_count} * 3;
        add_scaled(out_positions.data + begin, t.position_deltas, w, count);
        if (normals && t.normal_deltas != nullptr)
            add_scaled(out_normals.data + begin, t.normal_deltas, w, count);
    }
    return true;
}

}  // namespace stipple::anim
