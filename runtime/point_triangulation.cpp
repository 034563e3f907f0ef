#include "runtime/point_triangulation.h"

#include <algorithm>
#include <cmath>
#include <new>

#include "runtime/memory.h"
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

// Which triangles of the surface lie within reach of a point *along the surface*: the
// triangles connected to the point's host triangle through shared (welded) vertices whose
// bounding spheres meet the ball of radius `reach`. Two points may only be joined if one's host
// triangle is among the other's: parts that merely pass close (an arm by the torso, fingers)
// are never bridged, so no triangle spans the air between parts that move apart.
struct SurfaceReach {
    const MeshView* mesh = nullptr;
    Buffer<uint32_t> weld;         // vertex -> canonical vertex (same position)
    Buffer<uint32_t> start, tris;  // canonical vertex -> its triangles (CSR)
    Buffer<uint32_t> stamp;        // per triangle: last point that reached it
    Buffer<uint32_t> tested;       // per triangle: last point that tested its sphere
    Buffer<uint32_t> walked;       // per canonical vertex: last point that walked its triangles
    Buffer<uint32_t> queue;        // canonical vertices to walk
    Buffer<float> sphere;          // per triangle: centroid xyz, radius

    glm::vec3 vertex(uint32_t v) const {
        return glm::vec3(mesh->positions[v * 3], mesh->positions[v * 3 + 1],
                         mesh->positions[v * 3 + 2]);
    }

    bool build(const MeshView& m) {
        mesh = &m;
        const uint32_t nv = m.vertex_count, nt = m.triangle_count;
        Buffer<uint32_t> order = make_buffer<uint32_t>(nv + 1);
        weld = make_buffer<uint32_t>(nv + 1);
        start = make_buffer<uint32_t>(nv + 2);
        tris = make_buffer<uint32_t>(size_t(nt) * 3 + 1);
        stamp = make_buffer<uint32_t>(nt + 1);
        tested = make_buffer<uint32_t>(nt + 1);
        walked = make_buffer<uint32_t>(nv + 1);
        queue = make_buffer<uint32_t>(nv + 1);
        sphere = make_buffer<float>(size_t(nt) * 4 + 4);
        if (!order || !weld || !start || !tris || !stamp || !tested || !walked || !queue || !sphere)
            return false;
        std::fill(walked.get(), walked.get() + nv + 1, ~0u);
        for (uint32_t v = 0; v < nv; ++v) order[v] = v;
        auto less = [&](uint32_t a, uint32_t b) {
            const float* pa = m.positions + size_t(a) * 3;
            const float* pb = m.positions + size_t(b) * 3;
            return std::lexicographical_compare(pa, pa + 3, pb, pb + 3);
        };
        std::sort(order.get(), order.get() + nv, less);
        for (uint32_t k = 0; k < nv; ++k)
            weld[order[k]] = k > 0 && !less(order[k - 1], order[k]) ? weld[order[k - 1]] : order[k];
        std::fill(start.get(), start.get() + nv + 2, 0u);
        for (uint32_t t = 0; t < nt; ++t)
            for (int c = 0; c < 3; ++c) ++start[weld[m.indices[size_t(t) * 3 + c]] + 1];
        for (uint32_t v = 0; v < nv; ++v) start[v + 1] += start[v];
        Buffer<uint32_t> fill = make_buffer<uint32_t>(nv + 1);
        if (!fill) return false;
        std::copy(start.get(), start.get() + nv, fill.get());
        for (uint32_t t = 0; t < nt; ++t) {
            stamp[t] = tested[t] = ~0u;
            const uint32_t* tri = m.indices + size_t(t) * 3;
            for (int c = 0; c < 3; ++c) tris[fill[weld[tri[c]]]++] = t;
            const glm::vec3 a = vertex(tri[0]), b = vertex(tri[1]), cc = vertex(tri[2]);
            const glm::vec3 centre = (a + b + cc) / 3.0f;
            float* sp = sphere.get() + size_t(t) * 4;
            sp[0] = centre.x, sp[1] = centre.y, sp[2] = centre.z;
            sp[3] = std::sqrt(
                std::max({glm::dot(a - centre, a - centre), glm::dot(b - centre, b - centre),
                          glm::dot(cc - centre, cc - centre)}));
        }
        return true;
    }

    // Queues the canonical vertices of triangle t not yet walked for point id.
    void reach_corners(uint32_t id, uint32_t t, uint32_t* tail) {
        const uint32_t* tri = mesh->indices + size_t(t) * 3;
        for (int c = 0; c < 3; ++c) {
            const uint32_t v = weld[tri[c]];
            if (walked[v] == id) continue;
            walked[v] = id;
            queue[(*tail)++] = v;
        }
    }

    // Marks (stamp = id) the triangles reachable from `host` within `reach` of p: those
    // sharing a vertex with a marked one whose sphere meets the ball. Each vertex's triangles
    // are walked once and each triangle's sphere tested once per point.
    void mark(uint32_t id, uint32_t host, const glm::vec3& p, float reach) {
        uint32_t head = 0, tail = 0;
        stamp[host] = tested[host] = id;
        reach_corners(id, host, &tail);
        while (head < tail) {
            const uint32_t v = queue[head++];
            for (uint32_t k = start[v]; k < start[v + 1]; ++k) {
                const uint32_t u = tris[k];
                if (tested[u] == id) continue;
                tested[u] = id;
                const float* sp = sphere.get() + size_t(u) * 4;
                if (glm::length(glm::vec3(sp[0], sp[1], sp[2]) - p) > reach + sp[3]) continue;
                stamp[u] = id;
                reach_corners(id, u, &tail);
            }
        }
    }
};

Status out_of_memory(uint32_t count) {
    return make_status(StatusCode::out_of_memory, "out of memory triangulating %u points", count);
}

// Copies the `made` triangles of raw into out sorted by first corner (counting sort, stable:
// a point's triangles keep their order); first[i + 1] holds point i's count, first[0] 0.
void in_point_order(const uint32_t* raw, uint32_t made, uint32_t count, uint32_t* first,
                    uint32_t* out) {
    for (uint32_t i = 0; i < count; ++i) first[i + 1] += first[i];
    for (uint32_t t = 0; t < made; ++t) {
        const uint32_t at = first[raw[size_t(t) * 3]]++;
        std::copy(raw + size_t(t) * 3, raw + size_t(t) * 3 + 3, out + size_t(at) * 3);
    }
}

}  // namespace

double surface_area(const MeshView& m) {
    double area = 0.0;
    for (uint32_t t = 0; t < m.triangle_count; ++t) {
        const uint32_t* tri = m.indices + size_t(t) * 3;
        const glm::vec3 a(m.positions[tri[0] * 3], m.positions[tri[0] * 3 + 1],
                          m.positions[tri[0] * 3 + 2]);
        const glm::vec3 b(m.positions[tri[1] * 3], m.positions[tri[1] * 3 + 1],
                          m.positions[tri[1] * 3 + 2]);
        const glm::vec3 c(m.positions[tri[2] * 3], m.positions[tri[2] * 3 + 1],
                          m.positions[tri[2] * 3 + 2]);
        const float twice = glm::length(glm::cross(b - a, c - a));
        if (std::isfinite(twice)) area += 0.5 * double(twice);
    }
    return area;
}

Status triangulate_points(uint32_t count, const float* positions, const float* normals, double area,
                          const MeshView* surface, const uint32_t* host_triangle,
                          PointTriangulation* out) {
    *out = PointTriangulation();
    if (count < 3 || !(area > 0.0)) return {};
    SurfaceReach along;
    if (surface && host_triangle && !along.build(*surface)) return out_of_memory(count);
    const float spacing = float(std::sqrt(area / double(count)));
    const float reach = 2.2f * spacing;
    SpatialGrid grid;
    const size_t capacity = size_t(count) * 3;
    // The points are taken cell by cell (the grid's slots), so one point's neighbours and
    // hosts are still in cache for the next; the triangles are put in point order after.
    Buffer<uint32_t> tris = make_buffer<uint32_t>(capacity * 3);
    Buffer<uint32_t> raw = make_buffer<uint32_t>(capacity * 3);
    Buffer<uint32_t> first = make_buffer<uint32_t>(size_t(count) + 1);
    if (!tris || !raw || !first || !grid.build(positions, count, reach, nullptr))
        return out_of_memory(count);
    std::fill(first.get(), first.get() + count + 1, 0u);
    uint32_t made = 0;
    Candidate candidates[kMaxCandidates];
    for (uint32_t slot_i = 0; slot_i < count && made < capacity; ++slot_i) {
        const uint32_t i = grid.items[slot_i];
        const glm::vec3 p = grid.slot_point(slot_i);
        const glm::vec3 n(normals[i * 3], normals[i * 3 + 1], normals[i * 3 + 2]);
        if (!(glm::dot(n, n) > 0.5f)) continue;
        // Tangent frame (e1, e2, n), right-handed: counter-clockwise about n.
        const glm::vec3 axis = std::fabs(n.x) < 0.7f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
        const glm::vec3 e1 = glm::normalize(glm::cross(axis, n)), e2 = glm::cross(n, e1);
        // The nearest same-sheet neighbours within reach, along the surface.
        if (along.mesh) along.mark(i, host_triangle[i], p, reach);
        int found = 0;
        grid.near_slots(p, reach, [&](uint32_t slot) {
            const uint32_t j = grid.items[slot];
            if (j == i) return;
            if (along.mesh && along.stamp[host_triangle[j]] != i) return;  // another part
            const glm::vec3 d = grid.slot_point(slot) - p;
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
                                                    [](const Candidate& x, const Candidate& y) {
                                                        return x.distance2 < y.distance2;
                                                    });
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
            raw[size_t(made) * 3] = i;
            raw[size_t(made) * 3 + 1] = j;
            raw[size_t(made) * 3 + 2] = k;
            ++first[i + 1];
            ++made;
        }
    }
    in_point_order(raw.get(), made, count, first.get(), tris.get());
    out->triangle_count = made;
    out->indices = std::move(tris);
    return {};
}

}  // namespace stipple
