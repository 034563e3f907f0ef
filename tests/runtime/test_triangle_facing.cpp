// Triangle facing (runtime/silhouette.h): the AVX2 kernel (runtime/point_simd.h) gives the
// scalar code's flags, front / back / edge-on, on random triangles and on hostile ones (zero
// edges, collinear corners, corners at infinity, NaN, faces seen exactly edge-on), over a
// count that is not a multiple of 8, and an unpadded caller gets the scalar code only.
#include <gtest/gtest.h>

#include <limits>
#include <random>
#include <vector>

#include "runtime/point_simd.h"
#include "runtime/silhouette.h"

namespace {

using stipple::PointSimd;

struct Soup {
    std::vector<float> positions;
    std::vector<uint32_t> indices;
};

// `count` triangles over 40 vertices: random ones, then the hostile cases.
Soup soup(uint32_t count, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> coord(-2.0f, 2.0f);
    Soup s;
    for (int v = 0; v < 40; ++v)
        for (int d = 0; d < 3; ++d) s.positions.push_back(coord(rng));
    const float inf = std::numeric_limits<float>::infinity();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float special[][3] = {{0, 0, 0}, {1, 0, 0},   {2, 0, 0},
                                {0, 1, 0}, {inf, 0, 0}, {0, nan, 0}};
    for (const auto& p : special) s.positions.insert(s.positions.end(), p, p + 3);
    const uint32_t hostile[][3] = {{40, 40, 40}, {40, 41, 42}, {40, 41, 43}, {40, 43, 41},
                                   {40, 44, 43}, {40, 45, 41}, {41, 42, 43}};
    for (uint32_t t = 0; t < count; ++t) {
        if (t % 5 == 4) {
            const auto& h = hostile[(t / 5) % 7];
            s.indices.insert(s.indices.end(), h, h + 3);
        } else {
            for (int k = 0; k < 3; ++k) s.indices.push_back(rng() % 40);
        }
    }
    return s;
}

std::vector<uint8_t> facing(const Soup& s, const glm::vec3& eye, PointSimd simd, bool padded) {
    std::vector<float> positions = s.positions;
    positions.resize(positions.size() + stipple::kSimdPadFloats);  // the kernel's 16-byte loads
    std::vector<uint8_t> front(s.indices.size() / 3, 0xFF);
    stipple::point_simd_force(simd);
    stipple::triangle_facing(uint32_t(front.size()), s.indices.data(), positions.data(), eye,
                             front.data(), padded);
    stipple::point_simd_force(stipple::point_simd_detected());
    return front;
}

TEST(TriangleFacing, SimdKernelGivesTheScalarFlags) {
    if (!stipple::has_avx2(stipple::point_simd_detected()))
        GTEST_SKIP() << "this CPU has no AVX2 (or STIPPLE_SIMD=baseline): one path only";
    // Eyes off the plane z = 0 of the hostile triangles, in it (every one of them edge-on) and
    // at a corner.
    const glm::vec3 eyes[] = {
        {0.3f, 0.2f, 5.0f}, {0.3f, 0.2f, -5.0f}, {3.0f, 4.0f, 0.0f}, {0.0f, 0.0f, 0.0f}};
    for (uint32_t count : {203u, 8u, 7u}) {
        const Soup s = soup(count, count);
        for (const glm::vec3& eye : eyes) {
            const std::vector<uint8_t> scalar = facing(s, eye, PointSimd::baseline, true);
            const std::vector<uint8_t> simd = facing(s, eye, PointSimd::avx2, true);
            ASSERT_EQ(scalar, simd) << count << " triangles, eye " << eye.x << " " << eye.z;
            int kinds[3] = {};
            for (uint8_t f : scalar) {
                ASSERT_LE(f, stipple::kFacingEdgeOn);  // every flag written
                ++kinds[f];
            }
            if (count == 203) {
                EXPECT_GT(kinds[0] * kinds[1], 0) << "fronts and backs both";
            }
        }
    }
}

// Every flag is written, whatever the path, for a caller whose positions end at the last
// vertex (padded false: the scalar code reads exactly 3 floats per vertex).
TEST(TriangleFacing, UnpaddedCallersGetTheScalarCode) {
    const Soup s = soup(64, 3);
    const std::vector<uint8_t> a =
        facing(s, glm::vec3(0, 0, 5), stipple::point_simd_detected(), false);
    const std::vector<uint8_t> b = facing(s, glm::vec3(0, 0, 5), PointSimd::baseline, true);
    EXPECT_EQ(a, b);
}

}  // namespace
