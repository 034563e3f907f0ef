// Benchmark of the load-time work of the run-time refinement (what pipeline_init adds to
// reading the asset), CesiumMan baked to 20k and 100k points, per baked point:
//   - decode: load_asset_memory over the asset's bytes (checksums, quantised point streams,
//     neighbour lists): the least any load does, the baseline;
//   - triangulate: the triangulation of the baked points (runtime/point_triangulation.h);
//   - refinement_init: the points domain's tables, the first-point ranking
//     (runtime/refinement_order.h) and the early-out's clusters and path bounds
//     (runtime/refinement_cull.h).
// The three run alternately for a few rounds in one run; min and median per stage and each
// stage's ratio to decode (medians).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "bench/bench_asset.h"
#include "runtime/asset.h"
#include "runtime/point_placement.h"
#include "runtime/point_refinement.h"
#include "runtime/point_triangulation.h"

namespace {

struct Fixture {
    std::vector<uint8_t> bytes;
    stipple::Asset asset;
    std::vector<float> bind, bind_normals;
};

std::unique_ptr<Fixture> fixture(uint32_t points) {
    auto f = std::make_unique<Fixture>();
    if (!stipple::bench::bake_bytes("CesiumMan/CesiumMan.glb", points, &f->bytes)) return nullptr;
    if (!stipple::load_asset_memory(f->bytes.data(), f->bytes.size(), &f->asset).ok())
        return nullptr;
    const size_t n = f->asset.points.point_count;
    f->bind.resize(n * 3);
    f->bind_normals.resize(n * 3);
    const stipple::MeshView& m = f->asset.mesh;
    stipple::place_points(f->asset.points, m.indices, m.positions, m.normals, f->bind.data(),
                          f->bind_normals.data());
    return f;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void min_median(std::vector<double> v, double* lo, double* mid) {
    std::sort(v.begin(), v.end());
    *lo = v.front();
    *mid = v[v.size() / 2];
}

void BM_LoadWork(benchmark::State& state) {
    const std::unique_ptr<Fixture> f = fixture(uint32_t(state.range(0)));
    if (!f) return state.SkipWithError("fixture failed");
    const stipple::MeshView& m = f->asset.mesh;
    const uint32_t n = f->asset.points.point_count;
    constexpr int kRounds = 5;
    std::vector<double> decode, triangulate, init;
    for (auto _ : state) {
        for (int round = 0; round < kRounds; ++round) {
            auto start = std::chrono::steady_clock::now();
            stipple::Asset a;
            if (!stipple::load_asset_memory(f->bytes.data(), f->bytes.size(), &a).ok())
                return state.SkipWithError("decode failed");
            decode.push_back(seconds_since(start));
            start = std::chrono::steady_clock::now();
            stipple::PointTriangulation t;
            if (!stipple::triangulate_points(n, f->bind.data(), f->bind_normals.data(),
                                             stipple::surface_area(m), &m,
                                             f->asset.points.host_triangle, &t)
                     .ok())
                return state.SkipWithError("triangulation failed");
            triangulate.push_back(seconds_since(start));
            stipple::MeshView domain;
            domain.vertex_count = n;
            domain.triangle_count = t.triangle_count;
            domain.positions = f->bind.data();
            domain.normals = f->bind_normals.data();
            domain.indices = t.indices.get();
            start = std::chrono::steady_clock::now();
            stipple::RefinementMesh r;
            if (!stipple::refinement_init(&r, domain, f->asset.points, f->bind.data(),
                                          stipple::RefinementDomain::points, &m)
                     .ok())
                return state.SkipWithError("refinement_init failed");
            init.push_back(seconds_since(start));
        }
    }
    const char* names[3] = {"decode", "triangulate", "refinement_init"};
    const std::vector<double>* times[3] = {&decode, &triangulate, &init};
    double base = 0.0;
    for (int k = 0; k < 3; ++k) {
        double lo = 0.0, mid = 0.0;
        min_median(*times[k], &lo, &mid);
        if (k == 0) base = mid;
        state.counters[std::string(names[k]) + "_ms_min"] = lo * 1e3;
        state.counters[std::string(names[k]) + "_ns_per_point"] = mid * 1e9 / n;
        if (k > 0) state.counters[std::string(names[k]) + "_vs_decode"] = mid / base;
    }
}

BENCHMARK(BM_LoadWork)->Arg(20000)->Arg(100000)->Iterations(1)->Unit(benchmark::kMillisecond);

}  // namespace
