// The CPU point stages (place, relevance, size) at 100k points against the memory bandwidth
// bound of the bytes they touch, and over threads (issue 9 item 5). One run, interleaved
// rounds, min and median of each: every round measures, in turn,
//   - the bandwidth: memcpy of a buffer as large as the stages' streamed bytes (read + write),
//   - each stage on the baseline path (the scalar code: what the pipeline ran before) and on
//     the path chosen at run time (runtime/point_simd.h), on 1 thread, then on 2 threads.
// The bound of a stage is its streamed bytes per point / the measured bandwidth; the table
// gives ns per point, the ratio to the bound, and 1 / 2 thread scaling.
// Its own main (no Google Benchmark loop): stipple_bench_point_stages_scaling [rounds].
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <vector>

#include "bench/bench_asset.h"
#include "runtime/point_placement.h"
#include "runtime/point_simd.h"
#include "runtime/point_stages.h"
#include "runtime/thread_pool.h"

namespace {

using Clock = std::chrono::steady_clock;

struct Scene {
    stipple::Asset asset;
    std::vector<float> pos, nrm, scale, radius, size, pairs;
    stipple::SizeParams params;
    stipple::PointStageFrame frame;
};

double thread_seconds() {
    timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

// Seconds per call of f, the mean over `calls` calls: this thread's CPU time (one thread: the
// machine's other load does not count, only what it does to caches), or wall time (threads).
template <typename F>
double time_calls(int calls, bool wall, F f) {
    const Clock::time_point t0 = Clock::now();
    const double c0 = thread_seconds();
    for (int i = 0; i < calls; ++i) f();
    if (!wall) return (thread_seconds() - c0) / calls;
    return std::chrono::duration<double>(Clock::now() - t0).count() / calls;
}

struct Series {
    std::vector<double> ns;
    double min() const { return *std::min_element(ns.begin(), ns.end()); }
    double median() const {
        std::vector<double> s = ns;
        std::sort(s.begin(), s.end());
        return s[s.size() / 2];
    }
};

enum Stage { place, relevance, size, kStages };
const char* kStageNames[kStages] = {"place", "relevance", "size"};

void run_stage(Stage s, stipple::ThreadPool* pool, const Scene& sc) {
    const uint32_t n = sc.asset.points.point_count;
    if (s == place) stipple::point_stage_place(pool, sc.frame, nullptr, n);
    if (s == relevance) stipple::point_stage_relevance(pool, sc.frame, nullptr, n);
    if (s == size) stipple::point_stage_size(pool, sc.frame, nullptr, n);
}

// CesiumMan at 100k points in its bind pose; false if the bake fails.
bool make_scene(Scene* sc) {
    if (!stipple::bench::bake_asset("CesiumMan/CesiumMan.glb", 100000, &sc->asset)) return false;
    const stipple::PointsView& pts = sc->asset.points;
    const size_t n = pts.point_count;
    sc->pos.resize(n * 3 + stipple::kSimdPadFloats);  // the AVX2 kernels' 16-byte loads
    sc->nrm.resize(n * 3 + stipple::kSimdPadFloats);
    sc->scale.resize(n);
    sc->radius.resize(n);
    sc->size.resize(n);
    const stipple::MeshView& m = sc->asset.mesh;
    stipple::place_points(pts, m.indices, m.positions, m.normals, sc->pos.data(), sc->nrm.data());
    stipple::relevance_scale(pts, sc->pos.data(), sc->scale.data());
    sc->params.view_projection[1][1] = 2.0f;  // as bench_point_stages.cpp's size benchmark
    sc->params.view_projection[2][3] = -1.0f;
    sc->params.view_projection[3][3] = 3.0f;
    sc->params.eye = glm::vec3(0, 1, 3);
    stipple::PointStageFrame& f = sc->frame;
    f.points = &pts;
    f.indices = m.indices;
    f.vertex_positions = m.positions;
    f.vertex_normals = m.normals;
    sc->pairs.resize(size_t(m.vertex_count) * 8);
    stipple::pair_vertices(m.vertex_count, m.positions, m.normals, sc->pairs.data());
    f.vertex_pairs = sc->pairs.data();
    f.scale = sc->scale.data();
    f.fallback_radius = pts.radius;
    f.params = &sc->params;
    f.positions = sc->pos.data();
    f.normals = sc->nrm.data();
    f.radius = sc->radius.data();
    f.size = sc->size.data();
    return true;
}

struct Results {
    double nbrs = 0;             // neighbours per point
    double bytes[kStages] = {};  // streamed bytes per point
    size_t copy_bytes = 0;
    Series bandwidth;  // bytes per ns
    // [stage][0: baseline 1 thread, 1: run-time path 1 thread, 2: run-time path 2 threads]
    Series t[kStages][3];
    Series wall1[kStages];  // the run-time path on 1 thread, wall time (for the 2-thread ratio)
};

void measure(const Scene& sc, int rounds, stipple::PointSimd chosen, stipple::ThreadPool* two,
             Results* r) {
    std::vector<char> src(r->copy_bytes), dst(r->copy_bytes);
    std::memset(src.data(), 1, src.size());
    stipple::ThreadPool one;
    const double n = double(sc.asset.points.point_count);
    const int calls = 5;
    for (int round = 0; round < rounds; ++round) {
        const double copy_s =
            time_calls(calls, false, [&] { std::memcpy(dst.data(), src.data(), src.size()); });
        r->bandwidth.ns.push_back(2.0 * double(src.size()) / (copy_s * 1e9));
        for (int variant = 0; variant < 3; ++variant) {
            stipple::point_simd_force(variant == 0 ? stipple::PointSimd::baseline : chosen);
            stipple::ThreadPool* pool = variant == 2 ? two : &one;
            for (int s = 0; s < kStages; ++s) {
                // 1 thread: CPU time; 2 threads: wall time, and 1 thread's wall time beside it.
                const double sec =
                    time_calls(calls, variant == 2, [&] { run_stage(Stage(s), pool, sc); });
                r->t[s][variant].ns.push_back(sec * 1e9 / n);
                if (variant != 1) continue;
                const double wall = time_calls(calls, true, [&] { run_stage(Stage(s), pool, sc); });
                r->wall1[s].ns.push_back(wall * 1e9 / n);
            }
        }
    }
    stipple::point_simd_force(chosen);
}

void print(const Results& r, size_t n, int rounds, const char* path) {
    const double bw = *std::max_element(r.bandwidth.ns.begin(), r.bandwidth.ns.end());
    std::printf(
        "CesiumMan %zu points, %.1f neighbours per point, %d interleaved rounds, "
        "run-time SIMD path: %s\n",
        n, r.nbrs, rounds, path);
    std::printf("memcpy over %.1f MB (read + write): best %.2f GB/s, median %.2f GB/s\n",
                double(r.copy_bytes) / 1e6, bw, r.bandwidth.median());
    std::printf(
        "1 thread: ns/point of thread CPU time; 2 threads: wall time, against the same "
        "1-thread wall time (min / median)\n");
    std::printf(
        "| stage | bytes/pt | bound ns/pt | baseline 1T | %s 1T | %s 1T / bound | %s 1T "
        "wall | %s 2T wall | 2T speed-up (min) |\n",
        path, path, path, path);
    std::printf("| --- | --- | --- | --- | --- | --- | --- | --- | --- |\n");
    double sum[3] = {0, 0, 0}, sum_bound = 0, sum_wall = 0;
    for (int s = 0; s < kStages; ++s) {
        const double bound = r.bytes[s] / bw;
        const Series* t = r.t[s];
        sum_bound += bound;
        sum_wall += r.wall1[s].min();
        for (int v = 0; v < 3; ++v) sum[v] += t[v].min();
        std::printf(
            "| %s | %.0f | %.2f | %.2f / %.2f | %.2f / %.2f | %.1f | %.2f / %.2f | "
            "%.2f / %.2f | %.2f |\n",
            kStageNames[s], r.bytes[s], bound, t[0].min(), t[0].median(), t[1].min(), t[1].median(),
            t[1].min() / bound, r.wall1[s].min(), r.wall1[s].median(), t[2].min(), t[2].median(),
            r.wall1[s].min() / t[2].min());
    }
    std::printf("| all three | %.0f | %.2f | %.2f | %.2f | %.1f | %.2f | %.2f | %.2f |\n",
                r.bytes[0] + r.bytes[1] + r.bytes[2], sum_bound, sum[0], sum[1], sum[1] / sum_bound,
                sum_wall, sum[2], sum_wall / sum[2]);
}

}  // namespace

int main(int argc, char** argv) {
    const int rounds = argc > 1 ? std::max(3, std::atoi(argv[1])) : 15;
    Scene sc;
    if (!make_scene(&sc)) {
        std::fprintf(stderr, "bake failed\n");
        return 1;
    }
    const size_t n = sc.asset.points.point_count;
    Results r;
    r.nbrs = double(sc.asset.points.neighbour_count) / double(n);
    // Streamed bytes per point (the mesh's gathers are cache resident and not counted).
    r.bytes[place] = 4 + 4 + 4 + 12 + 12;  // host, u, v in; position, normal out
    // offset, scale, own position, radius out; per neighbour its index and position
    r.bytes[relevance] = 4 + 4 + 12 + 4 + r.nbrs * (4 + 12);
    r.bytes[size] = 12 + 12 + 4 + 4;  // position, normal, radius in; size out
    // A copy moving as many bytes (read + write) as the three stages stream.
    r.copy_bytes = size_t((r.bytes[0] + r.bytes[1] + r.bytes[2]) * double(n) / 2);
    stipple::ThreadPool two;
    if (!stipple::thread_pool_init(&two, 2).ok()) return 1;
    const stipple::PointSimd chosen = stipple::point_simd_detected();
    measure(sc, rounds, chosen, &two, &r);
    const double split = double(stipple::thread_pool_worker_ranges(&two)) /
                         double(rounds * kStages * 5 /* calls */ * 2 /* ranges */);
    stipple::thread_pool_destroy(&two);
    print(r, n, rounds, stipple::point_simd_name(chosen));
    std::printf(
        "2 threads: the worker ran %.0f%% of the ranges (50%%: an even split; less: "
        "it was not scheduled in time and the caller ran its range)\n",
        100.0 * split);
    return 0;
}
