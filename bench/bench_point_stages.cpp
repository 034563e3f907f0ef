// Benchmarks of the per-frame point stages on a real hierarchy: CesiumMan baked to 20k and
// 100k points, in its bind pose. Each reports ns per point and the bytes it streams, to
// compare with memory bandwidth (~15 GB/s one thread on the reference machine), and a
// simplest-alternative baseline in the same run:
//   - placement vs. a plain copy of stored positions (what a static point cloud costs),
//   - relevance recompute (Alg. 6.4) vs. using the stored radius (Alg. 6.3 alone),
//   - sizing (Alg. 3.2 + slope) vs. a constant size.
#include <benchmark/benchmark.h>

#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "bench/bench_asset.h"
#include "runtime/point_placement.h"
#include "runtime/stipple_size.h"

namespace {

struct Fixture {
    stipple::Asset asset;
    std::vector<float> pos, nrm, radius, scale, size, copy_src;
};

Fixture* fixture(uint32_t points) {
    static std::unique_ptr<Fixture> cache[2];
    int slot = points > 50000;
    if (cache[slot]) return cache[slot].get();
    auto f = std::make_unique<Fixture>();
    if (!stipple::bench::bake_asset("CesiumMan/CesiumMan.glb", points, &f->asset)) return nullptr;
    size_t n = f->asset.points.point_count;
    f->pos.resize(n * 3);
    f->nrm.resize(n * 3);
    f->radius.resize(n);
    f->scale.assign(n, 1.0f);
    f->size.resize(n);
    f->copy_src.resize(n * 3);
    const stipple::MeshView& m = f->asset.mesh;
    stipple::place_points(f->asset.points, m.indices, m.positions, m.normals, f->pos.data(),
                          f->nrm.data());
    cache[slot] = std::move(f);
    return cache[slot].get();
}

void report(benchmark::State& state, size_t points, size_t bytes_per_point) {
    state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(points));
    state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(points * bytes_per_point));
    state.counters["per_point"] =
        benchmark::Counter(double(points), benchmark::Counter::kIsIterationInvariantRate |
                                               benchmark::Counter::kInvert);
}

// Alg. 6.3: host index + 2 barycentrics in, 3 vertex positions/normals gathered (random
// access into a small mesh: cache resident), position + normal out.
void BM_PlacePoints(benchmark::State& state) {
    Fixture* f = fixture(uint32_t(state.range(0)));
    if (!f) return state.SkipWithError("fixture failed");
    const stipple::MeshView& m = f->asset.mesh;
    for (auto _ : state) {
        stipple::place_points(f->asset.points, m.indices, m.positions, m.normals, f->pos.data(),
                              f->nrm.data());
        benchmark::ClobberMemory();
    }
    report(state, f->asset.points.point_count, 12 + 24);
}

void BM_CopyStoredPositions(benchmark::State& state) {
    Fixture* f = fixture(uint32_t(state.range(0)));
    if (!f) return state.SkipWithError("fixture failed");
    for (auto _ : state) {
        std::memcpy(f->pos.data(), f->copy_src.data(), f->pos.size() * 4);
        benchmark::ClobberMemory();
    }
    report(state, f->asset.points.point_count, 24);
}

// Alg. 6.4: offsets + neighbour indices in, neighbour positions gathered, radius out.
void BM_RecomputeRelevance(benchmark::State& state) {
    Fixture* f = fixture(uint32_t(state.range(0)));
    if (!f) return state.SkipWithError("fixture failed");
    const stipple::PointsView& p = f->asset.points;
    for (auto _ : state) {
        stipple::recompute_relevance(p, f->pos.data(), f->scale.data(), p.radius, f->radius.data());
        benchmark::ClobberMemory();
    }
    double nbrs = double(p.neighbour_count) / double(p.point_count);
    report(state, p.point_count, size_t(4 + 12 + 4 + nbrs * 16));
    state.counters["neighbours_per_point"] = nbrs;
}

void BM_StoredRelevance(benchmark::State& state) {
    Fixture* f = fixture(uint32_t(state.range(0)));
    if (!f) return state.SkipWithError("fixture failed");
    const stipple::PointsView& p = f->asset.points;
    for (auto _ : state) {
        std::memcpy(f->radius.data(), p.radius, size_t(p.point_count) * 4);
        benchmark::ClobberMemory();
    }
    report(state, p.point_count, 8);
}

// Alg. 3.2 with screen-space region and slope factor, Lambert tone.
void BM_SizeStipples(benchmark::State& state) {
    Fixture* f = fixture(uint32_t(state.range(0)));
    if (!f) return state.SkipWithError("fixture failed");
    stipple::SizeParams params;
    params.view_projection[1][1] = 2.0f;
    params.view_projection[2][3] = -1.0f;
    params.view_projection[3][3] = 3.0f;
    params.eye = glm::vec3(0, 1, 3);
    const uint32_t n = f->asset.points.point_count;
    const float* radius = f->asset.points.radius;
    for (auto _ : state) {
        stipple::size_stipples(n, f->pos.data(), f->nrm.data(), radius, params, f->size.data());
        benchmark::ClobberMemory();
    }
    report(state, n, 12 + 12 + 4 + 4);
}

void BM_ConstantSize(benchmark::State& state) {
    Fixture* f = fixture(uint32_t(state.range(0)));
    if (!f) return state.SkipWithError("fixture failed");
    for (auto _ : state) {
        std::fill(f->size.begin(), f->size.end(), 2.0f);
        benchmark::ClobberMemory();
    }
    report(state, f->asset.points.point_count, 4);
}

BENCHMARK(BM_PlacePoints)->Arg(20000)->Arg(100000);
BENCHMARK(BM_CopyStoredPositions)->Arg(20000)->Arg(100000);
BENCHMARK(BM_RecomputeRelevance)->Arg(20000)->Arg(100000);
BENCHMARK(BM_StoredRelevance)->Arg(20000)->Arg(100000);
BENCHMARK(BM_SizeStipples)->Arg(20000)->Arg(100000);
BENCHMARK(BM_ConstantSize)->Arg(20000)->Arg(100000);

}  // namespace
