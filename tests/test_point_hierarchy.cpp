// The point hierarchies of thesis ch. 4 (simplify) and ch. 5 (relax), and the naive
// baseline (random): every point on the input surface with valid barycentrics and in-range
// neighbours, radii coarse to fine, the same bytes for the same seed (in memory and from the
// CLI), evenly spread compared with random points, randomization that folds nothing and
// makes no slivers, and no crash on malformed meshes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <glm/glm.hpp>
#include <sstream>

#include "bake/asset_writer.h"
#include "bake/point_hierarchy.h"
#include "bake/scene_import.h"
#include "tests/frame_check_util.h"

namespace {

using namespace stipple::bake;
using stipple::test::bin;
using stipple::test::run;
using stipple::test::source;

RawScene tube() {
    RawScene s;
    std::string error;
    EXPECT_TRUE(import_scene(source("assets/stretch_tube/stretch_tube.gltf"), &s, &error)) << error;
    return s;
}

glm::dvec3 corner(const RawScene& s, uint32_t t, int k) {
    const float* p = &s.positions[size_t(s.indices[size_t(t) * 3 + size_t(k)]) * 3];
    return glm::dvec3(p[0], p[1], p[2]);
}

// Distance from p to triangle t (projection onto the plane, clamped by edge distances).
double distance_to_triangle(const RawScene& s, uint32_t t, const glm::dvec3& p) {
    glm::dvec3 a = corner(s, t, 0), b = corner(s, t, 1), c = corner(s, t, 2);
    glm::dvec3 n = glm::normalize(glm::cross(b - a, c - a));
    glm::dvec3 q = p - n * glm::dot(p - a, n);
    bool inside = glm::dot(glm::cross(b - a, q - a), n) >= -1e-12 &&
                  glm::dot(glm::cross(c - b, q - b), n) >= -1e-12 &&
                  glm::dot(glm::cross(a - c, q - c), n) >= -1e-12;
    if (inside) return std::fabs(glm::dot(p - a, n));
    auto seg = [&](glm::dvec3 x, glm::dvec3 y) {
        double h = glm::clamp(glm::dot(p - x, y - x) / glm::dot(y - x, y - x), 0.0, 1.0);
        return glm::length(p - (x + (y - x) * h));
    };
    return std::min({seg(a, b), seg(b, c), seg(c, a)});
}

const char* method_name(HierarchyMethod m) {
    return m == HierarchyMethod::simplify ? "simplify" : m == HierarchyMethod::relax ? "relax" : "random";
}

// Every point on the input surface (the nearest input triangle, brute force, within 1e-5 of
// the bounding-box diagonal), barycentrics valid, neighbours in range and not the point
// itself, radius non-increasing from coarse to fine.
void expect_valid_hierarchy(const RawScene& s, const PointHierarchy& p) {
    glm::dvec3 lo(1e30), hi(-1e30);
    for (size_t v = 0; v < s.vertex_count(); ++v) {
        glm::dvec3 x(s.positions[v * 3], s.positions[v * 3 + 1], s.positions[v * 3 + 2]);
        lo = glm::min(lo, x);
        hi = glm::max(hi, x);
    }
    const double diagonal = glm::length(hi - lo);
    ASSERT_EQ(p.neighbour_offsets.size(), p.size() + 1);
    for (uint32_t i = 0; i < p.size(); ++i) {
        ASSERT_LT(p.host_triangle[i], s.triangle_count());
        const float u = p.bary_u[i], v = p.bary_v[i];
        ASSERT_TRUE(u >= 0 && v >= 0 && u + v <= 1.0f + 1e-6f) << i;
        const uint32_t t = p.host_triangle[i];
        glm::dvec3 x = corner(s, t, 0) * double(u) + corner(s, t, 1) * double(v) +
                       corner(s, t, 2) * (1.0 - u - v);
        // On the surface: the nearest input triangle (brute force) is within 1e-5 of the
        // bounding-box diagonal.
        double nearest = 1e30;
        for (uint32_t k = 0; k < s.triangle_count() && nearest > 1e-5 * diagonal; ++k)
            nearest = std::min(nearest, distance_to_triangle(s, k, x));
        ASSERT_LE(nearest, 1e-5 * diagonal) << i;
        if (i > 0) {
            ASSERT_LE(p.radius[i], p.radius[i - 1]) << "coarse to fine at " << i;
        }
        ASSERT_LE(p.neighbour_offsets[i], p.neighbour_offsets[i + 1]);
        for (uint32_t k = p.neighbour_offsets[i]; k < p.neighbour_offsets[i + 1]; ++k) {
            ASSERT_LT(p.neighbours[k], p.size());
            ASSERT_NE(p.neighbours[k], i);
        }
    }
}

class PointHierarchyMethods : public ::testing::TestWithParam<HierarchyMethod> {};

TEST_P(PointHierarchyMethods, PointsLieOnTheInputSurfaceWithValidData) {
    RawScene s = tube();
    HierarchyConfig config;
    config.method = GetParam();
    config.point_count = 3000;
    PointHierarchy p;
    std::string error;
    ASSERT_TRUE(build_point_hierarchy(s, config, &p, nullptr, &error)) << error;
    ASSERT_EQ(p.size(), 3000u);
    expect_valid_hierarchy(s, p);
}

INSTANTIATE_TEST_SUITE_P(AllMethods, PointHierarchyMethods,
                         ::testing::Values(HierarchyMethod::simplify, HierarchyMethod::relax,
                                           HierarchyMethod::random),
                         [](const ::testing::TestParamInfo<HierarchyMethod>& param) {
                             return std::string(method_name(param.param));
                         });

// Thesis §4.4: randomize and project keeps every point on the input surface at the
// largest jitter too (input vertices and subdivision vertices are projected back), folds
// nothing, and the sliver guard keeps the tube's faces as fat as plain bisection does.
TEST(PointHierarchy, RandomizeAndProjectStaysOnTheSurfaceWithoutSlivers) {
    RawScene s = tube();
    HierarchyConfig config;
    config.point_count = 3000;
    config.jitter = 0.75f;
    PointHierarchy p;
    HierarchyStats stats;
    std::string error;
    ASSERT_TRUE(build_point_hierarchy(s, config, &p, &stats, &error)) << error;
    expect_valid_hierarchy(s, p);
    EXPECT_EQ(stats.slivers_after_subdivision, stats.slivers_before_subdivision);
    config.jitter = 0;
    PointHierarchy plain;
    ASSERT_TRUE(build_point_hierarchy(s, config, &plain, nullptr, &error)) << error;
    EXPECT_NE(p.bary_u, plain.bary_u);  // the jitter moved the points
}

TEST_P(PointHierarchyMethods, SameSeedSameBytesOtherSeedOtherPoints) {
    RawScene s = tube();
    HierarchyConfig config;
    config.method = GetParam();
    config.point_count = 2000;
    PointHierarchy a, b, c;
    std::string error;
    ASSERT_TRUE(build_point_hierarchy(s, config, &a, nullptr, &error));
    ASSERT_TRUE(build_point_hierarchy(s, config, &b, nullptr, &error));
    config.seed = 2;
    ASSERT_TRUE(build_point_hierarchy(s, config, &c, nullptr, &error));
    EXPECT_EQ(encode_asset(s, a), encode_asset(s, b));
    EXPECT_NE(encode_asset(s, a), encode_asset(s, c));
}

// Same input, options and seed: byte-identical asset files from two CLI bakes, per method.
TEST(PointHierarchy, TwoBakesWriteIdenticalBytes) {
    const std::string dir = ::testing::TempDir() + "determinism_" + std::to_string(getpid());
    run("mkdir -p " + dir);
    for (const char* m : {"simplify", "relax", "random"}) {
        std::string bake = bin("stipple-bake") + " " + source("assets/CesiumMan/CesiumMan.glb") +
                           " --points 5000 --seed 7 --quiet --method " + m + " -o " + dir + "/";
        ASSERT_EQ(run(bake + "a.stip"), 0) << m;
        ASSERT_EQ(run(bake + "b.stip"), 0) << m;
        EXPECT_EQ(run("cmp " + dir + "/a.stip " + dir + "/b.stip"), 0) << m;
    }
    run("rm -rf " + dir);
}

// Spacing quality from stipple-inspect --quality: the coefficient of variation of the
// nearest-neighbour distance is clearly lower than for random points at every level, for
// both methods, and token relaxation is the more even at the finest level (thesis §5.7.3).
TEST(PointHierarchy, SpreadsMoreEvenlyThanRandomPoints) {
    const std::string dir = ::testing::TempDir() + "quality_" + std::to_string(getpid());
    run("mkdir -p " + dir);
    std::vector<double> cv[3];
    const char* methods[3] = {"simplify", "random", "relax"};
    for (int m = 0; m < 3; ++m) {
        // 20k points: the 16k prefix is a finished level, not the last, cut-short one.
        std::string asset = dir + "/" + methods[m] + ".stip", log;
        ASSERT_EQ(run(bin("stipple-bake") + " " + source("assets/CesiumMan/CesiumMan.glb") +
                      " -o " + asset + " --points 20000 --quiet --method " + methods[m]),
                  0);
        ASSERT_EQ(run(bin("stipple-inspect") + " " + asset + " --quality", &log), 0) << log;
        for (size_t at = log.find("\"nn_cv\": "); at != std::string::npos;
             at = log.find("\"nn_cv\": ", at + 1))
            cv[m].push_back(std::atof(log.c_str() + at + 9));
    }
    for (int m = 0; m < 3; ++m) ASSERT_EQ(cv[m].size(), 3u);  // 1k, 4k, 16k
    for (size_t level = 0; level < 3; ++level) {
        std::printf("level %zu: nn CV simplify %.3f, relax %.3f, random %.3f\n", level,
                    cv[0][level], cv[2][level], cv[1][level]);
        EXPECT_LT(cv[0][level], 0.7 * cv[1][level]);
        EXPECT_LT(cv[2][level], 0.7 * cv[1][level]);
    }
    EXPECT_LT(cv[2][2], cv[0][2]);
    run("rm -rf " + dir);
}

// Malformed meshes bake or fail with a named error, for every method: a non-manifold edge
// (three faces), a degenerate triangle, an isolated vertex and open boundaries bake; no
// non-degenerate triangle, a non-finite position or an index out of range fail.
TEST_P(PointHierarchyMethods, MalformedMeshesBakeOrFailWithANamedError) {
    RawScene s;
    s.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0.5f, 0.5f, 0, 7, 7, 7};
    s.normals.assign(s.positions.size(), 0.0f);
    // Edge (0,1) has three faces; face 3 is degenerate (collinear); vertex 6 is unused.
    s.indices = {0, 1, 2, 1, 0, 3, 0, 1, 4, 0, 5, 5, 1, 2, 5};
    HierarchyConfig config;
    config.method = GetParam();
    config.point_count = 500;
    PointHierarchy p;
    HierarchyStats stats;
    std::string error;
    ASSERT_TRUE(build_point_hierarchy(s, config, &p, &stats, &error)) << error;
    EXPECT_EQ(p.size(), 500u);
    EXPECT_GE(stats.skipped_faces, 1u);
    expect_valid_hierarchy(s, p);
    for (uint32_t i = 0; i < p.size(); ++i) EXPECT_NE(p.host_triangle[i], 3u);  // degenerate

    RawScene one;  // a single open triangle: three boundary edges
    one.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    one.normals.assign(9, 0.0f);
    one.indices = {0, 1, 2};
    ASSERT_TRUE(build_point_hierarchy(one, config, &p, nullptr, &error)) << error;
    expect_valid_hierarchy(one, p);

    auto fails_with = [&](RawScene bad, const char* words) {
        PointHierarchy q;
        std::string e;
        EXPECT_FALSE(build_point_hierarchy(bad, config, &q, nullptr, &e)) << words;
        EXPECT_NE(e.find(words), std::string::npos) << e;
    };
    RawScene flat = one;
    flat.positions = {0, 0, 0, 1, 0, 0, 2, 0, 0};
    fails_with(flat, "non-degenerate");
    RawScene nan = one;
    nan.positions[4] = std::nanf("");
    fails_with(nan, "not finite");
    RawScene range = one;
    range.indices[2] = 9;
    fails_with(range, "out of range");
    fails_with(RawScene(), "no triangles");
}

}  // namespace
