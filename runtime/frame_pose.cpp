#include "runtime/frame_pose.h"

#include <algorithm>
#include <cstring>

namespace stipple {

namespace {

// Samples clip `clip` at `time` into pose slot `slot` (locals and morph weights), with that
// slot's sampling context so forward playback only touches the keys it needs.
void sample_pose(Pipeline* p, int slot, int clip, float time) {
    const Asset& a = *p->asset;
    const anim::Skeleton& k = a.skin.skeleton;
    const uint32_t slots = a.morph.weight_count;
    anim::Span<float> weights(p->morph_weights[slot].get(), slots);
    anim::Span<const float> defaults(a.morph.default_weights, a.morph.default_weights ? slots : 0);
    if (clip < 0 || uint32_t(clip) >= a.clip_count) {
        std::copy(k.rest, k.rest + k.node_count, p->locals[slot].get());
        for (uint32_t i = 0; i < slots; ++i) weights[i] = defaults.size ? defaults[i] : 0.0f;
        return;
    }
    anim::SamplingJob job;
    job.skeleton = &k;
    job.clip = &a.clips[clip];
    job.time = time;
    job.wrap = anim::Wrap::loop;
    job.context = &p->contexts[slot];
    job.locals = anim::Span<anim::Trs>(p->locals[slot].get(), k.node_count);
    job.morph_weights = weights;
    job.default_morph_weights = defaults;
    expect_ran(job.run());
}

}  // namespace

void pose_mesh(Pipeline* p, const AnimationState& state, StageTimes* t,
               StageClock::time_point* clock) {
    const Asset& a = *p->asset;
    const MeshView& m = a.mesh;
    if (!a.skinned) {
        std::memcpy(p->vertex_positions.get(), m.positions, size_t(m.vertex_count) * 12);
        std::memcpy(p->vertex_normals.get(), m.normals, size_t(m.vertex_count) * 12);
        if (t) t->skin += ms_since(clock);
        return;
    }
    const anim::Skeleton& k = a.skin.skeleton;
    const uint32_t slots = a.morph.weight_count;
    sample_pose(p, 0, state.clip, state.time);
    int pose = 0;
    if (state.blend_clip >= 0 && state.blend_weight > 0.0f) {
        // ozz-style weighted layering of the two sampled poses (nlerp of rotations).
        sample_pose(p, 1, state.blend_clip, state.blend_time);
        const float w = std::min(state.blend_weight, 1.0f);
        const anim::BlendLayer layers[2] = {
            {{p->locals[0].get(), k.node_count}, 1.0f - w, {}, {p->morph_weights[0].get(), slots}},
            {{p->locals[1].get(), k.node_count}, w, {}, {p->morph_weights[1].get(), slots}}};
        anim::BlendingJob blend;
        blend.skeleton = &k;
        blend.layers = layers;
        blend.out = anim::Span<anim::Trs>(p->locals[2].get(), k.node_count);
        blend.out_morph_weights = anim::Span<float>(p->morph_weights[2].get(), slots);
        if (blend.run()) pose = 2;
    }
    anim::LocalToModelJob hierarchy;
    hierarchy.skeleton = &k;
    hierarchy.locals = {p->locals[pose].get(), k.node_count};
    hierarchy.models = {p->models.get(), k.node_count};
    expect_ran(hierarchy.run());
    anim::JointMatrixJob joints;
    joints.skeleton = &k;
    joints.models = {p->models.get(), k.node_count};
    joints.joint_matrices = {p->skin_matrices.get(), k.joint_count};
    expect_ran(joints.run());
    anim::SkinningJob skin;
    skin.method = p->config.skinning;
    if (skin.method == anim::Skinning::dqs) {
        uint32_t stretched = 0;
        expect_ran(anim::dqs_joints({p->skin_matrices.get(), k.joint_count},
                                    {p->dq_joints.get(), k.joint_count}, &stretched));
        skin.dq_joints = {p->dq_joints.get(), k.joint_count};
        skin.dq_rigid = stretched == 0;
    }
    if (t) t->sample += ms_since(clock);

    const size_t floats = size_t(m.vertex_count) * 3;
    anim::Span<const float> in_positions(m.positions, floats), in_normals(m.normals, floats);
    anim::Span<float> out_positions(p->vertex_positions.get(), floats);
    anim::Span<float> out_normals(p->vertex_normals.get(), floats);
    if (a.has_morph()) {  // morph targets apply in bind space, before skinning
        anim::MorphJob morph;
        morph.morph = &a.morph;
        morph.vertex_count = m.vertex_count;
        morph.weights = {p->morph_weights[pose].get(), slots};
        morph.in_positions = in_positions;
        morph.in_normals = in_normals;
        morph.out_positions = out_positions;
        morph.out_normals = out_normals;
        if (morph.run()) {
            in_positions = out_positions;
            in_normals = out_normals;
        }
    }
    skin.vertex_count = m.vertex_count;
    skin.joint_matrices = {p->skin_matrices.get(), k.joint_count};
    skin.joints = {a.skin.joints, size_t(m.vertex_count) * 4};
    skin.weights = {a.skin.weights, size_t(m.vertex_count) * 4};
    skin.in_positions = in_positions;
    skin.in_normals = in_normals;
    skin.out_positions = out_positions;
    skin.out_normals = out_normals;
    expect_ran(skin.run());
    if (t) t->skin += ms_since(clock);
}

}  // namespace stipple
