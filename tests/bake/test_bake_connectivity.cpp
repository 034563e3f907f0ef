// The bake's cost does not depend on a vertex's valence (docs/hierarchy.md, "Complexity"): a
// fan of 10,000 triangles around one vertex and the fan as a soup of duplicated vertices
// cost the projections (thesis §4.4.2) no more than twice what a regular grid of 10,000
// triangles does, counted in candidate triangles examined (no timing in tests:
// bench/bench_bake_connectivity.cpp times them). Every method bakes them. (A non-manifold
// star of 10,000 triangles on one edge is not yet linear: see "Complexity".)
#include <gtest/gtest.h>

#include "bake/connectivity_meshes.h"
#include "bake/point_hierarchy.h"

namespace stipple::bake {
namespace {

constexpr uint32_t kTriangles = 10000, kPoints = 20000;

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

TEST_P(ConnectivityCost, HighValenceMeshesCostAtMostTwiceAGrid) {
    PointHierarchy p;
    const HierarchyStats grid = bake(meshes::grid(kTriangles), GetParam(), &p);
    ASSERT_GT(grid.projection_candidates, 0u);
    const std::pair<const char*, RawScene> hostile[] = {
        {"fan", meshes::fan(kTriangles)}, {"duplicates", meshes::duplicates(kTriangles)}};
    for (const auto& [name, scene] : hostile) {
        const HierarchyStats s = bake(scene, GetParam(), &p);
        EXPECT_EQ(p.host_triangle.size(), size_t(kPoints)) << name;
        EXPECT_LE(s.projection_candidates, 2 * grid.projection_candidates)
            << name << ": " << s.projection_candidates << " against the grid's "
            << grid.projection_candidates;
    }
}

INSTANTIATE_TEST_SUITE_P(Methods, ConnectivityCost,
                         ::testing::Values(HierarchyMethod::simplify, HierarchyMethod::relax),
                         [](const ::testing::TestParamInfo<HierarchyMethod>& param) {
                             return param.param == HierarchyMethod::simplify ? "simplify" : "relax";
                         });

TEST(ConnectivityCost, EliminateBakesHighValenceMeshes) {
    for (const RawScene& s : {meshes::fan(kTriangles), meshes::duplicates(kTriangles)}) {
        PointHierarchy p;
        bake(s, HierarchyMethod::eliminate, &p);
        EXPECT_EQ(p.host_triangle.size(), size_t(kPoints));
    }
}

}  // namespace
}  // namespace stipple::bake
