// runtime/region_density.h: regions of influence that follow each coarse prefix's surface
// density (issue 7, tone 0.1 on small objects; docs/tone.md, "Small objects").
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "runtime/region_density.h"

namespace {

using stipple::density_corrected_radii;
using stipple::RegionDensityParams;

constexpr double kPi = 3.14159265358979;

// Area-uniform samples of a sphere (radius 0.28, area 0.985: closed, as the corpus's meshes
// are; an open sheet's rim would read as sparse) and, optionally, of four thin tubes beside it
// (radius 0.01, length 1, 0.25 apart: 20% of the area, thinner than the spacing of the
// first ~300 points, like a horse's legs); then ordered
// coarse to fine as sample elimination orders them, evenly in 3-D distance at every prefix
// (greedy farthest-point insertion). `on_tube` flags the tubes' points.
struct Surface {
    std::vector<float> positions;
    std::vector<uint8_t> on_tube;
    double area = 0;
};

Surface make_surface(uint32_t count, bool tube) {
    const double tube_radius = 0.01, tube_area = tube ? 4 * 2 * kPi * tube_radius : 0.0;
    Surface s;
    const double sphere_radius = 0.28, sphere_area = 4 * kPi * sphere_radius * sphere_radius;
    s.area = sphere_area + tube_area;
    std::normal_distribution<double> g(0.0, 1.0);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<float> p(size_t(count) * 3);
    std::vector<uint8_t> t(count);
    for (uint32_t i = 0; i < count; ++i) {
        if (u(rng) * s.area < tube_area) {
            const double a = 2 * kPi * u(rng);
            p[i * 3] = float(u(rng));
            p[i * 3 + 1] = float(1.25 + 0.25 * int(4 * u(rng)) + tube_radius * std::cos(a));
            p[i * 3 + 2] = float(tube_radius * std::sin(a));
            t[i] = 1;
        } else {
            double d[3] = {g(rng), g(rng), g(rng)};
            const double l = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            for (int c = 0; c < 3; ++c) p[i * 3 + c] = float(0.5 + sphere_radius * d[c] / l);
        }
    }
    // Greedy farthest-point order.
    std::vector<float> nearest(count, 1e30f);
    for (uint32_t i = 0; i < count; ++i) {
        uint32_t best = i;
        for (uint32_t j = i; j < count && i > 0; ++j)
            if (nearest[j] > nearest[best]) best = j;
        for (int c = 0; c < 3; ++c) std::swap(p[i * 3 + c], p[best * 3 + c]);
        std::swap(t[i], t[best]);
        std::swap(nearest[i], nearest[best]);
        for (uint32_t j = i + 1; j < count; ++j) {
            float d = 0;
            for (int c = 0; c < 3; ++c)
                d += (p[j * 3 + c] - p[i * 3 + c]) * (p[j * 3 + c] - p[i * 3 + c]);
            nearest[j] = std::min(nearest[j], d);
        }
    }
    s.positions = p;
    s.on_tube = t;
    return s;
}

// The bake's rank law: the point of rank i has the region area / (i + 1).
std::vector<float> rank_radii(const Surface& s) {
    std::vector<float> r(s.on_tube.size());
    for (size_t i = 0; i < r.size(); ++i) r[i] = float(std::sqrt(s.area / double(i + 1)));
    return r;
}

// The brute-force reference (the first version, O(limit x count)): the grid must give the
// same radii bit for bit (the count inside a ball is a sum of 1 and 1/2, exact in any order).
float ref_distance_squared(const float* p, uint32_t a, uint32_t b) {
    const float dx = p[a * 3] - p[b * 3], dy = p[a * 3 + 1] - p[b * 3 + 1];
    const float dz = p[a * 3 + 2] - p[b * 3 + 2];
    return dx * dx + dy * dy + dz * dz;
}

void reference_radii(const float* p, uint32_t count, const RegionDensityParams& params,
                     float* radius) {
    const uint32_t m = params.neighbours, limit = std::min(params.limit, count);
    if (m == 0 || m > 32 || limit < 8 || count < 4 * limit) return;
    double bias = 0;
    for (uint32_t i = 1; i < limit; ++i) {
        const uint32_t k = std::min(i, m);
        std::vector<float> d(i);
        for (uint32_t j = 0; j < i; ++j) d[j] = ref_distance_squared(p, i, j);
        std::nth_element(d.begin(), d.begin() + (k - 1), d.end());
        const float r2 = d[k - 1];
        double inside = 0;
        for (uint32_t j = 0; j < count; ++j) {
            const float e = ref_distance_squared(p, i, j);
            inside += e < r2 ? 1.0 : (e == r2 ? 0.5 : 0.0);
        }
        double c = double(i + 1) * (inside / double(count)) / (k + 0.5);
        c = c > 1e-6 ? c : 1e-6;
        if (i >= limit / 2) bias += c;
        radius[i] *= float(std::sqrt(c));
    }
    const float unbias = float(std::sqrt(double(limit - limit / 2) / bias));
    for (uint32_t i = 1; i < limit; ++i) radius[i] *= unbias;
}

// Points Alg. 3.2 draws at a threshold region `tau` (constant over the surface: a flat view),
// on the tube and in all.
void drawn(const Surface& s, const std::vector<float>& r, double tau, double* tube, double* all) {
    *tube = *all = 0;
    for (size_t i = 0; i < r.size(); ++i)
        if (double(r[i]) * r[i] >= tau) *all += 1, *tube += s.on_tube[i];
}

// A 3-D even prefix puts one point per spacing along a tube thinner than the spacing: far
// more than its area share. With the corrected regions the points drawn at a coarse threshold
// follow the area: the tubes' share within 30% of their area share (rank law: 1.5-1.9x), and
// the count drawn within 10% of area / tau.
TEST(RegionDensity, ThinPartsGetTheirAreaShare) {
    const Surface s = make_surface(8000, true);
    const std::vector<float> before = rank_radii(s);
    std::vector<float> after = before;
    ASSERT_TRUE(density_corrected_radii(s.positions.data(), uint32_t(before.size()),
                                        RegionDensityParams(), after.data()));
    const double tube_share = 4 * 2 * kPi * 0.01 / s.area;  // 20%
    for (double count : {64.0, 128.0}) {
        const double tau = s.area / count;
        double tube_before, all_before, tube_after, all_after;
        drawn(s, before, tau, &tube_before, &all_before);
        drawn(s, after, tau, &tube_after, &all_after);
        std::printf(
            "threshold for %3.0f points: tube %.0f of %.0f (rank law), %.0f of %.0f "
            "(density); area share %.1f\n",
            count, tube_before, all_before, tube_after, all_after, tube_share * count);
        EXPECT_GT(tube_before, 1.4 * tube_share * count);  // the setup shows the bias
        EXPECT_NEAR(tube_after / all_after, tube_share, 0.3 * tube_share) << count;
        EXPECT_NEAR(all_after, count, 0.1 * count);
    }
}

// On an evenly spread surface the correction is noise around the rank law: the drawn count
// at every coarse threshold within 10% of area / tau (plus one point), and every rank from
// `limit` on keeps its radius.
TEST(RegionDensity, EvenSurfaceKeepsTheRankLaw) {
    const Surface s = make_surface(8000, false);
    const std::vector<float> before = rank_radii(s);
    std::vector<float> after = before;
    RegionDensityParams params;
    ASSERT_TRUE(
        density_corrected_radii(s.positions.data(), uint32_t(before.size()), params, after.data()));
    for (double count : {16.0, 64.0, 256.0, 900.0}) {
        double tube, all;
        drawn(s, after, s.area / count, &tube, &all);
        EXPECT_NEAR(all, count, 0.1 * count + 1.0);
    }
    for (size_t i = params.limit; i < before.size(); ++i) ASSERT_EQ(after[i], before[i]) << i;
    EXPECT_EQ(after[0], before[0]);
}

// Too few points for a density estimate: nothing changes.
TEST(RegionDensity, SmallSetsAreLeftAlone) {
    const Surface s = make_surface(2000, false);
    const std::vector<float> before = rank_radii(s);
    std::vector<float> after = before;
    ASSERT_TRUE(density_corrected_radii(s.positions.data(), uint32_t(before.size()),
                                        RegionDensityParams(), after.data()));
    EXPECT_EQ(after, before);
}

// The grid gives the brute force's radii bit for bit: thin tubes beside a sphere, a sphere
// alone, and a flat square (no extent along one axis), at several neighbour counts.
TEST(RegionDensity, GridEqualsBruteForce) {
    Surface flat;
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int i = 0; i < 6000; ++i)
        flat.positions.insert(flat.positions.end(), {u(rng), 0.5f, u(rng)});
    flat.on_tube.assign(6000, 0);
    flat.area = 1;
    const Surface meshes[] = {make_surface(9000, true), make_surface(8000, false), flat};
    for (const Surface& s : meshes) {
        for (uint32_t m : {1u, 2u, 4u}) {
            RegionDensityParams params;
            params.neighbours = m;
            std::vector<float> fast = rank_radii(s), slow = fast;
            const uint32_t n = uint32_t(fast.size());
            ASSERT_TRUE(density_corrected_radii(s.positions.data(), n, params, fast.data()));
            reference_radii(s.positions.data(), n, params, slow.data());
            ASSERT_EQ(fast, slow) << "m " << m << " count " << n;
            EXPECT_NE(fast, rank_radii(s));
        }
    }
}

// Bad input leaves the radii as they are: a NaN or infinite coordinate, all points at one place.
TEST(RegionDensity, BadInputIsLeftAlone) {
    Surface s = make_surface(6000, false);
    const std::vector<float> before = rank_radii(s);
    for (float bad :
         {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
        std::vector<float> p = s.positions, after = before;
        p[3000 * 3 + 1] = bad;
        ASSERT_TRUE(density_corrected_radii(p.data(), uint32_t(before.size()),
                                            RegionDensityParams(), after.data()));
        EXPECT_EQ(after, before);
    }
    std::vector<float> same(s.positions.size(), 0.25f), after = before;
    ASSERT_TRUE(density_corrected_radii(same.data(), uint32_t(before.size()), RegionDensityParams(),
                                        after.data()));
    EXPECT_EQ(after, before);
}

}  // namespace
