// The bake's cost does not depend on a vertex's valence or on how much surface crowds a
// little volume (docs/hierarchy.md, "Complexity"): a fan of 10,000 triangles around one
// vertex, the fan as a soup of duplicated vertices and a non-manifold star of 10,000
// triangles on one edge cost every method no more than a small multiple of what a regular
// grid of 10,000 triangles does, counted in work done (no timing in tests:
// bench/bench_bake_connectivity.cpp times them): input triangles examined by the projections
// (thesis §4.4.2; simplify, relax) and samples or points examined by the neighbour searches
// (eliminate's eliminations and relevant neighbours, relax's level order).
#include <gtest/gtest.h>

#include "bake/connectivity_meshes.h"
#include "bake/point_hierarchy.h"

namespace stipple::bake {
namespace {

constexpr uint32_t kTriangles = 10000, kPoints = 20000;
// Work on a hostile mesh at most this many times a grid's (measured: 0.4-1.5).
constexpr uint64_t kMaxRatio = 2;

HierarchyStats bake(const RawScene& s, HierarchyMethod method, PointHierarchy* out) {
    HierarchyConfig config;
    config.method = method;
    config.point_count = kPoints;
    HierarchyStats stats;
    const BakeError e = build_point_hierarchy(s, config, out, &stats);
    EXPECT_TRUE(e.ok()) << e.message;
    return stats;
}

class ConnectivityCost : public ::testing::TestWithParam<HierarchyMethod> {};

TEST_P(ConnectivityCost, HostileMeshesCostAFewTimesAGrid) {
    const HierarchyMethod method = GetParam();
    PointHierarchy p;
    const HierarchyStats grid = bake(meshes::grid(kTriangles), method, &p);
    const bool projects = method != HierarchyMethod::eliminate;
    const bool searches = method != HierarchyMethod::simplify;
    if (projects) {
        ASSERT_GT(grid.projection_candidates, 0u);
    }
    if (searches) {
        ASSERT_GT(grid.neighbour_candidates, 0u);
    }
    RecordProperty("grid_projection_candidates", std::to_string(grid.projection_candidates));
    RecordProperty("grid_neighbour_candidates", std::to_string(grid.neighbour_candidates));
    const std::pair<const char*, RawScene> hostile[] = {
        {"fan", meshes::fan(kTriangles)},
        {"duplicates", meshes::duplicates(kTriangles)},
        {"star", meshes::star(kTriangles)}};
    for (const auto& [name, scene] : hostile) {
        const HierarchyStats s = bake(scene, method, &p);
        EXPECT_EQ(p.host_triangle.size(), size_t(kPoints)) << name;
        ASSERT_EQ(p.neighbour_offsets.size(), size_t(kPoints) + 1) << name;
        // Bounded neighbour lists: at most 4 relevant neighbours per point.
        EXPECT_LE(p.neighbours.size(), size_t(kPoints) * 4) << name;
        EXPECT_LE(s.projection_candidates, kMaxRatio * grid.projection_candidates)
            << name << ": " << s.projection_candidates << " triangles examined, the grid "
            << grid.projection_candidates;
        EXPECT_LE(s.neighbour_candidates, kMaxRatio * grid.neighbour_candidates)
            << name << ": " << s.neighbour_candidates << " neighbour candidates, the grid "
            << grid.neighbour_candidates;
        RecordProperty(std::string(name) + "_projection_candidates",
                       std::to_string(s.projection_candidates));
        RecordProperty(std::string(name) + "_neighbour_candidates",
                       std::to_string(s.neighbour_candidates));
    }
}

INSTANTIATE_TEST_SUITE_P(Methods, ConnectivityCost,
                         ::testing::Values(HierarchyMethod::eliminate, HierarchyMethod::simplify,
                                           HierarchyMethod::relax),
                         [](const ::testing::TestParamInfo<HierarchyMethod>& param) {
                             return param.param == HierarchyMethod::eliminate  ? "eliminate"
                                    : param.param == HierarchyMethod::simplify ? "simplify"
                                                                               : "relax";
                         });

}  // namespace
}  // namespace stipple::bake
