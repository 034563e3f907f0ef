// Unit tests of runtime/refinement_order.h: the order in which triangles' first extra points
// are handed out.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "runtime/refinement_order.h"

namespace {

using namespace stipple;

TEST(RefinementOrder, FirstPointsFillTheLargestHolesFirst) {
    // 100 triangles' first points on a line x = 0..99; baked points at x = 0..49. The order
    // starts in the empty half and every phase is distinct in (0, 1].
    const uint32_t n = 100;
    std::vector<float> first(n * 3, 0.0f), area(n, 1.0f), baked(50 * 3, 0.0f), phase(n);
    for (uint32_t t = 0; t < n; ++t) first[t * 3] = float(t);
    for (uint32_t i = 0; i < 50; ++i) baked[i * 3] = float(i);
    area[7] = 0.0f;  // degenerate: last
    ASSERT_TRUE(first_point_phases(n, first.data(), area.data(), 50, baked.data(), phase.data()));
    std::vector<float> sorted = phase;
    std::sort(sorted.begin(), sorted.end());
    for (uint32_t i = 0; i < n; ++i) EXPECT_FLOAT_EQ(sorted[i], (float(i) + 0.5f) / float(n));
    EXPECT_FLOAT_EQ(phase[7], (float(n - 1) + 0.5f) / float(n));
    const uint32_t first_ranked =
        uint32_t(std::min_element(phase.begin(), phase.end()) - phase.begin());
    EXPECT_GE(first_ranked, 52u);
    // The first ten ranked are spread over the empty half, not bunched.
    std::vector<float> xs;
    for (uint32_t t = 0; t < n; ++t)
        if (phase[t] < 10.0f / float(n)) xs.push_back(float(t));
    std::sort(xs.begin(), xs.end());
    ASSERT_EQ(xs.size(), 10u);
    for (size_t i = 1; i < xs.size(); ++i) EXPECT_GE(xs[i] - xs[i - 1], 3.0f);
}

}  // namespace
