// Unit tests of the baked points' triangulation (runtime/point_triangulation.h), the domain the
// run-time refinement continues the hierarchy on.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>
#include <random>
#include <set>
#include <tuple>
#include <vector>

#include "runtime/point_triangulation.h"

namespace {

using stipple::PointTriangulation;

glm::vec3 at(const std::vector<float>& p, uint32_t i) {
    return glm::vec3(p[i * 3], p[i * 3 + 1], p[i * 3 + 2]);
}

// Evenly spread points on the unit sphere (Fibonacci lattice) with outward normals.
void sphere(uint32_t n, std::vector<float>* p, std::vector<float>* nrm) {
    for (uint32_t i = 0; i < n; ++i) {
        const float z = 1.0f - 2.0f * (float(i) + 0.5f) / float(n);
        const float r = std::sqrt(1.0f - z * z), phi = 2.39996323f * float(i);
        const glm::vec3 v(r * std::cos(phi), r * std::sin(phi), z);
        for (int d = 0; d < 3; ++d) p->push_back(v[d]), nrm->push_back(v[d]);
    }
}

TEST(PointTriangulation, ClosedSurfaceGetsAboutTwoTrianglesPerPoint) {
    const uint32_t n = 4000;
    std::vector<float> p, nrm;
    sphere(n, &p, &nrm);
    PointTriangulation t;
    ASSERT_TRUE(
        stipple::triangulate_points(n, p.data(), nrm.data(), 4.0 * 3.14159265, nullptr, nullptr, &t)
            .ok());
    // Euler: a closed triangulation of n points has 2n - 4 triangles; allow a few misses.
    std::printf("sphere: %u points, %u triangles\n", n, t.triangle_count);
    EXPECT_GT(t.triangle_count, uint32_t(0.97 * (2 * n - 4)));
    EXPECT_LE(t.triangle_count, 2 * n - 4 + n / 50);
    const float spacing = std::sqrt(4.0f * 3.14159265f / float(n));
    std::set<std::tuple<uint32_t, uint32_t, uint32_t>> seen;
    double area = 0.0;
    for (uint32_t k = 0; k < t.triangle_count; ++k) {
        const uint32_t* tri = &t.indices[size_t(k) * 3];
        const glm::vec3 a = at(p, tri[0]), b = at(p, tri[1]), c = at(p, tri[2]);
        // Small, counter-clockwise seen from outside, each once.
        ASSERT_LT(glm::length(b - a), 3.0f * spacing);
        ASSERT_LT(glm::length(c - a), 3.0f * spacing);
        const glm::vec3 normal = glm::cross(b - a, c - a);
        ASSERT_GT(glm::dot(normal, a + b + c), 0.0f) << k;
        area += 0.5 * glm::length(normal);
        uint32_t s[3] = {tri[0], tri[1], tri[2]};
        std::sort(s, s + 3);
        ASSERT_TRUE(seen.insert({s[0], s[1], s[2]}).second) << "triangle " << k << " twice";
    }
    // The chords cover the sphere: their area is the sphere's less the chord deficit.
    EXPECT_NEAR(area, 4.0 * 3.14159265, 0.02 * 4.0 * 3.14159265);
}

TEST(PointTriangulation, OpenSheetStopsAtItsBoundaryAndThinSheetsStayApart) {
    // Two parallel jittered grids 0.05 apart (a thin sheet seen from both sides): no triangle
    // may join them, and neither may span the open boundary.
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> jitter(-0.25f, 0.25f);
    std::vector<float> p, nrm;
    const int side = 40;
    for (int sheet = 0; sheet < 2; ++sheet)
        for (int y = 0; y < side; ++y)
            for (int x = 0; x < side; ++x) {
                p.insert(p.end(), {(float(x) + jitter(rng)) / side, (float(y) + jitter(rng)) / side,
                                   0.05f * float(sheet)});
                nrm.insert(nrm.end(), {0.0f, 0.0f, sheet ? 1.0f : -1.0f});
            }
    const uint32_t n = uint32_t(p.size() / 3);
    PointTriangulation t;
    ASSERT_TRUE(
        stipple::triangulate_points(n, p.data(), nrm.data(), 2.0, nullptr, nullptr, &t).ok());
    std::printf("two sheets: %u points, %u triangles\n", n, t.triangle_count);
    const uint32_t per_sheet = side * side;
    // A planar triangulation of m points with b on the hull has 2m - 2 - b triangles.
    EXPECT_GT(t.triangle_count, 2 * (2 * per_sheet - 2 - 4 * side) * 95 / 100);
    for (uint32_t k = 0; k < t.triangle_count; ++k) {
        const uint32_t* tri = &t.indices[size_t(k) * 3];
        const bool s0 = tri[0] >= per_sheet;
        ASSERT_EQ(tri[1] >= per_sheet, s0);
        ASSERT_EQ(tri[2] >= per_sheet, s0);
        ASSERT_LT(glm::length(at(p, tri[1]) - at(p, tri[0])), 3.5f / side);
    }
    PointTriangulation none;
    ASSERT_TRUE(
        stipple::triangulate_points(2, p.data(), nrm.data(), 1.0, nullptr, nullptr, &none).ok());
    EXPECT_EQ(none.triangle_count, 0u);
}

}  // namespace
