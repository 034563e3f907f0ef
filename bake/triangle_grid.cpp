#include "bake/triangle_grid.h"

#include <algorithm>
#include <cmath>

#include "bake/closest_on_triangle.h"

namespace stipple::bake {

namespace {

glm::ivec3 cell_of(const TriangleGrid& g, glm::vec3 p) {
    return glm::ivec3(glm::floor((p - g.origin) / g.cell));
}

bool inside(const TriangleGrid& g, glm::ivec3 c) {
    return c.x >= 0 && c.y >= 0 && c.z >= 0 && c.x < g.dims.x && c.y < g.dims.y && c.z < g.dims.z;
}

size_t cell_index(const TriangleGrid& g, glm::ivec3 c) {
    return (size_t(c.z) * size_t(g.dims.y) + size_t(c.y)) * size_t(g.dims.x) + size_t(c.x);
}

// Calls visit(cell index) for every cell the triangle's bounding box touches.
template <typename Visit>
void for_cells(const TriangleGrid& g, size_t t, Visit visit) {
    const glm::vec3* c = &g.corners[t * 3];
    const glm::ivec3 lo = glm::max(cell_of(g, glm::min(c[0], glm::min(c[1], c[2]))), 0);
    const glm::ivec3 hi = glm::min(cell_of(g, glm::max(c[0], glm::max(c[1], c[2]))), g.dims - 1);
    for (int z = lo.z; z <= hi.z; ++z)
        for (int y = lo.y; y <= hi.y; ++y)
            for (int x = lo.x; x <= hi.x; ++x) visit(cell_index(g, {x, y, z}));
}

}  // namespace

TriangleGrid build_triangle_grid(const float* positions, const std::vector<uint32_t>& tris) {
    TriangleGrid g;
    const size_t n = tris.size() / 3;
    g.corners.resize(n * 3);
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    double edge = 0.0;
    for (size_t i = 0; i < n * 3; ++i) {
        const float* v = positions + size_t(tris[i]) * 3;
        g.corners[i] = glm::vec3(v[0], v[1], v[2]);
        lo = glm::min(lo, g.corners[i]);
        hi = glm::max(hi, g.corners[i]);
        if (i % 3 == 1) edge += double(glm::length(g.corners[i] - g.corners[i - 1]));
    }
    if (n == 0) return g;
    g.origin = lo;
    g.cell = std::max(float(2.0 * edge / double(n)), 1e-6f);
    const glm::vec3 extent = hi - lo;
    for (;;) {  // at most 2^22 cells: coarser cells where the mesh is mostly empty space
        g.dims = glm::ivec3(glm::floor(extent / g.cell)) + 1;
        if (double(g.dims.x) * double(g.dims.y) * double(g.dims.z) <= double(1 << 22)) break;
        g.cell *= 1.25f;
    }
    g.cell_start.assign(cell_index(g, g.dims - 1) + 2, 0);
    for (size_t t = 0; t < n; ++t) for_cells(g, t, [&](size_t c) { ++g.cell_start[c + 1]; });
    for (size_t c = 1; c < g.cell_start.size(); ++c) g.cell_start[c] += g.cell_start[c - 1];
    g.items.resize(g.cell_start.back());
    std::vector<uint32_t> fill(g.cell_start.begin(), g.cell_start.end() - 1);
    for (size_t t = 0; t < n; ++t)
        for_cells(g, t, [&](size_t c) { g.items[fill[c]++] = uint32_t(t); });
    return g;
}

float one_sided_gap(const TriangleGrid& g, glm::vec3 p, float side) {
    if (g.items.empty()) return 0.0f;
    const glm::ivec3 c = cell_of(g, p);
    // Every triangle not yet visited after ring r touches no cell within r of p's cell, so it
    // is at least r cells plus p's distance to its own cell's faces away.
    const glm::vec3 in_cell = (p - g.origin) / g.cell - glm::vec3(c);
    const float margin = std::max(0.0f, std::min({in_cell.x, in_cell.y, in_cell.z, 1 - in_cell.x,
                                                  1 - in_cell.y, 1 - in_cell.z}) *
                                            g.cell);
    float best = INFINITY, gap = 0.0f;
    for (int ring = 0; ring <= 6; ++ring) {
        for (int z = -ring; z <= ring; ++z)
            for (int y = -ring; y <= ring; ++y)
                for (int x = -ring; x <= ring; ++x) {
                    if (std::max(std::abs(x), std::max(std::abs(y), std::abs(z))) != ring)
                        continue;  // the shell of this ring only
                    const glm::ivec3 at = c + glm::ivec3(x, y, z);
                    if (!inside(g, at)) continue;
                    const size_t k = cell_index(g, at);
                    for (uint32_t j = g.cell_start[k]; j < g.cell_start[k + 1]; ++j) {
                        const glm::vec3* t = &g.corners[size_t(g.items[j]) * 3];
                        const glm::vec3 q = closest_on_triangle(
                            p, t[0], t[1], t[2],
                            [](glm::vec3 u, glm::vec3 v) { return glm::dot(u, v); });
                        const float dist = glm::length(p - q);
                        if (dist >= best) continue;
                        best = dist;
                        const glm::vec3 n = glm::cross(t[1] - t[0], t[2] - t[0]);
                        gap = side * glm::dot(p - q, n) > 0.0f ? dist : 0.0f;
                    }
                }
        if (best <= float(ring) * g.cell + margin) break;  // nothing nearer beyond
    }
    return std::isfinite(best) ? gap : 0.0f;
}

}  // namespace stipple::bake
