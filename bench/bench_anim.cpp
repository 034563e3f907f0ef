// Benchmarks for anim/: one frame's pose (sample_clip + local_to_model + joint_matrices) for a
// synthetic 20-joint skeleton with a 30-key clip, and linear blend skinning of 3,273 vertices
// (CesiumMan's count) and 100,000 vertices. Skinning reports ns per vertex and bytes streamed,
// to compare with memory bandwidth (~15 GB/s single-threaded on the reference machine).
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "anim/anim.h"

namespace {

using namespace stipple::anim;

constexpr uint32_t kJoints = 20;
constexpr uint32_t kKeys = 30;
constexpr float kDuration = 1.0f;

// Bytes each skinned vertex streams: joints (4 x u16) + weights (4 x f32) + position and normal
// in (2 x 3 x f32) + position and normal out (2 x 3 x f32).
constexpr int64_t kBytesPerVertex = 4 * 2 + 4 * 4 + 2 * 3 * 4 + 2 * 3 * 4;

// A 20-node tree (parent of i is (i - 1) / 2), every node one joint, and a clip animating the
// translation, rotation and scale of every node with 30 keys each (60 channels).
struct SyntheticRig {
    std::vector<int32_t> parents;
    std::vector<Trs> rest;
    std::vector<uint32_t> joint_nodes;
    std::vector<float> inverse_bind;
    std::vector<float> times;
    std::vector<float> translations;
    std::vector<float> rotations;
    std::vector<float> scales;
    std::vector<Channel> channels;
    Skeleton skeleton{};
    Clip clip{};

    SyntheticRig() {
        std::mt19937 rng(1234);
        std::uniform_real_distribution<float> u(-1.0f, 1.0f);
        for (uint32_t i = 0; i < kJoints; ++i) {
            parents.push_back(i == 0 ? -1 : static_cast<int32_t>((i - 1) / 2));
            rest.push_back(Trs{{0, 0.5f, 0}, {0, 0, 0, 1}, {1, 1, 1}});
            joint_nodes.push_back(i);
            const float ib[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -0.5f * i, 0, 1};
            inverse_bind.insert(inverse_bind.end(), ib, ib + 16);
        }
        for (uint32_t k = 0; k < kKeys; ++k) times.push_back(kDuration * k / (kKeys - 1));
        for (uint32_t i = 0; i < kJoints * kKeys; ++i) {
            translations.insert(translations.end(), {0.1f * u(rng), 0.5f + 0.1f * u(rng), 0});
            float q[4] = {u(rng), u(rng), u(rng), 2.0f + u(rng)};
            const float len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
            for (float& c : q) c /= len;
            rotations.insert(rotations.end(), q, q + 4);
            const float s = 1.0f + 0.05f * u(rng);
            scales.insert(scales.end(), {s, s, s});
        }
        for (uint32_t i = 0; i < kJoints; ++i) {
            channels.push_back({i, Path::translation, Interp::linear, kKeys, times.data(),
                                translations.data() + 3 * kKeys * i});
            channels.push_back({i, Path::rotation, Interp::linear, kKeys, times.data(),
                                rotations.data() + 4 * kKeys * i});
            channels.push_back({i, Path::scale, Interp::linear, kKeys, times.data(),
                                scales.data() + 3 * kKeys * i});
        }
        skeleton = Skeleton{kJoints, parents.data(),     rest.data(),
                            kJoints, joint_nodes.data(), inverse_bind.data()};
        clip =
            Clip{"synthetic", kDuration, static_cast<uint32_t>(channels.size()), channels.data()};
    }
};

// Random mesh: 4 influences per vertex on random joints, weights summing to 1, unit normals.
struct SyntheticMesh {
    std::vector<uint16_t> joints;
    std::vector<float> weights;
    std::vector<float> positions;
    std::vector<float> normals;
    std::vector<float> out_positions;
    std::vector<float> out_normals;

    explicit SyntheticMesh(uint32_t n)
        : joints(4 * size_t{n}),
          weights(4 * size_t{n}),
          positions(3 * size_t{n}),
          normals(3 * size_t{n}),
          out_positions(3 * size_t{n}),
          out_normals(3 * size_t{n}) {
        std::mt19937 rng(42);
        std::uniform_real_distribution<float> u(-1.0f, 1.0f);
        std::uniform_int_distribution<int> joint(0, kJoints - 1);
        for (size_t v = 0; v < n; ++v) {
            float sum = 0;
            for (int k = 0; k < 4; ++k) {
                joints[4 * v + k] = static_cast<uint16_t>(joint(rng));
                weights[4 * v + k] = u(rng) + 1.0f;
                sum += weights[4 * v + k];
            }
            for (int k = 0; k < 4; ++k) weights[4 * v + k] /= sum;
            float nrm[3] = {u(rng), u(rng), u(rng) + 2.0f};
            const float len = std::sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
            for (int c = 0; c < 3; ++c) {
                positions[3 * v + c] = u(rng);
                normals[3 * v + c] = nrm[c] / len;
            }
        }
    }

    SkinJob job(const glm::mat4* skin) {
        return SkinJob{static_cast<uint32_t>(joints.size() / 4),
                       skin,
                       kJoints,
                       joints.data(),
                       weights.data(),
                       positions.data(),
                       normals.data(),
                       out_positions.data(),
                       out_normals.data()};
    }
};

// Per-frame pose: sample all 60 channels, then model and skin matrices for 20 joints.
void BM_Pose(benchmark::State& state) {
    SyntheticRig rig;
    Trs locals[kJoints];
    glm::mat4 model[kJoints];
    glm::mat4 skin[kJoints];
    float t = 0.0f;
    for (auto _ : state) {
        sample_clip(rig.skeleton, rig.clip, t, locals);
        local_to_model(rig.skeleton, locals, model);
        joint_matrices(rig.skeleton, model, skin);
        benchmark::DoNotOptimize(skin);
        benchmark::ClobberMemory();
        t += 1.0f / 60.0f;
        if (t > kDuration) t -= kDuration;
    }
    // Joints per second, inverted: seconds per joint (the console prints e.g. "46ns").
    state.counters["per_joint"] = benchmark::Counter(
        kJoints, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_Pose);

// Skinning alone, from a fixed pose.
void BM_SkinLbs(benchmark::State& state) {
    const uint32_t n = static_cast<uint32_t>(state.range(0));
    SyntheticRig rig;
    SyntheticMesh mesh(n);
    Trs locals[kJoints];
    glm::mat4 model[kJoints];
    glm::mat4 skin[kJoints];
    sample_clip(rig.skeleton, rig.clip, 0.37f, locals);
    local_to_model(rig.skeleton, locals, model);
    joint_matrices(rig.skeleton, model, skin);
    const SkinJob job = mesh.job(skin);
    for (auto _ : state) {
        skin_lbs(job);
        benchmark::ClobberMemory();
    }
    benchmark::DoNotOptimize(mesh.out_positions.data());
    state.SetBytesProcessed(state.iterations() * int64_t{n} * kBytesPerVertex);
    // Vertices per second, inverted: seconds per vertex (the console prints e.g. "6.6ns"; JSON
    // output holds seconds).
    state.counters["per_vertex"] = benchmark::Counter(
        n, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_SkinLbs)->Arg(3273)->Arg(100000);

// A whole frame for a CesiumMan-sized character: pose + skin 3,273 vertices.
void BM_Frame(benchmark::State& state) {
    const uint32_t n = static_cast<uint32_t>(state.range(0));
    SyntheticRig rig;
    SyntheticMesh mesh(n);
    Trs locals[kJoints];
    glm::mat4 model[kJoints];
    glm::mat4 skin[kJoints];
    const SkinJob job = mesh.job(skin);
    float t = 0.0f;
    for (auto _ : state) {
        sample_clip(rig.skeleton, rig.clip, t, locals);
        local_to_model(rig.skeleton, locals, model);
        joint_matrices(rig.skeleton, model, skin);
        skin_lbs(job);
        benchmark::ClobberMemory();
        t += 1.0f / 60.0f;
        if (t > kDuration) t -= kDuration;
    }
    state.SetBytesProcessed(state.iterations() * int64_t{n} * kBytesPerVertex);
}
BENCHMARK(BM_Frame)->Arg(3273);

}  // namespace
