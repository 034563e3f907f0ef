// Benchmarks for anim/, per unit of work, on CesiumMan (assets/CesiumMan/CesiumMan.glb via
// bake::import_gltf: 22 nodes, 19 joints, 57 LINEAR channels of 49 keys, 3,273 vertices) and
// on a 100k-vertex mesh made of 31 copies of CesiumMan's (101,463 vertices, the size
// PLATFORM-NOTES measured ozz-animation on), plus a worst case of 100,000 random vertices
// with 4 influences each.
//
//   BM_Sample: SamplingJob with a context, looping playback at 60 fps: ns per joint.
//   BM_Pose:   sampling + LocalToModelJob + JointMatrixJob: ns per joint.
//   BM_Skin/<mesh>/<method>: SkinningJob, positions and normals: ns per vertex, for LBS and
//              DQS, SIMD (run) and scalar (run_scalar); `bound_ns` is the time to stream the
//              bytes a vertex touches (joints 8 + weights 16 + position and normal in 24 + out
//              24 = 72 bytes) at the read bandwidth BM_StreamRead measures in the same run,
//              and `x_bound` the ratio measured / bound (1.0 = memory-bound).
//   BM_Frame:  CesiumMan, sample + hierarchy + LBS skinning: the figure to hold against
//              ozz's 10.6 us per frame (PLATFORM-NOTES).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "anim/anim.h"
#include "bake/raw_anim_view.h"
#include "bake/scene_import.h"

namespace {

using namespace stipple::anim;

constexpr double kBytesPerVertex = 4 * 2 + 4 * 4 + 2 * 3 * 4 + 2 * 3 * 4;

// Single-thread read bandwidth over a 256 MiB buffer (well past the caches), bytes/second.
double read_bandwidth() {
    static double bandwidth = [] {
        const size_t n = (size_t(256) << 20) / sizeof(float);
        std::vector<float> data(n, 1.0f);
        double best = 0;
        for (int rep = 0; rep < 5; ++rep) {
            const auto start = std::chrono::steady_clock::now();
            // 8 independent sums so the adds are not the bottleneck (vectorised at -O3).
            float s[8] = {};
            for (size_t i = 0; i < n; i += 8) {
                for (int k = 0; k < 8; ++k) s[k] += data[i + size_t(k)];
            }
            benchmark::DoNotOptimize(s);
            const double seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            best = std::max(best, double(n * sizeof(float)) / seconds);
        }
        std::fprintf(stderr, "read bandwidth (one thread, 256 MiB): %.2f GB/s; SIMD path: %s\n",
                     best / 1e9, simd_path());
        return best;
    }();
    return bandwidth;
}

void BM_StreamRead(benchmark::State& state) {
    for (auto _ : state) benchmark::DoNotOptimize(read_bandwidth());
    state.counters["GB_per_s"] = read_bandwidth() / 1e9;
}
BENCHMARK(BM_StreamRead)->Iterations(1);

struct Cesium {
    stipple::bake::RawScene scene;
    stipple::bake::RawAnimView view;
    Cesium() {
        const stipple::bake::BakeError error = stipple::bake::import_gltf(
            std::string(STIPPLE_SOURCE_DIR) + "/assets/CesiumMan/CesiumMan.glb", &scene);
        if (!error.ok()) {
            std::fprintf(stderr, "%s\n", error.message.c_str());
            std::abort();
        }
        stipple::bake::make_anim_view(scene, &view);
    }
};

const Cesium& cesium() {
    static const Cesium c;
    return c;
}

void BM_Sample(benchmark::State& state) {
    const Cesium& c = cesium();
    const Skeleton& k = c.view.skeleton;
    std::vector<Trs> locals(k.node_count);
    std::vector<uint32_t> cursors(c.view.clips[0].channel_count);
    SamplingContext context;
    context.cursors = {cursors.data(), cursors.size()};
    SamplingJob job;
    job.skeleton = &k;
    job.clip = &c.view.clips[0];
    job.wrap = Wrap::loop;
    job.context = &context;
    job.locals = {locals.data(), locals.size()};
    float t = 0;
    for (auto _ : state) {
        job.time = t;
        benchmark::DoNotOptimize(job.run());
        benchmark::ClobberMemory();
        t += 1.0f / 60.0f;
    }
    state.counters["per_joint"] = benchmark::Counter(
        k.joint_count, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
    state.counters["per_channel"] = benchmark::Counter(
        c.view.clips[0].channel_count,
        benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_Sample);

struct PoseBuffers {
    std::vector<Trs> locals;
    std::vector<glm::mat4> models, palette;
    std::vector<uint32_t> cursors;
    SamplingContext context;
    explicit PoseBuffers(const Cesium& c)
        : locals(c.view.skeleton.node_count),
          models(c.view.skeleton.node_count),
          palette(c.view.skeleton.joint_count),
          cursors(c.view.clips[0].channel_count) {
        context.cursors = {cursors.data(), cursors.size()};
    }
    void pose(const Cesium& c, float t) {
        SamplingJob s;
        s.skeleton = &c.view.skeleton;
        s.clip = &c.view.clips[0];
        s.wrap = Wrap::loop;
        s.time = t;
        s.context = &context;
        s.locals = {locals.data(), locals.size()};
        benchmark::DoNotOptimize(s.run());
        LocalToModelJob l;
        l.skeleton = &c.view.skeleton;
        l.locals = {locals.data(), locals.size()};
        l.models = {models.data(), models.size()};
        benchmark::DoNotOptimize(l.run());
        JointMatrixJob j;
        j.skeleton = &c.view.skeleton;
        j.models = {models.data(), models.size()};
        j.joint_matrices = {palette.data(), palette.size()};
        benchmark::DoNotOptimize(j.run());
    }
};

void BM_Pose(benchmark::State& state) {
    const Cesium& c = cesium();
    PoseBuffers b(c);
    float t = 0;
    for (auto _ : state) {
        b.pose(c, t);
        benchmark::ClobberMemory();
        t += 1.0f / 60.0f;
    }
    state.counters["per_joint"] = benchmark::Counter(
        c.view.skeleton.joint_count,
        benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_Pose);

// Skinning inputs: CesiumMan's mesh, 31 copies of it, or random 4-influence vertices.
struct SkinMesh {
    std::vector<uint16_t> joints;
    std::vector<float> weights, positions, normals, out_p, out_n;
    uint32_t count() const { return uint32_t(positions.size() / 3); }
};

const SkinMesh& skin_mesh(int which) {
    static SkinMesh meshes[3];
    SkinMesh& m = meshes[which];
    if (!m.positions.empty()) return m;
    const Cesium& c = cesium();
    if (which < 2) {
        const int copies = which == 0 ? 1 : 31;
        for (int i = 0; i < copies; ++i) {
            m.joints.insert(m.joints.end(), c.scene.joints.begin(), c.scene.joints.end());
            m.weights.insert(m.weights.end(), c.scene.weights.begin(), c.scene.weights.end());
            m.positions.insert(m.positions.end(), c.scene.positions.begin(),
                               c.scene.positions.end());
            m.normals.insert(m.normals.end(), c.scene.normals.begin(), c.scene.normals.end());
        }
    } else {
        std::mt19937 rng(42);
        std::uniform_real_distribution<float> u(-1.0f, 1.0f);
        for (int v = 0; v < 100000; ++v) {
            float w[4], sum = 0;
            for (float& x : w) sum += (x = u(rng) + 1.1f);
            for (int k = 0; k < 4; ++k) {
                m.joints.push_back(uint16_t(rng() % c.view.skeleton.joint_count));
                m.weights.push_back(w[k] / sum);
            }
            float n[3] = {u(rng), u(rng), u(rng) + 2};
            const float l = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            for (int k = 0; k < 3; ++k) {
                m.positions.push_back(u(rng));
                m.normals.push_back(n[k] / l);
            }
        }
    }
    m.out_p.resize(m.positions.size());
    m.out_n.resize(m.normals.size());
    return m;
}

// Arguments: mesh (0 CesiumMan, 1 CesiumMan x31, 2 random 4-influence 100k), method
// (0 LBS SIMD, 1 LBS scalar, 2 DQS SIMD, 3 DQS scalar).
void BM_Skin(benchmark::State& state) {
    const Cesium& c = cesium();
    SkinMesh& m = const_cast<SkinMesh&>(skin_mesh(int(state.range(0))));
    const int method = int(state.range(1));
    PoseBuffers b(c);
    b.pose(c, 0.37f);
    std::vector<DqsJoint> dq(b.palette.size());
    uint32_t stretched = 0;
    if (!dqs_joints({b.palette.data(), b.palette.size()}, {dq.data(), dq.size()}, &stretched))
        return state.SkipWithError("dqs_joints failed");
    SkinningJob job;
    job.method = method >= 2 ? Skinning::dqs : Skinning::lbs;
    job.vertex_count = m.count();
    job.joint_matrices = {b.palette.data(), b.palette.size()};
    job.dq_joints = {dq.data(), dq.size()};
    job.dq_rigid = stretched == 0;
    job.joints = {m.joints.data(), m.joints.size()};
    job.weights = {m.weights.data(), m.weights.size()};
    job.in_positions = {m.positions.data(), m.positions.size()};
    job.in_normals = {m.normals.data(), m.normals.size()};
    job.out_positions = {m.out_p.data(), m.out_p.size()};
    job.out_normals = {m.out_n.data(), m.out_n.size()};
    const bool scalar = method % 2 == 1;
    const auto start = std::chrono::steady_clock::now();
    for (auto _ : state) {
        if (scalar) {
            benchmark::DoNotOptimize(job.run_scalar());
        } else {
            benchmark::DoNotOptimize(job.run());
        }
        benchmark::ClobberMemory();
    }
    const double ns_per_vertex =
        std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start).count() /
        (double(state.iterations()) * m.count());
    state.counters["per_vertex"] = benchmark::Counter(
        m.count(), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
    const double bound_ns = kBytesPerVertex / read_bandwidth() * 1e9;
    state.counters["bound_ns"] = bound_ns;
    state.counters["x_bound"] = ns_per_vertex / bound_ns;
    state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(m.count()) *
                            int64_t(kBytesPerVertex));
    state.SetLabel(std::string(method >= 2 ? "dqs" : "lbs") + (scalar ? "_scalar" : "_simd") +
                   (stretched ? " stretched" : ""));
}
BENCHMARK(BM_Skin)->ArgsProduct({{0, 1, 2}, {0, 1, 2, 3}});

void BM_Frame(benchmark::State& state) {
    const Cesium& c = cesium();
    PoseBuffers b(c);
    const SkinMesh& m = skin_mesh(0);
    std::vector<float> out_p(m.positions.size()), out_n(m.normals.size());
    SkinningJob job;
    job.vertex_count = m.count();
    job.joint_matrices = {b.palette.data(), b.palette.size()};
    job.joints = {m.joints.data(), m.joints.size()};
    job.weights = {m.weights.data(), m.weights.size()};
    job.in_positions = {m.positions.data(), m.positions.size()};
    job.in_normals = {m.normals.data(), m.normals.size()};
    job.out_positions = {out_p.data(), out_p.size()};
    job.out_normals = {out_n.data(), out_n.size()};
    float t = 0;
    for (auto _ : state) {
        b.pose(c, t);
        benchmark::DoNotOptimize(job.run());
        benchmark::ClobberMemory();
        t += 1.0f / 60.0f;
    }
}
BENCHMARK(BM_Frame);

}  // namespace
