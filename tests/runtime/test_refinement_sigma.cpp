// The refinement cull's stretch factor (runtime/refinement_sigma.h): sigma^2 is the largest
// squared singular value of a triangle's bind-to-posed map (checked against that map built
// explicitly), +inf where the bind triangle has no area or the pose is not finite, and the AVX2
// kernel (runtime/point_simd.h) gives the scalar code's bits on random and hostile triangles,
// listed in any order, over counts that are not a multiple of 4.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "runtime/point_simd.h"
#include "runtime/refinement_sigma.h"

namespace {

using stipple::PointSimd;

struct Soup {
    std::vector<float> bind, posed, gram;  // 3 floats per vertex; the bind Grams per triangle
    std::vector<uint32_t> indices;
};

void fill_gram(Soup* s) {
    s->gram.clear();
    for (size_t t = 0; t < s->indices.size() / 3; ++t) {
        const float* a = &s->bind[s->indices[t * 3] * 3];
        const float* b = &s->bind[s->indices[t * 3 + 1] * 3];
        const float* c = &s->bind[s->indices[t * 3 + 2] * 3];
        float e1[3], e2[3];
        for (int d = 0; d < 3; ++d) e1[d] = b[d] - a[d], e2[d] = c[d] - a[d];
        s->gram.push_back(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
        s->gram.push_back(e1[0] * e2[0] + e1[1] * e2[1] + e1[2] * e2[2]);
        s->gram.push_back(e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2]);
    }
}

// `count` triangles over 40 random vertices, posed by a random linear map and noise; every
// fifth triangle a hostile one: no bind area, posed corners at infinity or NaN, all corners
// posed to one point.
Soup soup(uint32_t count, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> coord(-2.0f, 2.0f);
    Soup s;
    float m[9];
    for (float& x : m) x = coord(rng);
    for (int v = 0; v < 40; ++v) {
        float p[3];
        for (float& x : p) x = coord(rng);
        s.bind.insert(s.bind.end(), p, p + 3);
        for (int r = 0; r < 3; ++r)
            s.posed.push_back(m[r * 3] * p[0] + m[r * 3 + 1] * p[1] + m[r * 3 + 2] * p[2] +
                              0.1f * coord(rng));
    }
    const float inf = std::numeric_limits<float>::infinity();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float bind_special[][3] = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    const float posed_special[][3] = {{0, 0, 0}, {inf, 0, 0}, {0, nan, 0}, {0, 0, 0}, {0, 0, 0}};
    for (int k = 0; k < 5; ++k) {
        s.bind.insert(s.bind.end(), bind_special[k], bind_special[k] + 3);
        s.posed.insert(s.posed.end(), posed_special[k], posed_special[k] + 3);
    }
    // collinear bind corners; a corner at infinity; a NaN; every corner posed to the origin
    const uint32_t hostile[][3] = {{40, 41, 42}, {43, 41, 44}, {42, 43, 44}, {40, 43, 44}};
    for (uint32_t t = 0; t < count; ++t) {
        if (t % 5 == 4) {
            const auto& h = hostile[(t / 5) % 4];
            s.indices.insert(s.indices.end(), h, h + 3);
        } else {
            for (int k = 0; k < 3; ++k) s.indices.push_back(rng() % 40);
        }
    }
    fill_gram(&s);
    return s;
}

std::vector<float> sigma(const Soup& s, const std::vector<uint32_t>& list, PointSimd simd) {
    std::vector<float> out(s.indices.size() / 3, -1.0f);
    stipple::point_simd_force(simd);
    stipple::refinement_sigma2_listed(list.data(), uint32_t(list.size()), s.indices.data(),
                                      s.posed.data(), s.gram.data(), out.data());
    stipple::point_simd_force(stipple::point_simd_detected());
    return out;
}

// The map's largest squared singular value built the long way: the bind triangle's edges in
// an orthonormal frame of its plane, the posed edges times that 2x2 basis' inverse (a 3x2
// Jacobian J), then the larger eigenvalue of J^T J.
double reference_sigma2(const Soup& s, uint32_t t) {
    auto edge = [&](const std::vector<float>& p, int k, double* e) {
        for (int d = 0; d < 3; ++d)
            e[d] = double(p[s.indices[t * 3 + k] * 3 + d]) - double(p[s.indices[t * 3] * 3 + d]);
    };
    double b1[3], b2[3], p1[3], p2[3];
    edge(s.bind, 1, b1), edge(s.bind, 2, b2), edge(s.posed, 1, p1), edge(s.posed, 2, p2);
    const double l1 = std::sqrt(b1[0] * b1[0] + b1[1] * b1[1] + b1[2] * b1[2]);
    double u[3], w[3];
    for (int d = 0; d < 3; ++d) u[d] = b1[d] / l1;
    const double b2u = b2[0] * u[0] + b2[1] * u[1] + b2[2] * u[2];
    for (int d = 0; d < 3; ++d) w[d] = b2[d] - b2u * u[d];
    const double lw = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    // bind edges in the (u, w / |w|) frame: columns (l1, 0) and (b2u, lw); its inverse
    const double i00 = 1.0 / l1, i01 = -b2u / (l1 * lw), i11 = 1.0 / lw;
    double j0[3], j1[3];  // J's columns
    for (int d = 0; d < 3; ++d) j0[d] = p1[d] * i00, j1[d] = p1[d] * i01 + p2[d] * i11;
    const double a = j0[0] * j0[0] + j0[1] * j0[1] + j0[2] * j0[2];
    const double b = j0[0] * j1[0] + j0[1] * j1[1] + j0[2] * j1[2];
    const double c = j1[0] * j1[0] + j1[1] * j1[1] + j1[2] * j1[2];
    return 0.5 * (a + c) + std::sqrt(0.25 * (a - c) * (a - c) + b * b);
}

TEST(RefinementSigma, IsTheLargestSquaredSingularValueOfTheMap) {
    const Soup s = soup(200, 3);
    std::vector<uint32_t> all(200);
    for (uint32_t t = 0; t < 200; ++t) all[t] = t;
    const std::vector<float> got = sigma(s, all, PointSimd::baseline);
    int checked = 0;
    for (uint32_t t = 0; t < 200; ++t) {
        if (t % 5 == 4) {  // collapsed to a point: 0; no bind area or not finite: +inf
            const float want = (t / 5) % 4 == 3 ? 0.0f : std::numeric_limits<float>::infinity();
            EXPECT_EQ(got[t], want) << "hostile triangle " << t;
            continue;
        }
        const float* g = &s.gram[t * 3];
        if (!(g[0] * g[2] - g[1] * g[1] > 1e-3f)) continue;  // nearly flat random triangles
        const double want = reference_sigma2(s, t);
        EXPECT_NEAR(got[t] / want, 1.0 + 1e-5, 1e-4) << "triangle " << t;
        // Above the map's (the 1 + 1e-5 covers the float Grams' rounding) where the bind
        // triangle is not a sliver, whose Gram rounding the condition number amplifies.
        const float trace = g[0] + g[2];
        if (g[0] * g[2] - g[1] * g[1] > 0.05f * trace * trace) {
            EXPECT_GE(double(got[t]), want) << "an upper bound, triangle " << t;
        }
        ++checked;
    }
    EXPECT_GT(checked, 100);
}

TEST(RefinementSigma, PureScaleGivesItsSquare) {
    Soup s;
    s.bind = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    s.posed = {0, 0, 0, 3, 0, 0, 0, 0.5f, 0};  // x stretched 3x, y squashed
    s.indices = {0, 1, 2};
    fill_gram(&s);
    const float got = sigma(s, {0}, PointSimd::baseline)[0];
    EXPECT_NEAR(got, 9.0 * (1.0 + 1e-5), 1e-5);
}

TEST(RefinementSigma, SimdKernelGivesTheScalarBits) {
    if (!stipple::has_avx2(stipple::point_simd_detected()))
        GTEST_SKIP() << "this CPU has no AVX2: only the scalar code runs";
    for (uint32_t count : {0u, 1u, 3u, 4u, 7u, 64u, 203u}) {
        const Soup s = soup(count, 11 + count);
        std::vector<uint32_t> list(count);
        for (uint32_t t = 0; t < count; ++t) list[t] = (t * 37 + 5) % count;  // scattered order
        std::sort(list.begin(), list.end());
        list.erase(std::unique(list.begin(), list.end()), list.end());
        std::reverse(list.begin(), list.end());
        const std::vector<float> scalar = sigma(s, list, PointSimd::baseline);
        const std::vector<float> simd = sigma(s, list, PointSimd::avx2);
        ASSERT_EQ(scalar.size(), simd.size());
        for (size_t t = 0; t < scalar.size(); ++t) {
            uint32_t a, b;
            std::memcpy(&a, &scalar[t], 4), std::memcpy(&b, &simd[t], 4);
            EXPECT_EQ(a, b) << "count " << count << ", triangle " << t << ": " << scalar[t]
                            << " against " << simd[t];
        }
    }
}

}  // namespace
