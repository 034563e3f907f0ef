#include "bake/scene_poser.h"

#include <algorithm>
#include <cmath>

#include "bake/raw_anim_view.h"

namespace stipple::bake {

namespace {

// The mesh posed by the runtime's jobs: locals and morph weights in, the morphed and skinned
// vertices out. Holds the buffers so that posing allocates nothing.
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

    void skin_matrices() {
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
        // cannot fail, and if they did the pose would be the bind pose.
        if (!to_model.run() || !to_joints.run())
            std::fill(skin.begin(), skin.end(), glm::mat4(1.0f));
    }

    // Morphs and skins the pose in `locals` / `weights` into `skinned`.
    const float* pose() {
        skin_matrices();
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
        return skinned.data();
    }
};

}  // namespace

std::vector<float> pose_sample_times(const anim::Clip& clip, const PoseSampling& sampling) {
    std::vector<float> t;
    const float duration = std::isfinite(clip.duration) ? std::max(clip.duration, 0.0f) : 0.0f;
    const size_t uniform =
        size_t(std::ceil(double(duration) * double(sampling.samples_per_second))) + 1;
    const size_t cap = std::max<size_t>(sampling.max_samples_per_clip, 2);
    const size_t steps = std::min(std::max<size_t>(uniform, 2), cap);
    for (size_t i = 0; i < steps; ++i) t.push_back(duration * float(i) / float(steps - 1));
    for (uint32_t c = 0; c < clip.channel_count; ++c)
        t.insert(t.end(), clip.channels[c].times,
                 clip.channels[c].times + clip.channels[c].key_count);
    std::sort(t.begin(), t.end());
    t.erase(std::unique(t.begin(), t.end()), t.end());
    if (t.size() > cap) {
        std::vector<float> thin;
        for (size_t i = 0; i < cap; ++i) thin.push_back(t[i * (t.size() - 1) / (cap - 1)]);
        t.swap(thin);
    }
    return t;
}

void for_each_pose(const RawScene& scene, const PoseSampling& sampling,
                   const std::function<void(int clip, const float* positions)>& visit) {
    if (!scene.animated()) {
        visit(-1, scene.positions.data());
        return;
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
    visit(-1, poser.pose());
    for (size_t c = 0; c < view.clips.size(); ++c)
        for (float t : pose_sample_times(view.clips[c], sampling)) {
            anim::SamplingJob job;
            job.skeleton = &view.skeleton;
            job.clip = &view.clips[c];
            job.time = t;
            job.wrap = anim::Wrap::clamp;  // the last key too (looping would sample 0 there)
            job.context = &context;
            job.locals = {poser.locals.data(), poser.locals.size()};
            job.morph_weights = {poser.weights.data(), poser.slots};
            job.default_morph_weights = {view.morph.default_weights, poser.slots};
            if (job.run()) visit(int(c), poser.pose());
        }
}

}  // namespace stipple::bake
