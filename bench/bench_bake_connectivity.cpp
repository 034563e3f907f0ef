// The bake's point hierarchy on hostile connectivity against a regular grid of the same
// triangle count (docs/hierarchy.md, "Complexity"): a fan around one vertex, a non-manifold
// star on one edge, the fan with every vertex duplicated. Each iteration bakes the grid and
// the hostile mesh (20,000 points), each in a child process of its own, and reports both
// times, both peak memories (the child's maximum resident set, which includes the few MB the
// bench itself holds) and their ratios (issue target: both ratios <= 2 for 10,000 and 70,000
// triangles).
#include <benchmark/benchmark.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>

#include "bake/connectivity_meshes.h"
#include "bake/point_hierarchy.h"

namespace {

using namespace stipple::bake;

struct Cost {
    double seconds = -1;
    double peak_mb = -1;
};

// Bakes in a forked child: its time comes back through a pipe, its peak memory from wait4.
Cost bake_cost(const RawScene& s, HierarchyMethod method) {
    int fd[2];
    if (pipe(fd) != 0) return {};
    const pid_t child = fork();
    if (child < 0) return {};
    if (child == 0) {
        close(fd[0]);
        HierarchyConfig config;
        config.method = method;
        PointHierarchy p;
        const auto t0 = std::chrono::steady_clock::now();
        const BakeError e = build_point_hierarchy(s, config, &p, nullptr);
        const auto t1 = std::chrono::steady_clock::now();
        const double seconds = e.ok() ? std::chrono::duration<double>(t1 - t0).count() : -1;
        const ssize_t written = write(fd[1], &seconds, sizeof(seconds));
        _exit(written == ssize_t(sizeof(seconds)) ? 0 : 1);
    }
    close(fd[1]);
    Cost cost;
    if (read(fd[0], &cost.seconds, sizeof(cost.seconds)) != ssize_t(sizeof(cost.seconds)))
        cost.seconds = -1;
    close(fd[0]);
    int status = 0;
    struct rusage usage = {};
    if (wait4(child, &status, 0, &usage) == child && WIFEXITED(status) && WEXITSTATUS(status) == 0)
        cost.peak_mb = double(usage.ru_maxrss) / 1024.0;  // KB on Linux
    return cost;
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
    Cost g, h;
    for (auto _ : state) {
        g = bake_cost(grid, method);
        h = bake_cost(hostile, method);
    }
    state.counters["grid_s"] = g.seconds;
    state.counters["hostile_s"] = h.seconds;
    state.counters["time_ratio"] = g.seconds > 0 ? h.seconds / g.seconds : 0;
    state.counters["grid_MB"] = g.peak_mb;
    state.counters["hostile_MB"] = h.peak_mb;
    state.counters["memory_ratio"] = g.peak_mb > 0 ? h.peak_mb / g.peak_mb : 0;
    if (g.seconds < 0 || h.seconds < 0 || g.peak_mb < 0 || h.peak_mb < 0)
        state.SkipWithError("a bake failed");
}

BENCHMARK(BM_HostileVsGrid)
    ->ArgNames({"method", "mesh", "triangles"})
    ->ArgsProduct({{0, 1, 2}, {0, 1, 2}, {10000, 70000}})
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

}  // namespace
