// The point hierarchies of progressive sample elimination (eliminate, the default), thesis
// ch. 4 (simplify) and ch. 5 (relax), and the naive baseline (random): every point on the
// input surface with valid barycentrics and in-range neighbours, radii coarse to fine, the
// same bytes for the same seed, randomization that folds nothing and makes no slivers, no crash on
// malformed meshes; the default's prefixes evenly spread on the surface of low-poly
// meshes of long thin triangles (a cylinder of ring slivers, a fan, a 2-triangle plane), and
// as dense along the boundary of an open surface as inside it (and along a crack).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <glm/glm.hpp>
#include <sstream>

#include "bake/asset_writer.h"
#include "bake/point_grid.h"
#include "bake/point_hierarchy.h"
#include "bake/scene_import.h"
#include "tests/common/bake_result.h"
#include "tests/common/fixtures.h"

namespace {

using namespace stipple::bake;
using stipple::test::source;

RawScene tube() {
    RawScene s;
    std::string error;
    EXPECT_TRUE(stipple::test::bake_ok(
        import_scene(source("assets/stretch_tube/stretch_tube.gltf"), &s), &error))
        << error;
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
    switch (m) {
        case HierarchyMethod::simplify:
            return "simplify";
        case HierarchyMethod::relax:
            return "relax";
        case HierarchyMethod::random:
            return "random";
        case HierarchyMethod::eliminate:
            return "eliminate";
    }
    return "?";
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
        // On the surface: the nearest input triangle (brute force, from the host on) is within
        // 1e-5 of the bounding-box diagonal.
        double nearest = distance_to_triangle(s, t, x);
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
    ASSERT_TRUE(stipple::test::bake_ok(build_point_hierarchy(s, config, &p, nullptr), &error))
        << error;
    ASSERT_EQ(p.size(), 3000u);
    expect_valid_hierarchy(s, p);
}

INSTANTIATE_TEST_SUITE_P(AllMethods, PointHierarchyMethods,
                         ::testing::Values(HierarchyMethod::eliminate, HierarchyMethod::simplify,
                                           HierarchyMethod::relax, HierarchyMethod::random),
                         [](const ::testing::TestParamInfo<HierarchyMethod>& param) {
                             return std::string(method_name(param.param));
                         });

// Thesis §4.4: randomize and project keeps every point on the input surface at the
// largest jitter too (input vertices and subdivision vertices are projected back), folds
// nothing, and the sliver guard keeps the tube's faces as fat as plain bisection does.
TEST(PointHierarchy, RandomizeAndProjectStaysOnTheSurfaceWithoutSlivers) {
    RawScene s = tube();
    HierarchyConfig config;
    config.method = HierarchyMethod::simplify;
    config.point_count = 3000;
    config.jitter = 0.75f;
    PointHierarchy p;
    HierarchyStats stats;
    std::string error;
    ASSERT_TRUE(stipple::test::bake_ok(build_point_hierarchy(s, config, &p, &stats), &error))
        << error;
    expect_valid_hierarchy(s, p);
    EXPECT_EQ(stats.slivers_after_subdivision, stats.slivers_before_subdivision);
    config.jitter = 0;
    PointHierarchy plain;
    ASSERT_TRUE(stipple::test::bake_ok(build_point_hierarchy(s, config, &plain, nullptr), &error))
        << error;
    EXPECT_NE(p.bary_u, plain.bary_u);  // the jitter moved the points
}

TEST_P(PointHierarchyMethods, SameSeedSameBytesOtherSeedOtherPoints) {
    RawScene s = tube();
    HierarchyConfig config;
    config.method = GetParam();
    config.point_count = 2000;
    PointHierarchy a, b, c;
    std::string error;
    ASSERT_TRUE(stipple::test::bake_ok(build_point_hierarchy(s, config, &a, nullptr), &error));
    ASSERT_TRUE(stipple::test::bake_ok(build_point_hierarchy(s, config, &b, nullptr), &error));
    config.seed = 2;
    ASSERT_TRUE(stipple::test::bake_ok(build_point_hierarchy(s, config, &c, nullptr), &error));
    EXPECT_EQ(encode_asset(s, a), encode_asset(s, b));
    EXPECT_NE(encode_asset(s, a), encode_asset(s, c));
}

// Low-poly game meshes: what simplify + subdivide lines up (rings on a cylinder of long
// thin quads, circles on a fan of slivers, nothing near the border of a 2-triangle plane).

// A closed cylinder (radius 1, height 10) of `around` x `rows` quads, each split in two long
// thin triangles (aspect ~10: the rings of RiggedSimple), capped by fans of slivers.
RawScene sliver_cylinder(int around = 24, int rows = 4) {
    RawScene s;
    for (int r = 0; r <= rows; ++r)
        for (int a = 0; a < around; ++a) {
            const double t = 2 * M_PI * a / around;
            s.positions.insert(s.positions.end(),
                               {float(std::cos(t)), float(10.0 * r / rows), float(std::sin(t))});
        }
    const uint32_t bottom = uint32_t(s.positions.size() / 3), top = bottom + 1;
    s.positions.insert(s.positions.end(), {0, 0, 0, 0, 10, 0});
    auto at = [&](int r, int a) { return uint32_t(r * around + (a % around)); };
    for (int r = 0; r < rows; ++r)
        for (int a = 0; a < around; ++a)
            s.indices.insert(s.indices.end(), {at(r, a), at(r + 1, a), at(r, a + 1), at(r, a + 1),
                                               at(r + 1, a), at(r + 1, a + 1)});
    for (int a = 0; a < around; ++a) {
        s.indices.insert(s.indices.end(), {bottom, at(0, a), at(0, a + 1)});
        s.indices.insert(s.indices.end(), {top, at(rows, a + 1), at(rows, a)});
    }
    s.normals.assign(s.positions.size(), 0.0f);
    return s;
}

// A flat disc of radius 1: one fan of `around` slivers (about 5.6 degrees at the centre).
RawScene sliver_fan(int around = 64) {
    RawScene s;
    s.positions = {0, 0, 0};
    for (int a = 0; a < around; ++a) {
        const double t = 2 * M_PI * a / around;
        s.positions.insert(s.positions.end(), {float(std::cos(t)), float(std::sin(t)), 0});
    }
    for (int a = 0; a < around; ++a)
        s.indices.insert(s.indices.end(), {0, uint32_t(1 + a), uint32_t(1 + (a + 1) % around)});
    s.normals.assign(s.positions.size(), 0.0f);
    return s;
}

// A 4 x 1 rectangle of two triangles.
RawScene two_triangle_plane() {
    RawScene s;
    s.positions = {0, 0, 0, 4, 0, 0, 4, 1, 0, 0, 1, 0};
    s.indices = {0, 1, 2, 0, 2, 3};
    s.normals.assign(s.positions.size(), 0.0f);
    return s;
}

std::vector<double> point_positions(const RawScene& s, const PointHierarchy& p) {
    std::vector<double> xyz;
    for (uint32_t i = 0; i < p.size(); ++i) {
        const uint32_t t = p.host_triangle[i];
        const glm::dvec3 x = corner(s, t, 0) * double(p.bary_u[i]) +
                             corner(s, t, 1) * double(p.bary_v[i]) +
                             corner(s, t, 2) * (1.0 - p.bary_u[i] - p.bary_v[i]);
        xyz.insert(xyz.end(), {x.x, x.y, x.z});
    }
    return xyz;
}

// Nearest-neighbour distances in 3D among the first n points: their coefficient of
// variation and the share of points nearer than half the median ("clumps").
struct PrefixSpread {
    double cv = 0, clumps = 0;
};

PrefixSpread prefix_spread(const std::vector<double>& xyz, uint32_t n, double area) {
    stipple::bake::PointGrid grid;
    const double spacing = std::sqrt(area / n);
    grid.build(xyz.data(), n, spacing);
    std::vector<double> d(n);
    for (uint32_t i = 0; i < n; ++i) {
        double best = 1e300;
        for (int ring = 1; ring <= 64 && !(std::sqrt(best) <= ring * spacing); ring *= 2)
            grid.visit(&xyz[size_t(i) * 3], ring, [&](uint32_t j) {
                if (j == i) return;
                double s2 = 0;
                for (size_t k = 0; k < 3; ++k) {
                    const double e = xyz[size_t(j) * 3 + k] - xyz[size_t(i) * 3 + k];
                    s2 += e * e;
                }
                best = std::min(best, s2);
            });
        d[i] = std::sqrt(best);
    }
    double sum = 0, sum2 = 0;
    for (double x : d) {
        sum += x;
        sum2 += x * x;
    }
    std::vector<double> sorted = d;
    std::nth_element(sorted.begin(), sorted.begin() + n / 2, sorted.end());
    const double median = sorted[n / 2], mean = sum / n;
    PrefixSpread out;
    out.cv = std::sqrt(std::max(sum2 / n - mean * mean, 0.0)) / mean;
    for (double x : d) out.clumps += x < 0.5 * median;
    out.clumps /= n;
    return out;
}

double area_of(const RawScene& s) {
    double a = 0;
    for (uint32_t t = 0; t < s.triangle_count(); ++t)
        a += 0.5 * glm::length(glm::cross(corner(s, t, 1) - corner(s, t, 0),
                                          corner(s, t, 2) - corner(s, t, 0)));
    return a;
}

// Every prefix the runtime may draw (it draws prefixes: thesis §3.1.1) is evenly spread on
// the surface however the mesh is triangulated: nearest-neighbour CV <= 0.2 and < 1 %
// clumps, measured in 3D on the baked points of the default method (0.09-0.14 and none,
// measured). For comparison, simplify: CV 0.37-0.85 and up to 12 % clumps on the cylinder,
// 0.47-0.67 and up to 19 % on the fan; relax: 0.10-0.27 (mid-level prefixes).
TEST(PointHierarchy, DefaultPrefixesAreEvenOnSliverMeshes) {
    struct Case {
        const char* name;
        RawScene scene;
    };
    const Case cases[] = {
        {"cylinder", sliver_cylinder()}, {"fan", sliver_fan()}, {"plane", two_triangle_plane()}};
    for (const Case& c : cases) {
        HierarchyConfig config;  // the default method
        config.point_count = 4000;
        PointHierarchy p;
        std::string error;
        ASSERT_TRUE(
            stipple::test::bake_ok(build_point_hierarchy(c.scene, config, &p, nullptr), &error))
            << error;
        expect_valid_hierarchy(c.scene, p);
        const std::vector<double> xyz = point_positions(c.scene, p);
        const double area = area_of(c.scene);
        for (uint32_t n : {60u, 150u, 333u, 700u, 1000u, 1500u, 2345u, 4000u}) {
            const PrefixSpread s = prefix_spread(xyz, n, area);
            EXPECT_LE(s.cv, 0.2) << c.name << " prefix " << n;
            EXPECT_LT(s.clumps, 0.01) << c.name << " prefix " << n;
        }
    }
}

// No part of a 2-triangle plane is left out by any prefix: of cells twice the even spacing
// (about n / 16 of them over the 4 x 1 plane), none is empty.
TEST(PointHierarchy, DefaultPrefixesCoverATwoTrianglePlane) {
    const RawScene s = two_triangle_plane();
    HierarchyConfig config;
    config.point_count = 4000;
    PointHierarchy p;
    std::string error;
    ASSERT_TRUE(stipple::test::bake_ok(build_point_hierarchy(s, config, &p, nullptr), &error))
        << error;
    const std::vector<double> xyz = point_positions(s, p);
    for (uint32_t n : {64u, 256u, 1000u, 4000u}) {
        const double cell = 2 * std::sqrt(4.0 / n);
        const int nx = int(4 / cell), ny = int(1 / cell);  // whole cells only
        std::vector<int> count(size_t(nx * ny), 0);
        for (uint32_t i = 0; i < n; ++i) {
            const int x = int(xyz[size_t(i) * 3] / cell), y = int(xyz[size_t(i) * 3 + 1] / cell);
            if (x < nx && y < ny) ++count[size_t(y * nx + x)];
        }
        EXPECT_EQ(std::count(count.begin(), count.end(), 0), 0) << "prefix " << n;
    }
}

// A unit square of k x k quads (two triangles each) in the z = 0 plane; with `crack`, the
// right half's vertices are moved right by `crack`, so the middle column is two boundaries
// facing each other (not welded) while the surface goes on across them.
RawScene open_square(int k, float crack = 0) {
    RawScene s;
    for (int half = 0; half < (crack > 0 ? 2 : 1); ++half) {
        const uint32_t base = uint32_t(s.positions.size() / 3);
        const int x0 = crack > 0 ? half * k / 2 : 0, x1 = crack > 0 ? x0 + k / 2 : k;
        const int w = x1 - x0 + 1;
        for (int y = 0; y <= k; ++y)
            for (int x = x0; x <= x1; ++x)
                s.positions.insert(s.positions.end(), {float(x) / float(k) + (half ? crack : 0.0f),
                                                       float(y) / float(k), 0.0f});
        for (int y = 0; y < k; ++y)
            for (int x = 0; x < w - 1; ++x) {
                const uint32_t a = base + uint32_t(y * w + x), b = a + 1, c = a + uint32_t(w),
                               d = c + 1;
                s.indices.insert(s.indices.end(), {a, b, d, a, d, c});
            }
    }
    s.normals.assign(s.positions.size(), 0.0f);
    return s;
}

// Point density within half a spacing sqrt(area / n) of the square's border (with
// `middle`: of its middle line x = 0.5, farther than two spacings from the border), over the
// density farther than two spacings from both, for the prefix of n of `points` points,
// pooled over seeds 1-4.
double band_density_ratio(const RawScene& s, uint32_t points, uint32_t n, bool middle) {
    const double spacing = std::sqrt(1.0 / n);
    auto classify = [&](double x, double y) {  // 1: band, 2: interior, 0: neither
        const double border = std::min({x, y, 1 - x, 1 - y}), mid = std::fabs(x - 0.5);
        if (middle ? mid < 0.5 * spacing && border >= 2 * spacing : border < 0.5 * spacing)
            return 1;
        return border >= 2 * spacing && (!middle || mid >= 2 * spacing) ? 2 : 0;
    };
    double count[3] = {0, 0, 0}, area[3] = {0, 0, 0};
    const int kGrid = 500;  // areas on a fine grid
    for (int i = 0; i < kGrid; ++i)
        for (int j = 0; j < kGrid; ++j) area[classify((i + 0.5) / kGrid, (j + 0.5) / kGrid)] += 1;
    for (uint64_t seed = 1; seed <= 4; ++seed) {
        HierarchyConfig config;  // the default method
        config.point_count = points;
        config.seed = seed;
        PointHierarchy p;
        std::string error;
        EXPECT_TRUE(stipple::test::bake_ok(build_point_hierarchy(s, config, &p, nullptr), &error))
            << error;
        const std::vector<double> xyz = point_positions(s, p);
        for (uint32_t i = 0; i < n && i < p.size(); ++i)
            count[classify(std::min(xyz[size_t(i) * 3], 1.0), xyz[size_t(i) * 3 + 1])] += 1;
    }
    return (count[1] / area[1]) / (count[2] / area[2]);
}

// Open surfaces: no prefix of the default method is denser along the boundary. Sample
// elimination as such keeps the samples near a boundary (fewer neighbours, lower weights):
// 1.5-1.7x the interior density within half a spacing of the square's border at every
// prefix; the surface continued across the boundary by ghost samples makes it 0.95-1.05.
TEST(PointHierarchy, DefaultPrefixesAreNotDenserAlongABoundary) {
    const RawScene s = open_square(8);
    for (uint32_t n : {250u, 1000u, 4000u}) {
        const double ratio = band_density_ratio(s, 4000, n, false);
        std::printf("prefix %u: density within half a spacing of the border / interior %.3f\n", n,
                    ratio);
        EXPECT_NEAR(ratio, 1.0, 0.15) << "prefix " << n;
    }
    // The ghosts have their own random numbers, from the seed: still the same bytes.
    HierarchyConfig config;
    config.point_count = 2000;
    PointHierarchy a, b;
    std::string error;
    ASSERT_TRUE(stipple::test::bake_ok(build_point_hierarchy(s, config, &a, nullptr), &error))
        << error;
    ASSERT_TRUE(stipple::test::bake_ok(build_point_hierarchy(s, config, &b, nullptr), &error))
        << error;
    EXPECT_EQ(encode_asset(s, a), encode_asset(s, b));
    expect_valid_hierarchy(s, a);
}

// Where the surface goes on across a boundary (a crack: two halves of a square, not
// welded, 1e-5 apart), it is not continued by ghosts, which would lie on the other half and
// thin out the points along the crack.
TEST(PointHierarchy, DefaultPrefixesAreEvenAcrossACrack) {
    const RawScene s = open_square(8, 1e-5f);
    for (uint32_t n : {250u, 1000u, 4000u}) {
        const double ratio = band_density_ratio(s, 4000, n, true);
        std::printf("prefix %u: density near the border or the crack / interior %.3f\n", n, ratio);
        EXPECT_NEAR(ratio, 1.0, 0.15) << "prefix " << n;
    }
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
    ASSERT_TRUE(stipple::test::bake_ok(build_point_hierarchy(s, config, &p, &stats), &error))
        << error;
    EXPECT_EQ(p.size(), 500u);
    EXPECT_GE(stats.skipped_faces, 1u);
    expect_valid_hierarchy(s, p);
    for (uint32_t i = 0; i < p.size(); ++i) EXPECT_NE(p.host_triangle[i], 3u);  // degenerate

    RawScene one;  // a single open triangle: three boundary edges
    one.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    one.normals.assign(9, 0.0f);
    one.indices = {0, 1, 2};
    ASSERT_TRUE(stipple::test::bake_ok(build_point_hierarchy(one, config, &p, nullptr), &error))
        << error;
    expect_valid_hierarchy(one, p);

    auto fails_with = [&](RawScene bad, const char* words) {
        PointHierarchy q;
        std::string e;
        EXPECT_FALSE(stipple::test::bake_ok(build_point_hierarchy(bad, config, &q, nullptr), &e))
            << words;
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
