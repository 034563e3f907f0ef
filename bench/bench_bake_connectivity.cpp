// The bake's point hierarchy on hostile connectivity against a regular grid of the same
// triangle count (docs/hierarchy.md, "Complexity"): a fan around one vertex, a non-manifold
// star on one edge, the fan with every vertex duplicated. Each run bakes the grid and the
// hostile mesh once per iteration and reports both times and their ratio (issue target:
// ratio <= 2 for fans of 10,000 and 70,000 triangles). Peak memory is measured on the
// command line (`make-test-meshes`, `/usr/bin/time -f '%e s %M KB' stipple-bake`).
#include <benchmark/benchmark.h>

#include <chrono>

#include "bake/connectivity_meshes.h"
#include "bake/point_hierarchy.h"

namespace {

using namespace stipple::bake;

double bake_seconds(const RawScene& s, HierarchyMethod method) {
    HierarchyConfig config;
    config.method = method;
    PointHierarchy p;
    const auto t0 = std::chrono::steady_clock::now();
    const BakeError e = build_point_hierarchy(s, config, &p, nullptr);
    const auto t1 = std::chrono::steady_clock::now();
    return e.ok() ? std::chrono::duration<double>(t1 - t0).count() : -1;
}

// range(0): method (0 eliminate, 1 simplify, 2 relax); range(1): mesh (0 fan, 1 star,
// 2 duplicates); range(2): triangles.
void BM_HostileVsGrid(benchmark::State& state) {
    const HierarchyMethod methods[] = {HierarchyMethod::eliminate, HierarchyMethod::simplify,
                                       HierarchyMethod::relax};
    const HierarchyMethod method = methods[state.range(0)];
    const uint32_t n = uint32_t(state.range(2));
    const RawScene grid = meshes::grid(n);
    const RawScene hostile = state.range(1) == 0   ? meshes::fan(n)
                             : state.range(1) == 1 ? meshes::star(n)
                                                   : meshes::duplicates(n);
    double grid_s = 0, hostile_s = 0;
    for (auto _ : state) {
        grid_s += bake_seconds(grid, method);
        hostile_s += bake_seconds(hostile, method);
    }
    const double runs = double(state.iterations());
    state.counters["grid_s"] = grid_s / runs;
    state.counters["hostile_s"] = hostile_s / runs;
    state.counters["ratio"] = grid_s > 0 ? hostile_s / grid_s : 0;
}

BENCHMARK(BM_HostileVsGrid)
    ->ArgNames({"method", "mesh", "triangles"})
    ->ArgsProduct({{0, 1, 2}, {0, 1, 2}, {2000, 10000, 70000}})
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

}  // namespace
