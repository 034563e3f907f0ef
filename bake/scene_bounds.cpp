#include "bake/scene_bounds.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "anim/anim.h"
#include "bake/raw_anim_view.h"

namespace stipple::bake {

namespace {

void box_of(const float* positions, size_t vertex_count, float* box) {
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < vertex_count; ++i)
        for (int k = 0; k < 3; ++k) {
            lo[k] = std::min(lo[k], positions[i * 3 + size_t(k)]);
            hi[k] = std::max(hi[k], positions[i * 3 + size_t(k)]);
        }
    for (int k = 0; k < 3; ++k) {
        box[k] = vertex_count ? lo[k] : 0.0f;
        box[k + 3] = vertex_count ? hi[k] : 0.0f;
    }
}

void grow(float* box, const float* other) {
    for (int k = 0; k < 3; ++k) {
        box[k] = std::min(box[k], other[k]);
        box[k + 3] = std::max(box[k + 3], other[k + 3]);
    }
}

std::vector<float> sample_times(const anim::Clip& clip, const BoundsConfig& config) {
    std::vector<float> t;
    const float duration = std::isfinite(clip.duration) ? std::max(clip.duration, 0.0f) : 0.0f;
    const size_t uniform =
        size_t(std::ceil(double(duration) * double(config.samples_per_second))) + 1;
    const size_t steps = std::min(std::max<size_t>(uniform, 2), config.max_samples_per_clip);
    for (size_t i = 0; i < steps; ++i) t.push_back(duration * float(i) / float(steps - 1));
    for (uint32_t c = 0; c < clip.channel_count; ++c)
        t.insert(t.end(), clip.channels[c].times,
                 clip.channels[c].times + clip.channels[c].key_count);
    std::sort(t.begin(), t.end());
    t.erase(std::unique(t.begin(), t.end()), t.end());
    if (t.size() > config.max_samples_per_clip) {
        std::vector<float> thin;
        const size_t n = config.max_samples_per_clip;
        for (size_t i = 0; i < n; ++i) thin.push_back(t[i * (t.size() - 1) / (n - 1)]);
        t.swap(thin);
    }
    return t;
}

// The mesh posed by the runtime's jobs: locals and morph weights in, the box of the
// morphed and skinned vertices out. Holds the buffers so that posing allocates nothing.
struct Poser {
    const RawScene& scene;
    const RawAnimView& view;
    size_t vertex_count;
    uint32_t slots;
    std::vector<anim::Trs> locals;
    std::vector<glm::mat4> models, skin;
    std::vector<float> weights, morphed, morphed_normals, skinned, skinned_normals;

    Poser(const RawScene& s, const RawAnimView& v)
        : scene(s),
          view(v),
          vertex_count(s.vertex_count()),
          slots(v.morph.weight_count),
          locals(v.skeleton.node_count),
          models(v.skeleton.node_count),
          skin(v.skeleton.joint_count),
          weights(slots + 1),
          morphed(vertex_count * 3),
          morphed_normals(vertex_count * 3),
          skinned(vertex_count * 3),
          skinned_normals(vertex_count * 3) {}

    // Morph, skin and box the pose in `locals` / `weights`.
    void pose_box(float* box) {
        const anim::Skeleton& k = view.skeleton;
        anim::LocalToModelJob to_model;
        to_model.skeleton = &k;
        to_model.locals = {locals.data(), locals.size()};
        to_model.models = {models.data(), models.size()};
        anim::JointMatrixJob to_joints;
        to_joints.skeleton = &k;
        to_joints.models = {models.data(), models.size()};
        to_joints.joint_matrices = {skin.data(), skin.size()};
        // The buffers are sized from this skeleton, which the importer checked: the jobs
        // cannot fail, and if they did the box would be the bind pose's.
        if (!to_model.run() || !to_joints.run())
            std::fill(skin.begin(), skin.end(), glm::mat4(1.0f));
        const size_t floats = vertex_count * 3;
        anim::Span<const float> in_p(scene.positions.data(), floats),
            in_n(scene.normals.data(), floats);
        if (!view.morph_targets.empty()) {
            anim::MorphJob morph;
            morph.morph = &view.morph;
            morph.vertex_count = uint32_t(vertex_count);
            morph.weights = {weights.data(), slots};
            morph.in_positions = in_p;
            morph.in_normals = in_n;
            morph.out_positions = {morphed.data(), floats};
            morph.out_normals = {morphed_normals.data(), floats};
            if (morph.run()) {
                in_p = {morphed.data(), floats};
                in_n = {morphed_normals.data(), floats};
            }
        }
        anim::SkinningJob job;
        job.vertex_count = uint32_t(vertex_count);
        job.joint_matrices = {skin.data(), skin.size()};
        job.joints = {scene.joints.data(), scene.joints.size()};
        job.weights = {scene.weights.data(), scene.weights.size()};
        job.in_positions = in_p;
        job.in_normals = in_n;
        job.out_positions = {skinned.data(), floats};
        job.out_normals = {skinned_normals.data(), floats};
        if (!job.run()) std::copy(in_p.data, in_p.data + floats, skinned.begin());
        box_of(skinned.data(), vertex_count, box);
    }
};

// The box around every pose of `clip` at its sample times; the rest box if none samples.
void clip_box(Poser& poser, const anim::Clip& clip, const BoundsConfig& config,
              anim::SamplingContext* context, const float* rest, float* box) {
    const uint32_t slots = poser.slots;
    bool first = true;
    for (float t : sample_times(clip, config)) {
        anim::SamplingJob job;
        job.skeleton = &poser.view.skeleton;
        job.clip = &clip;
        job.time = t;
        job.wrap = anim::Wrap::clamp;  // the last key too (looping would sample 0 there)
        job.context = context;
        job.locals = {poser.locals.data(), poser.locals.size()};
        job.morph_weights = {poser.weights.data(), slots};
        job.default_morph_weights = {poser.view.morph.default_weights, slots};
        if (!job.run()) continue;
        float pose[6];
        poser.pose_box(pose);
        if (first)
            std::copy(pose, pose + 6, box);
        else
            grow(box, pose);
        first = false;
    }
    if (first) std::copy(rest, rest + 6, box);
}

}  // namespace

SceneBounds compute_scene_bounds(const RawScene& scene, const BoundsConfig& config) {
    SceneBounds out;
    if (!scene.animated()) {
        box_of(scene.positions.data(), scene.vertex_count(), out.rest);
        out.clips.assign(scene.clips.size() * 6, 0.0f);
        for (size_t c = 0; c < scene.clips.size(); ++c)
            std::copy(out.rest, out.rest + 6, out.clips.begin() + long(c) * 6);
        return out;
    }
    RawAnimView view;
    make_anim_view(scene, &view);
    Poser poser(scene, view);
    uint32_t max_channels = 1;
    for (const anim::Clip& c : view.clips) max_channels = std::max(max_channels, c.channel_count);
    std::vector<uint32_t> cursors(max_channels);
    anim::SamplingContext context;
    context.cursors = {cursors.data(), cursors.size()};

    std::copy(view.skeleton.rest, view.skeleton.rest + view.skeleton.node_count,
              poser.locals.begin());
    for (uint32_t i = 0; i < poser.slots; ++i) poser.weights[i] = view.morph.default_weights[i];
    poser.pose_box(out.rest);
    out.clips.assign(view.clips.size() * 6, 0.0f);
    for (size_t c = 0; c < view.clips.size(); ++c)
        clip_box(poser, view.clips[c], config, &context, out.rest, out.clips.data() + c * 6);
    return out;
}

}  // namespace stipple::bake
