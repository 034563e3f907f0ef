#include "runtime/point_triangulation.h"

#include <algorithm>
#include <cmath>
#include <new>

#include "runtime/spatial_grid.h"

namespace stipple {

namespace {

constexpr int kMaxCandidates = 16;
constexpr int kMaxVertices = 4 + kMaxCandidates + 4;

// A convex polygon in the tangent plane; label[m] names the candidate whose bisector made the
// edge from v[m] to v[m + 1] (-1: the search box).
struct Cell {
    int n = 0;
    glm::vec2 v[kMaxVertices];
    int label[kMaxVertices];
};

// Clips `cell` by the half-plane closer to the origin than to q (the bisector of 0 and q).
void clip(Cell* cell, const glm::vec2& q, int candidate) {
    const float h = 0.5f * glm::dot(q, q);
    Cell out;
    for (int m = 0; m < cell->n && out.n < kMaxVertices - 2; ++m) {
        const glm::vec2 a = cell->v[m], b = cell->v[(m + 1) % cell->n];
        const float da = glm::dot(a, q) - h, db = glm::dot(b, q) - h;
        if (da <= 0.0f) {
            out.v[out.n] = a;
            out.label[out.n++] = cell->label[m];
            if (db > 0.0f) {  // leaves: the clip line starts here
                out.v[out.n] = a + (b - a) * (da / (da - db));
                out.label[out.n++] = candidate;
            }
        } else if (db <= 0.0f) {  // enters: the rest of the original edge
            out.v[out.n] = a + (b - a) * (da / (da - db));
            out.label[out.n++] = cell->label[m];
        }
    }
    *cell = out;
}

struct Candidate {
    float distance2;
    uint32_t index;
    glm::vec2 q;  // in the tangent plane
};

}  // namespace

double surface_area(const MeshView& m) {
    double area = 0.0;
    for (uint32_t t = 0; t < m.triangle_count; ++t) {
        const uint32_t* tri = m.indices + size_t(t) * 3;
        const glm::vec3 a(m.positions[tri[0] * 3], m.positions[tri[0] * 3 + 1], m.positions[tri[0] * 3 + 2]);
        const glm::vec3 b(m.positions[tri[1] * 3], m.positions[tri[1] * 3 + 1], m.positions[tri[1] * 3 + 2]);
        const glm::vec3 c(m.positions[tri[2] * 3], m.positions[tri[2] * 3 + 1], m.positions[tri[2] * 3 + 2]);
        const float twice = glm::length(glm::cross(b - a, c - a));
        if (std::isfinite(twice)) area += 0.5 * double(twice);
    }
    return area;
}

bool triangulate_points(uint32_t count, const float* positions, const float* normals,
                        double area, PointTriangulation* out) {
    *out = PointTriangulation();
    if (count < 3 || !(area > 0.0)) return true;
    const float spacing = float(std::sqrt(area / double(count)));
    const float reach = 2.2f * spacing;
    SpatialGrid grid;
    const size_t capacity = size_t(count) * 3;
    std::unique_ptr<uint32_t[]> tris(new (std::nothrow) uint32_t[capacity * 3]);
    if (!tris || !grid.build(positions, count, reach, nullptr)) return false;
    uint32_t made = 0;
    Candidate candidates[kMaxCandidates];
    for (uint32_t i = 0; i < count && made < capacity; ++i) {
        const glm::vec3 p = grid.point(i);
        const glm::vec3 n(normals[i * 3], normals[i * 3 + 1], normals[i * 3 + 2]);
        if (!(glm::dot(n, n) > 0.5f)) continue;
        // Tangent frame (e1, e2, n), right-handed: counter-clockwise about n.
        const glm::vec3 axis = std::fabs(n.x) < 0.7f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
        const glm::vec3 e1 = glm::normalize(glm::cross(axis, n)), e2 = glm::cross(n, e1);
        // The nearest same-sheet neighbours within reach.
        int found = 0;
        grid.near(p, reach, [&](uint32_t j) {
            if (j == i) return;
            const glm::vec3 d = grid.point(j) - p;
            const float d2 = glm::dot(d, d);
            if (!(d2 > 0.0f) || d2 > reach * reach) return;
            const glm::vec3 nj(normals[j * 3], normals[j * 3 + 1], normals[j * 3 + 2]);
            const float off = glm::dot(d, n);
            if (glm::dot(nj, n) < 0.5f || off * off > 0.25f * d2) return;  // another sheet
            const Candidate c{d2, j, glm::vec2(glm::dot(d, e1), glm::dot(d, e2))};
            if (found < kMaxCandidates) {
                candidates[found++] = c;
            } else {
                Candidate* worst = std::max_element(candidates, candidates + found,
                    [](const Candidate& x, const Candidate& y) { return x.distance2 < y.distance2; });
                if (c.distance2 < worst->distance2) *worst = c;
            }
        });
        std::sort(candidates, candidates + found,
                  [](const Candidate& x, const Candidate& y) { return x.distance2 < y.distance2; });
        // Voronoi cell of i among them; its edges name the Delaunay neighbours in order.
        Cell cell;
        cell.n = 4;
        const float box = reach;
        const glm::vec2 corners[4] = {{-box, -box}, {box, -box}, {box, box}, {-box, box}};
        for (int m = 0; m < 4; ++m) cell.v[m] = corners[m], cell.label[m] = -1;
        for (int c = 0; c < found && cell.n > 0; ++c) clip(&cell, candidates[c].q, c);
        // Consecutive neighbour edges make triangles; kept by the lowest-indexed corner.
        for (int m = 0; m < cell.n && made < capacity; ++m) {
            const int a = cell.label[m], b = cell.label[(m + 1) % cell.n];
            if (a < 0 || b < 0 || a == b) continue;
            const uint32_t j = candidates[a].index, k = candidates[b].index;
            if (i > j || i > k) continue;
            tris[size_t(made) * 3] = i;
            tris[size_t(made) * 3 + 1] = j;
            tris[size_t(made) * 3 + 2] = k;
            ++made;
        }
    }
    out->triangle_count = made;
    out->indices = std::move(tris);
    return true;
}

}  // namespace stipple
