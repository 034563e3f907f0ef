// The animation jobs allocate nothing: 1,000 frames of sampling (two clips' worth of layers
// with sampling contexts, looping), blending (masked layering + crossfade), hierarchy,
// morphing, and skinning with LBS and DQS (SIMD and scalar), counted with the global
// operator new hook of tests/alloc/alloc_counter.cpp, on the clips and skin of a baked asset.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "anim/anim.h"
#include "runtime/asset.h"
#include "tests/alloc/alloc_counter.h"
#include "tests/common/fixtures.h"

namespace {

using namespace stipple::anim;

TEST(AnimAllocation, ThousandFramesOfSamplingBlendingAndSkinningAllocateNothing) {
    stipple::Asset asset;
    std::string error;
    ASSERT_TRUE(stipple::test::load_baked(
        stipple::test::baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 10000"), &asset,
        &error))
        << error;
    ASSERT_TRUE(asset.skinned);
    ASSERT_GT(asset.clip_count, 0u);
    const Skeleton& skeleton = asset.skin.skeleton;
    const size_t nodes = skeleton.node_count, joints = skeleton.joint_count;
    const uint32_t nv = asset.mesh.vertex_count;
    const Clip& clip = asset.clips[0];
    const size_t floats = size_t{nv} * 3, influences = size_t{nv} * 4;

    // Everything is allocated here, before counting.
    std::vector<Trs> layer_a(nodes), layer_b(nodes), blended(nodes), faded(nodes);
    std::vector<uint32_t> cursors_a(clip.channel_count), cursors_b(clip.channel_count);
    SamplingContext context_a, context_b;
    context_a.cursors = {cursors_a.data(), cursors_a.size()};
    context_b.cursors = {cursors_b.data(), cursors_b.size()};
    std::vector<float> mask(nodes, 1.0f);
    for (size_t i = 0; i < nodes; i += 2) mask[i] = 0.0f;  // layer b drives every other node
    std::vector<glm::mat4> models(nodes), palette(joints);
    std::vector<DqsJoint> dq(joints);
    std::vector<float> morphed_p(floats), morphed_n(floats);
    std::vector<float> out_p(floats), out_n(floats);
    const float morph_defaults[1] = {0.0f};
    const Morph morph = {0, morph_defaults, 0, nullptr};

    stipple::test::g_allocations = 0;
    stipple::test::g_counting = true;
    long frames_ok = 0;
    for (int frame = 0; frame < 1000; ++frame) {
        const float t = float(frame) / 60.0f;
        bool ok = true;
        SamplingJob sample;
        sample.skeleton = &skeleton;
        sample.clip = &clip;
        sample.wrap = Wrap::loop;
        sample.time = t;
        sample.context = &context_a;
        sample.locals = {layer_a.data(), nodes};
        ok &= sample.run();
        sample.time = 0.7f * t + 0.3f;  // a second, slower playback of the clip
        sample.context = &context_b;
        sample.locals = {layer_b.data(), nodes};
        ok &= sample.run();

        BlendLayer layers[2];
        layers[0].locals = {layer_a.data(), nodes};
        layers[0].weight = 0.6f;
        layers[1].locals = {layer_b.data(), nodes};
        layers[1].weight = 0.4f;
        layers[1].node_weights = {mask.data(), nodes};
        BlendingJob blend;
        blend.skeleton = &skeleton;
        blend.layers = layers;
        blend.out = {blended.data(), nodes};
        ok &= blend.run();
        ok &= crossfade(skeleton, {layer_a.data(), nodes}, {blended.data(), nodes},
                        float(frame % 100) / 100.0f, {faded.data(), nodes});

        LocalToModelJob l2m;
        l2m.skeleton = &skeleton;
        l2m.locals = {faded.data(), nodes};
        l2m.models = {models.data(), nodes};
        ok &= l2m.run();
        JointMatrixJob jm;
        jm.skeleton = &skeleton;
        jm.models = {models.data(), nodes};
        jm.joint_matrices = {palette.data(), joints};
        ok &= jm.run();
        uint32_t stretched = 0;
        ok &= dqs_joints({palette.data(), joints}, {dq.data(), joints}, &stretched);

        MorphJob mj;
        mj.morph = &morph;
        mj.vertex_count = nv;
        mj.in_positions = {asset.mesh.positions, floats};
        mj.in_normals = {asset.mesh.normals, floats};
        mj.out_positions = {morphed_p.data(), morphed_p.size()};
        mj.out_normals = {morphed_n.data(), morphed_n.size()};
        ok &= mj.run();

        SkinningJob skin;
        skin.vertex_count = nv;
        skin.joint_matrices = {palette.data(), joints};
        skin.dq_joints = {dq.data(), joints};
        skin.dq_rigid = stretched == 0;
        skin.joints = {asset.skin.joints, influences};
        skin.weights = {asset.skin.weights, influences};
        skin.in_positions = {morphed_p.data(), morphed_p.size()};
        skin.in_normals = {morphed_n.data(), morphed_n.size()};
        skin.out_positions = {out_p.data(), out_p.size()};
        skin.out_normals = {out_n.data(), out_n.size()};
        skin.method = frame % 2 ? Skinning::dqs : Skinning::lbs;
        ok &= skin.run();
        ok &= skin.run_scalar();
        frames_ok += ok ? 1 : 0;
    }
    stipple::test::g_counting = false;
    EXPECT_EQ(stipple::test::g_allocations.load(), 0);
    EXPECT_EQ(frames_ok, 1000);
}

}  // namespace
