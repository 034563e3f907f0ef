// Skeletal animation runtime: clip sampling (STEP, LINEAR, CUBICSPLINE; translation,
// rotation, scale and morph weights), pose blending, morph targets, local-to-model
// transforms, and linear blend (LBS) or dual-quaternion (DQS) skinning.
//
// ozz-animation style (../shared/STYLE.md): every stage is a *job*, a plain struct of input
// and output spans plus validate() and run(). run() validates first and returns false
// without touching any memory when a span is too small or a required input is missing. A
// job never owns or allocates its buffers; each field's comment says the size it needs.
// Nothing here allocates, throws, calls virtual functions or keeps hidden state: the only
// state between frames is the caller-owned SamplingContext.
//
// A frame:  SamplingJob (or several + BlendingJob) -> LocalToModelJob -> JointMatrixJob
//           [-> dqs_joints()] -> MorphJob (if the mesh has morph targets) -> SkinningJob.
//
// Data validity: jobs check buffer *sizes*. Clip and skeleton *contents* are checked once at
// load with check_clip() / check_skeleton(); sampling is nevertheless memory-safe on any
// content (channels naming a node or morph weight outside the outputs are ignored, key
// cursors are clamped, out-of-range joint indices read joint 0).
#pragma once
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace stipple::anim {

// A pointer and an element count: what a job reads or writes. Converts from arrays.
template <typename T>
struct Span {
    T* data = nullptr;
    size_t size = 0;

    constexpr Span() = default;
    constexpr Span(T* d, size_t n) : data(d), size(n) {}
    template <size_t N>
    constexpr Span(T (&array)[N]) : data(array), size(N) {}  // NOLINT: implicit by design
    // Span<T> -> Span<const T>.
    template <typename U>
    constexpr Span(const Span<U>& other) : data(other.data), size(other.size) {}  // NOLINT
    T& operator[](size_t i) const { return data[i]; }
    bool empty() const { return size == 0; }
};

// A node's local transform. Rotation is stored x, y, z, w (glTF order), unit length.
// 10 floats, no padding: Trs arrays are read straight from the asset file.
struct Trs {
    float translation[3];
    float rotation[4];
    float scale[3];
};

// glTF 2.0 §3.11 "Animation": the animated property (channel.target.path).
enum class Path : uint8_t { translation = 0, rotation = 1, scale = 2, weights = 3 };
// glTF 2.0 §3.11 "Animation Samplers" / Appendix C: sampler.interpolation.
enum class Interp : uint8_t { step = 0, linear = 1, cubic_spline = 2 };
// What a clip does outside [0, duration].
enum class Wrap : uint8_t { clamp = 0, loop = 1 };

// One animated property of one node. Views into the loaded asset.
//   times:  key_count seconds, strictly increasing (>= 1 key).
//   values: key_count * width floats for STEP/LINEAR; for CUBICSPLINE key_count * 3 * width,
//           glTF's layout kept as is: per key (in-tangent, value, out-tangent), each `width`
//           floats. width = 3 (translation, scale), 4 (rotation x,y,z,w), or weight_count
//           (weights). Tangents are per second (Appendix C multiplies them by the key gap).
// A weights channel writes morph weights [weight_begin, weight_begin + weight_count) of the
// pose (the slots of `node`'s mesh instance, see Morph); the two fields are 0 otherwise.
struct Channel {
    uint32_t node;
    Path path;
    Interp interp;
    uint32_t key_count;
    const float* times;
    const float* values;
    uint32_t weight_begin;
    uint32_t weight_count;
};

// Floats per key value: 3, 4 or weight_count.
uint32_t channel_width(const Channel& channel);
// Floats `values` must hold: key_count * width, times 3 for CUBICSPLINE.
size_t channel_value_count(const Channel& channel);

struct Clip {
    const char* name;  // NUL-terminated
    float duration;    // seconds, >= 0
    uint32_t channel_count;
    const Channel* channels;
};

// Node hierarchy and skin. parents[i] < i (or -1 for roots): one forward pass suffices.
struct Skeleton {
    uint32_t node_count;
    const int32_t* parents;  // node_count
    const Trs* rest;         // node_count, the bind/rest local transforms
    uint32_t joint_count;
    const uint32_t* joint_nodes;  // joint_count, each < node_count
    const float* inverse_bind;    // joint_count * 16, column-major
};

// ---------------------------------------------------------------------------------------
// Morph targets (glTF 2.0 §3.7.2.2 "Morph Targets") of the merged mesh.
//
// Morph weights live in "slots": every mesh instance (node) with N targets owns N
// consecutive slots. A target applies its deltas to one contiguous vertex range (one
// primitive of that mesh in the merged vertex array), scaled by the weight of its slot:
//   position = base position + sum over targets of weight[slot] * position delta
//   normal   = base normal   + sum over targets of weight[slot] * normal delta  (then the
//              skinning job renormalises it)
// Several targets (one per primitive of the mesh) share a slot.
struct MorphTarget {
    uint32_t weight;               // slot, < Morph::weight_count
    uint32_t vertex_begin;         // first vertex of the range
    uint32_t vertex_count;         // vertices in the range
    const float* position_deltas;  // 3 * vertex_count
    const float* normal_deltas;    // 3 * vertex_count, or nullptr (no normal deltas)
};

struct Morph {
    uint32_t weight_count;         // slots
    const float* default_weights;  // weight_count: node.weights, else mesh.weights, else 0
    uint32_t target_count;
    const MorphTarget* targets;  // target_count
};

// ---------------------------------------------------------------------------------------
// Load-time content checks (for the asset loader): what is wrong, and where.

enum class DataError : uint8_t {
    ok = 0,
    bad_path,              // path or interpolation value unknown
    no_keys,               // key_count == 0
    node_out_of_range,     // channel.node >= node_count
    weights_out_of_range,  // weights channel range outside the morph slots, or width 0
    times_not_increasing,  // key times not strictly increasing (or not finite)
    non_finite_value,      // NaN or infinity in values, or a negative duration
    parent_out_of_range,   // skeleton: parents[i] >= i or < -1
    joint_out_of_range,    // skeleton: joint_nodes[j] >= node_count
    target_out_of_range,   // morph: a target's slot or vertex range is outside its arrays
};
const char* data_error_name(DataError error);

// Checks a clip against the skeleton's node count and the number of morph slots; on error
// *bad_channel (if not null) is the first offending channel. `values` sizes are taken from
// channel_value_count(): the loader must have checked that those floats exist.
[[nodiscard]] DataError check_clip(const Clip& clip, uint32_t node_count,
                                   uint32_t morph_weight_count, uint32_t* bad_channel);
[[nodiscard]] DataError check_skeleton(const Skeleton& skeleton);
[[nodiscard]] DataError check_morph(const Morph& morph, uint32_t vertex_count);

// ---------------------------------------------------------------------------------------
// Sampling

// Per-channel key cursors, reused from frame to frame (ozz's SamplingJob::Context): for
// forward playback each channel moves at most a key or two, so a frame touches only the
// keys it needs instead of binary-searching. Any time, forward or backward, is correct;
// jumps of more than a few keys fall back to a binary search.
struct SamplingContext {
    Span<uint32_t> cursors;      // caller-owned; >= channel_count of every clip sampled with it
    const Clip* clip = nullptr;  // the clip the cursors belong to (run() resets on change)
    void invalidate() { clip = nullptr; }
};

// Writes the clip's pose at `time` into `locals`. Nodes the clip does not animate get their
// rest transform; morph slots no weights channel animates get default_morph_weights (or 0).
//   Wrap::clamp: time is clamped to [0, duration] (NaN samples 0).
//   Wrap::loop:  time is wrapped into [0, duration) (duration 0 samples 0).
// Each channel then holds its first/last key outside its own key range (§3.11).
// Interpolation, glTF 2.0 Appendix C: STEP holds the key at or before t; LINEAR lerps, and
// slerps rotations on the shortest arc; CUBICSPLINE evaluates the Hermite spline (rotations
// are normalised afterwards). Rotation outputs are always unit length.
struct SamplingJob {
    const Skeleton* skeleton = nullptr;
    const Clip* clip = nullptr;
    float time = 0.0f;
    Wrap wrap = Wrap::clamp;
    SamplingContext* context = nullptr;       // optional; cursors >= clip->channel_count
    Span<Trs> locals;                         // >= skeleton->node_count
    Span<float> morph_weights;                // optional output, one per morph slot
    Span<const float> default_morph_weights;  // empty (zeros) or >= morph_weights.size
    [[nodiscard]] bool validate() const;
    [[nodiscard]] bool run() const;
};

// ---------------------------------------------------------------------------------------
// Blending (ozz BlendingJob): weighted average of N poses, per node.
//   translation, scale: sum(w_i * x_i) / sum(w_i)
//   rotation: normalised sum of w_i * q_i, each q_i negated if it lies in the other
//             hemisphere from the running sum ("nlerp"; exact for 2 layers up to the nlerp
//             vs slerp speed difference)
//   w_i = layer weight * node mask weight (1 without a mask). Where sum(w_i) < threshold,
//   the rest pose fills the deficit with weight (threshold - sum), so a node no layer
//   drives (masked out everywhere, or all weights 0) returns to its rest pose.
// Morph weights blend the same way (weighted mean, rest = default weights).
struct BlendLayer {
    Span<const Trs> locals;           // >= node_count
    float weight = 0.0f;              // <= 0 (or NaN): the layer is skipped
    Span<const float> node_weights;   // optional per-node mask in [0, 1]; >= node_count
    Span<const float> morph_weights;  // optional; >= out_morph_weights.size
};

struct BlendingJob {
    const Skeleton* skeleton = nullptr;  // node_count and the rest pose
    Span<const BlendLayer> layers;
    float threshold = 0.1f;                   // > 0
    Span<Trs> out;                            // >= node_count
    Span<float> out_morph_weights;            // optional
    Span<const float> default_morph_weights;  // empty (zeros) or >= out_morph_weights.size
    [[nodiscard]] bool validate() const;
    [[nodiscard]] bool run() const;
};

// Crossfade from `from` to `to` (alpha 0 -> 1): a two-layer BlendingJob.
[[nodiscard]] bool crossfade(const Skeleton& skeleton, Span<const Trs> from, Span<const Trs> to,
                             float alpha, Span<Trs> out);

// ---------------------------------------------------------------------------------------
// Hierarchy

// model[i] = model[parent[i]] * (T * R * S)(locals[i])  (glTF 2.0 §3.5.3).
struct LocalToModelJob {
    const Skeleton* skeleton = nullptr;
    Span<const Trs> locals;  // >= node_count
    Span<glm::mat4> models;  // >= node_count
    [[nodiscard]] bool validate() const;
    [[nodiscard]] bool run() const;
};

// skin[j] = model[joint_nodes[j]] * inverse_bind[j]  (glTF 2.0 §3.7.3 joint matrix).
struct JointMatrixJob {
    const Skeleton* skeleton = nullptr;
    Span<const glm::mat4> models;    // >= node_count
    Span<glm::mat4> joint_matrices;  // >= joint_count
    [[nodiscard]] bool validate() const;
    [[nodiscard]] bool run() const;
};

// ---------------------------------------------------------------------------------------
// Morph targets: out = in + sum of weighted deltas (see Morph). Applied before skinning, in
// bind space. out may be the same buffer as in; otherwise they must not overlap. Normals
// are optional (both spans empty) and are not renormalised here.
struct MorphJob {
    const Morph* morph = nullptr;
    uint32_t vertex_count = 0;
    Span<const float> weights;            // >= morph->weight_count
    Span<const float> in_positions;       // >= 3 * vertex_count
    Span<const float> in_normals;         // empty, or >= 3 * vertex_count
    Span<float> out_positions;            // >= 3 * vertex_count
    Span<float> out_normals;              // empty iff in_normals is; else >= 3 * vertex_count
    [[nodiscard]] bool validate() const;  // also checks every target's range fits vertex_count
    [[nodiscard]] bool run() const;
};

// ---------------------------------------------------------------------------------------
// Skinning

// A joint for dual-quaternion skinning (Kavan, Collins, Zara, O'Sullivan 2007, "Skinning
// with dual quaternions"): the joint matrix M is split into M = [R | t] * S, where [R | t]
// is rigid (the unit dual quaternion real + eps dual, dual = 0.5 * (t, 0) * real) and S is
// the remaining 3x3 (scale/shear; the identity for rigid joints). S is blended linearly and
// applied first, the dual quaternions are blended by DLB ("two-phase" skinning, Kavan et al.
// §4 on non-rigid joints).
struct DqsJoint {
    float real[4];      // rotation quaternion x, y, z, w (unit)
    float dual[4];      // x, y, z, w
    float stretch[12];  // S, 3 columns of (x, y, z, 0)
};

// Converts joint matrices to DQS joints. Returns false on size mismatch (out.size <
// joint_matrices.size); *stretched (optional) = number of joints whose S is not the
// identity (within 1e-5): 0 means SkinningJob::dq_rigid may be set.
[[nodiscard]] bool dqs_joints(Span<const glm::mat4> joint_matrices, Span<DqsJoint> out,
                              uint32_t* stretched);

enum class Skinning : uint8_t { lbs = 0, dqs = 1 };

// Skins positions (and normals, optional) by 4 influences per vertex.
//   LBS (glTF 2.0 §3.7.3): M = sum w_k joint_matrices[j_k]; p' = M p; n' = normalise(M3x3 n)
//       (exact for rigid and uniformly scaled joints, the glTF convention).
//   DQS (Kavan et al. 2007, DLB): dual quaternions blended with signs aligned to the first
//       influence, normalised, applied to S-blended p and n; n' is renormalised.
// Joint indices >= the palette size read joint 0. Weights are used as given (the bake
// renormalises them). out may be the same buffer as in; otherwise they must not overlap.
// run() picks the SIMD path (SSE2, NEON) where compiled in; run_scalar() is the portable
// reference, kept bit-for-bit simple, which the SIMD path matches to ~1e-6 relative.
struct SkinningJob {
    Skinning method = Skinning::lbs;
    uint32_t vertex_count = 0;
    Span<const glm::mat4> joint_matrices;  // LBS: the palette (joint count entries, >= 1)
    Span<const DqsJoint> dq_joints;        // DQS: the palette from dqs_joints() (>= 1)
    bool dq_rigid = false;                 // DQS: every S is identity (skips the S blend)
    Span<const uint16_t> joints;           // >= 4 * vertex_count
    Span<const float> weights;             // >= 4 * vertex_count
    Span<const float> in_positions;        // >= 3 * vertex_count
    Span<const float> in_normals;          // empty, or >= 3 * vertex_count
    Span<float> out_positions;             // >= 3 * vertex_count
    Span<float> out_normals;               // empty iff in_normals is; else >= 3 * vertex_count
    [[nodiscard]] bool validate() const;
    [[nodiscard]] bool run() const;
    [[nodiscard]] bool run_scalar() const;
};

// "sse2", "neon" or "scalar": the path SkinningJob::run() and the hierarchy jobs use.
const char* simd_path();

}  // namespace stipple::anim
