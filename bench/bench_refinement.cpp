// Benchmark of the run-time refinement (runtime/point_refinement.h) on CesiumMan baked to 20k
// points, bind pose, 640x480, constant tone 0.3, on the triangulation of the baked points (as
// the pipeline refines):
//   - close-up (zoom 8 on the chest): ns per extra point generated, against the simplest
//     alternative: a bake dense enough to need no refinement, whose points are placed
//     (Alg. 6.3) and relevance-updated (Alg. 6.4) every frame — per point of that bake;
//   - full view (zoom 0.5): what the refinement costs when the baked hierarchy suffices (its
//     per-vertex and per-triangle checks), per triangle of the domain (~2 per baked point);
//   - building the triangulation at load, per baked point;
//   - the early-out (runtime/refinement_cull.h), CesiumMan at 100k points, bind pose: the
//     stage as it ran before (every baked point placed, then refine_points) against the culled
//     one (refinement_cull, then only the active clusters' corners placed and refined), in
//     interleaved rounds of one run, ns per domain triangle (min and median over rounds) and
//     their ratio, for a far view (nothing added) and closer ones (some clusters active).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <glm/gtc/matrix_transform.hpp>
#include <memory>
#include <vector>

#include "bench/bench_asset.h"
#include "runtime/point_placement.h"
#include "runtime/point_refinement.h"
#include "runtime/point_triangulation.h"

namespace {

struct Fixture {
    stipple::Asset asset;
    stipple::RefinementMesh refinement;
    stipple::PointTriangulation triangles;
    stipple::MeshView domain;  // the triangles between the baked points
    std::vector<float> bind, bind_normals, positions, normals, radius;
    std::vector<uint32_t> triangle, index;
    stipple::RefinedPoints out;
    glm::vec3 lo = glm::vec3(1e30f), hi = glm::vec3(-1e30f);
};

Fixture* fixture(uint32_t points) {
    static std::unique_ptr<Fixture> cache[2];
    const int slot = points > 50000;
    if (cache[slot]) return cache[slot].get();
    auto f = std::make_unique<Fixture>();
    if (!stipple::bench::bake_asset("CesiumMan/CesiumMan.glb", points, &f->asset)) return nullptr;
    const stipple::MeshView& m = f->asset.mesh;
    const size_t n = f->asset.points.point_count, capacity = 1u << 20;
    f->bind.resize(n * 3);
    f->bind_normals.resize(n * 3);
    stipple::place_points(f->asset.points, m.indices, m.positions, m.normals, f->bind.data(),
                          f->bind_normals.data());
    const double area = stipple::surface_area(m);
    if (!stipple::triangulate_points(uint32_t(n), f->bind.data(), f->bind_normals.data(), area, &m,
                                     f->asset.points.host_triangle, &f->triangles)
             .ok())
        return nullptr;
    f->domain.vertex_count = uint32_t(n);
    f->domain.triangle_count = f->triangles.triangle_count;
    f->domain.positions = f->bind.data();
    f->domain.normals = f->bind_normals.data();
    f->domain.indices = f->triangles.indices.get();
    if (!stipple::refinement_init(&f->refinement, f->domain, f->asset.points, f->bind.data(),
                                  stipple::RefinementDomain::points, &m)
             .ok())
        return nullptr;
    f->positions.resize(std::max(capacity, n) * 3);
    f->normals.resize(std::max(capacity, n) * 3);
    f->radius.resize(std::max(capacity, n));
    f->triangle.resize(capacity);
    f->index.resize(capacity);
    f->out.capacity = uint32_t(capacity);
    f->out.positions = f->positions.data();
    f->out.normals = f->normals.data();
    f->out.radius = f->radius.data();
    f->out.triangle = f->triangle.data();
    f->out.index = f->index.data();
    for (uint32_t i = 0; i < m.vertex_count; ++i) {
        const glm::vec3 p(m.positions[i * 3], m.positions[i * 3 + 1], m.positions[i * 3 + 2]);
        f->lo = glm::min(f->lo, p);
        f->hi = glm::max(f->hi, p);
    }
    cache[slot] = std::move(f);
    return cache[slot].get();
}

// Camera in front of the bind pose (CesiumMan faces +Y in bind space before its node
// transform; the benchmark only needs a fixed, reproducible view of the body).
stipple::SizeParams view(const Fixture& f, float zoom) {
    stipple::SizeParams s;
    const glm::vec3 centre = 0.5f * (f.lo + f.hi);
    const float radius = 0.5f * glm::length(f.hi - f.lo);
    s.eye = centre + glm::vec3(0.0f, -radius / std::sin(glm::radians(15.0f)), 0.0f);
    const float fov = 2.0f * std::atan(std::tan(glm::radians(15.0f)) / zoom);
    s.view_projection = glm::perspective(fov, 640.0f / 480.0f, 0.05f * radius, 10.0f * radius) *
                        glm::lookAt(s.eye, centre, glm::vec3(0, 0, 1));
    s.viewport_height = 480.0f;
    s.constant_tone = 0.3f;
    return s;
}

void BM_RefineCloseUp(benchmark::State& state) {
    Fixture* f = fixture(20000);
    if (!f) return state.SkipWithError("fixture failed");
    const stipple::SizeParams s = view(*f, 8.0f);
    const stipple::MeshView& m = f->domain;
    for (auto _ : state) {
        stipple::refine_points(&f->refinement, m, m.positions, m.normals, nullptr, s, true, &f->out,
                               nullptr);
        benchmark::ClobberMemory();
    }
    state.counters["extra_points"] = double(f->out.count);
    state.counters["per_point"] =
        benchmark::Counter(double(f->out.count), benchmark::Counter::kIsIterationInvariantRate |
                                                     benchmark::Counter::kInvert);
}

// The simplest alternative: bake that many more points and place + update them all.
void BM_PlaceAndRelevanceOfADenseBake(benchmark::State& state) {
    Fixture* f = fixture(uint32_t(state.range(0)));
    if (!f) return state.SkipWithError("fixture failed");
    const stipple::MeshView& m = f->asset.mesh;
    const stipple::PointsView& p = f->asset.points;
    std::vector<float> scale(p.point_count);
    stipple::relevance_scale(p, f->bind.data(), scale.data());
    for (auto _ : state) {
        stipple::place_points(p, m.indices, m.positions, m.normals, f->positions.data(),
                              f->normals.data());
        stipple::recompute_relevance(p, f->positions.data(), scale.data(), p.radius,
                                     f->radius.data());
        benchmark::ClobberMemory();
    }
    state.counters["per_point"] =
        benchmark::Counter(double(p.point_count), benchmark::Counter::kIsIterationInvariantRate |
                                                      benchmark::Counter::kInvert);
}

void BM_RefineFullViewNothingNeeded(benchmark::State& state) {
    Fixture* f = fixture(20000);
    if (!f) return state.SkipWithError("fixture failed");
    stipple::SizeParams s = view(*f, 0.5f);
    const stipple::MeshView& m = f->domain;
    for (auto _ : state) {
        stipple::refine_points(&f->refinement, m, m.positions, m.normals, nullptr, s, true, &f->out,
                               nullptr);
        benchmark::ClobberMemory();
    }
    state.counters["extra_points"] = double(f->out.count);
    state.counters["per_triangle"] =
        benchmark::Counter(double(m.triangle_count), benchmark::Counter::kIsIterationInvariantRate |
                                                         benchmark::Counter::kInvert);
}

void BM_TriangulateAtLoad(benchmark::State& state) {
    Fixture* f = fixture(20000);
    if (!f) return state.SkipWithError("fixture failed");
    const uint32_t n = f->asset.points.point_count;
    for (auto _ : state) {
        stipple::PointTriangulation t;
        const stipple::Status st = stipple::triangulate_points(
            n, f->bind.data(), f->bind_normals.data(), stipple::surface_area(f->asset.mesh),
            &f->asset.mesh, f->asset.points.host_triangle, &t);
        if (!st.ok()) return state.SkipWithError(st.message);
        benchmark::DoNotOptimize(t.triangle_count);
    }
    state.counters["per_point"] = benchmark::Counter(
        double(n), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

// The stage before and after the early-out, interleaved (see the header).
void BM_RefineEarlyOut(benchmark::State& state) {
    Fixture* f = fixture(100000);
    if (!f) return state.SkipWithError("fixture failed");
    const stipple::SizeParams s = view(*f, float(state.range(0)) / 100.0f);
    const stipple::MeshView& m = f->asset.mesh;
    const stipple::PointsView& pts = f->asset.points;
    stipple::MeshView domain = f->domain;
    std::vector<float> pos(size_t(pts.point_count) * 3), nrm(size_t(pts.point_count) * 3);
    domain.positions = pos.data();
    domain.normals = nrm.data();
    stipple::RefinementMesh& r = f->refinement;
    constexpr int kRounds = 7, kReps = 10;
    std::vector<double> before, after;
    uint32_t count[2] = {0, 0}, active = 0;
    using Clock = std::chrono::steady_clock;
    for (auto _ : state) {
        for (int round = 0; round < kRounds; ++round) {
            for (int variant = 0; variant < 2; ++variant) {
                const Clock::time_point t0 = Clock::now();
                for (int rep = 0; rep < kReps; ++rep) {
                    if (variant == 0) {
                        stipple::place_points(pts, m.indices, m.positions, m.normals, pos.data(),
                                              nrm.data());
                        stipple::refine_points(&r, domain, pos.data(), nrm.data(), nullptr, s, true,
                                               &f->out, nullptr);
                    } else {
                        f->out.count = 0;
                        active = stipple::refinement_cull(&r.cull, m, m.positions, m.normals, s,
                                                          true, stipple::refinement_near_w(s));
                        if (active > 0) {
                            stipple::place_listed_points(pts, m.indices, m.positions, m.normals,
                                                         r.cull.list.get(), r.cull.list_count,
                                                         pos.data(), nrm.data());
                            stipple::refine_points_culled(&r, domain, pos.data(), nrm.data(), s,
                                                          true, &f->out, nullptr, nullptr);
                        }
                    }
                    benchmark::ClobberMemory();
                }
                const double ns =
                    std::chrono::duration<double, std::nano>(Clock::now() - t0).count() /
                    (double(kReps) * domain.triangle_count);
                (variant == 0 ? before : after).push_back(ns);
                count[variant] = f->out.count;
            }
        }
    }
    auto min_median = [](std::vector<double> v, double* lo, double* mid) {
        std::sort(v.begin(), v.end());
        *lo = v.front();
        *mid = v[v.size() / 2];
    };
    double b_min, b_med, a_min, a_med;
    min_median(before, &b_min, &b_med);
    min_median(after, &a_min, &a_med);
    state.counters["before_ns_min"] = b_min;
    state.counters["before_ns_median"] = b_med;
    state.counters["after_ns_min"] = a_min;
    state.counters["after_ns_median"] = a_med;
    state.counters["ratio_min"] = a_min / b_min;
    state.counters["ratio_median"] = a_med / b_med;
    state.counters["extra_points"] = double(count[0]);
    state.counters["same_count"] = double(count[0] == count[1]);
    state.counters["active_clusters"] = double(active);
    state.counters["clusters"] = double(r.cull.cluster_count);
}

BENCHMARK(BM_RefineCloseUp);
BENCHMARK(BM_RefineEarlyOut)
    ->Arg(50)
    ->Arg(300)
    ->Arg(800)
    ->Arg(1600)
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TriangulateAtLoad);
BENCHMARK(BM_PlaceAndRelevanceOfADenseBake)->Arg(100000);
BENCHMARK(BM_RefineFullViewNothingNeeded);

}  // namespace
