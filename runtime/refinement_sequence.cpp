#include "runtime/refinement_sequence.h"

#include <algorithm>
#include <cmath>

namespace stipple {

namespace {

#include "runtime/refinement_pattern.inc"

// The six orders of a cell's corners.
constexpr uint8_t kCornerOrder[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1},
                                        {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};

}  // namespace

glm::mat2 isometric(const float* frame) {
    // p = u A + v B + w C with A = 0: p = v B + (1 - u - v) C, so dp = dv B - (du + dv) C.
    const glm::vec2 B(frame[0], 0.0f), C(frame[1], frame[2]);
    return glm::mat2(-C, B - C);  // columns: d/du, d/dv
}

Cell bisect(const Cell& cell, const glm::mat2& to_2d, int bit) {
    float longest = -1.0f;
    int e = 0;
    for (int i = 0; i < 3; ++i) {
        const glm::vec2 d = to_2d * (cell.c[(i + 1) % 3] - cell.c[i]);
        const float l = glm::dot(d, d);
        if (l > longest) longest = l, e = i;
    }
    const glm::vec2 a = cell.c[e], b = cell.c[(e + 1) % 3], opposite = cell.c[(e + 2) % 3];
    const glm::vec2 mid = 0.5f * (a + b);
    return bit ? Cell{{b, opposite, mid}} : Cell{{opposite, a, mid}};
}

Cell quarter(const Cell& cell, uint32_t digit) {
    const glm::vec2 ab = 0.5f * (cell.c[0] + cell.c[1]), bc = 0.5f * (cell.c[1] + cell.c[2]),
                    ca = 0.5f * (cell.c[2] + cell.c[0]);
    switch (digit) {
        case 1:
            return Cell{{cell.c[0], ab, ca}};
        case 2:
            return Cell{{ab, cell.c[1], bc}};
        case 3:
            return Cell{{ca, bc, cell.c[2]}};
        default:
            return Cell{{bc, ca, ab}};
    }
}

Cell root_cell(const glm::mat2& to_2d, uint32_t depth, uint32_t j) {
    Cell cell = kWholeTriangle;
    for (uint32_t level = 0; level < depth; ++level)
        cell = bisect(cell, to_2d, int((j >> level) & 1u));
    return cell;
}

uint32_t pattern_points() {
    return kPatternPoints;
}
uint32_t sub_cell_start() {
    return kPatternPoints / 4;
}
uint32_t variant_count() {
    return kPatterns * 6;
}

uint32_t triangle_variant(uint32_t t) {
    uint32_t h = t * 0x9E3779B1u + 0x7F4A7C15u;
    h ^= h >> 15;
    h *= 0x2C1B3C6Du;
    h ^= h >> 12;
    h *= 0x297A2D39u;
    h ^= h >> 15;
    return h % variant_count();
}

glm::vec2 pattern_point(const Cell& cell, uint32_t variant, uint32_t i) {
    const uint16_t* q = kPattern[variant / 6][i];
    const uint8_t* order = kCornerOrder[variant % 6];
    const float a = float(q[0]) * (1.0f / 65535.0f), b = float(q[1]) * (1.0f / 65535.0f);
    const glm::vec2 c0 = cell.c[order[0]], c1 = cell.c[order[1]], c2 = cell.c[order[2]];
    return c2 + a * (c0 - c2) + b * (c1 - c2);
}

uint32_t root_depth(float area, float longest2, float density) {
    if (!(area > 0.0f)) return 0;
    // Slivers: about (longest edge / height) root cells along their length.
    const float elongation = longest2 / (2.0f * area) / 1.5f;  // 0.77 for an equilateral
    int depth = elongation > 1.0f ? int(std::lround(std::log2(elongation))) : 0;
    // Large triangles: cells of about kRootCellPoints baked points' area, so the pattern
    // (kPatternPoints per cell) lasts up to 128x the bake's density before sub-cells.
    const float cells = area * density / kRootCellPoints;
    if (cells > 1.0f) depth = std::max(depth, int(std::ceil(std::log2(cells))));
    return uint32_t(std::min(depth, 16));
}

glm::vec2 refinement_barycentric(const float* frame, uint32_t depth, uint32_t variant, uint32_t k) {
    const uint32_t roots = 1u << depth;
    Cell cell = root_cell(isometric(frame), depth, k & (roots - 1));
    uint32_t local = k >> depth, start = 0;
    while (local >= kPatternPoints - start) {
        local -= kPatternPoints - start;
        cell = quarter(cell, local & 3u);
        local >>= 2;
        start = sub_cell_start();
    }
    return pattern_point(cell, variant, start + local);
}

}  // namespace stipple
