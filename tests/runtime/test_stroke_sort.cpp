// Unit tests of runtime/stroke_sort.h: back-to-front order of paintstroke segments (stable
// radix sort on depth) and the gathering of their triangles in that order.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include "runtime/stroke_sort.h"

namespace {

stipple::StrokeMesh mesh_of(std::vector<stipple::StrokeSegment>& s) {
    stipple::StrokeMesh m;
    m.segments = s.data();
    m.segment_capacity = m.segment_count = uint32_t(s.size());
    return m;
}

std::vector<uint32_t> sorted(std::vector<stipple::StrokeSegment>& s) {
    stipple::StrokeMesh m = mesh_of(s);
    std::vector<uint32_t> order(s.size() + 1, 0xffffffffu), scratch(2 * s.size());
    stipple::sort_segments_back_to_front(m, order.data(), scratch.data());
    EXPECT_EQ(order.back(), 0xffffffffu);  // nothing past segment_count
    order.pop_back();
    return order;
}

TEST(StrokeSort, BackToFrontAndStable) {
    std::mt19937 rng(7);
    for (int n : {0, 1, 2, 17, 1000, 5000}) {
        std::vector<stipple::StrokeSegment> s(n);
        for (int k = 0; k < n; ++k) {
            // Few distinct depths (many ties), spanning several exponents, zero included.
            const int level = int(rng() % 40);
            s[k] = stipple::StrokeSegment{uint32_t(k), 3, level == 0 ? 0.0f : 0.01f * level * level,
                                          uint32_t(k)};
        }
        const std::vector<uint32_t> order = sorted(s);
        std::vector<uint32_t> expect(n);
        for (int k = 0; k < n; ++k) expect[k] = uint32_t(k);
        std::stable_sort(expect.begin(), expect.end(),
                         [&](uint32_t a, uint32_t b) { return s[a].depth > s[b].depth; });
        EXPECT_EQ(order, expect);
        for (int k = 1; k < n; ++k) {
            const auto& a = s[order[k - 1]];
            const auto& b = s[order[k]];
            ASSERT_GE(a.depth, b.depth);
            if (a.depth == b.depth) {
                ASSERT_LT(order[k - 1], order[k]);  // stable
            }
        }
    }
}

TEST(StrokeSort, OrdersAnyFloatDepth) {
    std::vector<stipple::StrokeSegment> s;
    const float depths[] = {1.0f, -2.0f, 1e-30f, 3e20f, 0.0f, -0.5f, 1.0f, 7.25f, -1e10f};
    for (float d : depths) s.push_back({0, 0, d, 0});
    const std::vector<uint32_t> order = sorted(s);
    const std::vector<uint32_t> expect = {3, 7, 0, 6, 2, 4, 5, 1, 8};
    EXPECT_EQ(order, expect);
}

TEST(StrokeSort, GathersTrianglesInOrder) {
    std::vector<uint32_t> indices = {0, 1, 2, 10, 11, 12, 13, 14, 15, 20, 21, 22};
    std::vector<stipple::StrokeSegment> s = {{0, 3, 1.0f, 0}, {3, 6, 5.0f, 1}, {9, 3, 2.0f, 2}};
    stipple::StrokeMesh m = mesh_of(s);
    m.indices = indices.data();
    m.index_count = m.index_capacity = uint32_t(indices.size());
    std::vector<uint32_t> order(3), scratch(6), out(indices.size() + 1, 99);
    stipple::sort_segments_back_to_front(m, order.data(), scratch.data());
    stipple::gather_sorted_indices(m, order.data(), out.data());
    const std::vector<uint32_t> expect = {10, 11, 12, 13, 14, 15, 20, 21, 22, 0, 1, 2, 99};
    EXPECT_EQ(out, expect);
}

}  // namespace
