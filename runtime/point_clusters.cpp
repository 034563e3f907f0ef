#include "runtime/point_clusters.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/gtc/type_ptr.hpp>

namespace stipple {

namespace {

// Thesis §9.1.2's parts: about this many grid cells' worth of surface (cell side =
// sqrt(area / kTargetCells)), split further by dominant joint. Fixed by the mesh, not by the
// point count, so a denser bake has as many clusters, each with more points.
constexpr double kTargetCells = 256.0;
constexpr uint32_t kCellBits = 13;    // cell coordinates per axis: 0 .. 2^13 - 1
constexpr double kBucketEdge = 0.38;  // ~sin 22.5 deg: a face's normals in 3 x 3 cells

const float* vertex(const float* positions, uint32_t v) {
    return positions + size_t(v) * 3;
}

// Bind-pose position of point i (thesis Alg. 6.3 on the bind mesh).
void bind_position(const Asset& a, uint32_t i, float out[3]) {
    const PointsView& p = a.points;
    const uint32_t* tri = a.mesh.indices + size_t(p.host_triangle[i]) * 3;
    const float u = p.bary_u[i], v = p.bary_v[i], w = 1.0f - u - v;
    for (int k = 0; k < 3; ++k)
        out[k] = u * vertex(a.mesh.positions, tri[0])[k] + v * vertex(a.mesh.positions, tri[1])[k] +
                 w * vertex(a.mesh.positions, tri[2])[k];
}

// Which measure relevance_scale (runtime/point_placement.cpp) gives point i: bit 1 the area
// measure k I2^(1/4) (neighbours spanning an area, or none: the fallback radius), bit 2 the
// mean distance (nearly collinear neighbours); both near the 0.01 tr^2 threshold (rounding).
int relevance_measure(const Asset& a, uint32_t i) {
    const PointsView& p = a.points;
    if (p.neighbour_offsets[i] == p.neighbour_offsets[i + 1]) return 1;
    float c[3], q[3];
    bind_position(a, i, c);
    float xx = 0, yy = 0, zz = 0, xy = 0, xz = 0, yz = 0;
    for (uint32_t k = p.neighbour_offsets[i]; k < p.neighbour_offsets[i + 1]; ++k) {
        bind_position(a, p.neighbours[k], q);
        const float dx = q[0] - c[0], dy = q[1] - c[1], dz = q[2] - c[2];
        xx += dx * dx, yy += dy * dy, zz += dz * dz;
        xy += dx * dy, xz += dx * dz, yz += dy * dz;
    }
    const float i2 = (xx * yy - xy * xy) + (xx * zz - xz * xz) + (yy * zz - yz * yz);
    const float trace = xx + yy + zz;
    const bool area = i2 > 0.009f * trace * trace && i2 > 0.0f;
    const bool line = !(i2 > 0.011f * trace * trace && i2 > 0.0f);
    return (area ? 1 : 0) | (line ? 2 : 0);
}

// The bind face normal's direction bucket (0 .. 53; 0 when degenerate): its dominant axis and
// sign (a cube face), and on that face which third each other component falls in (beyond
// -kBucketEdge, within, beyond +kBucketEdge of the normal's length: 3 x 3 cells per face).
// Clusters facing one way have narrow normal cones, so the back-face test culls whole clusters
// and the slope bound (point_clusters_select.cpp) tightens the cut of those seen at a grazing
// angle. (Measured against the six faces alone: the points run per frame 24.1k -> 20.4k on the
// CesiumMan walk, 27.7k -> 19.0k on the bent horse; docs/performance.md, seventh round.)
uint64_t normal_bucket(const MeshView& m, const uint32_t* tri) {
    const glm::dvec3 a(glm::make_vec3(vertex(m.positions, tri[0])));
    const glm::dvec3 b(glm::make_vec3(vertex(m.positions, tri[1])));
    const glm::dvec3 c(glm::make_vec3(vertex(m.positions, tri[2])));
    const glm::dvec3 n = glm::cross(b - a, c - a);
    const glm::dvec3 size = glm::abs(n);
    const int axis = size.x >= size.y && size.x >= size.z ? 0 : (size.y >= size.z ? 1 : 2);
    const double edge = kBucketEdge * glm::length(n);
    auto third = [&](double x) { return uint64_t(x > edge ? 2 : (x < -edge ? 1 : 0)); };
    const uint64_t face = uint64_t(axis * 2 + (n[axis] < 0.0 ? 1 : 0));
    return face * 9 + third(n[(axis + 1) % 3]) * 3 + third(n[(axis + 2) % 3]);
}

// Per triangle: dominant joint (skinned), bind normal's bucket and grid cell of the bind
// centroid, as one key.
uint64_t triangle_key(const Asset& a, uint32_t t, const float lo[3], double cell) {
    const uint32_t* tri = a.mesh.indices + size_t(t) * 3;
    uint64_t joint = 0;
    if (a.skinned && a.skin.joints && a.skin.weights) {
        uint16_t ids[12];
        float sums[12];
        int n = 0;
        for (int k = 0; k < 3; ++k)
            for (int j = 0; j < 4; ++j) {
                const uint16_t id = a.skin.joints[size_t(tri[k]) * 4 + j];
                const float w = a.skin.weights[size_t(tri[k]) * 4 + j];
                int m = 0;
                while (m < n && ids[m] != id) ++m;
                if (m == n) ids[n] = id, sums[n++] = 0.0f;
                sums[m] += w;
            }
        int best = 0;
        for (int m = 1; m < n; ++m)
            if (sums[m] > sums[best] || (sums[m] == sums[best] && ids[m] < ids[best])) best = m;
        joint = ids[best];
    }
    uint64_t key = joint << 6 | normal_bucket(a.mesh, tri);  // 16 + 6 + 3 x 13 bits
    for (int k = 0; k < 3; ++k) {
        const double centre =
            (double(vertex(a.mesh.positions, tri[0])[k]) + vertex(a.mesh.positions, tri[1])[k] +
             vertex(a.mesh.positions, tri[2])[k]) /
            3.0;
        const double x = std::floor((centre - lo[k]) / cell);
        const uint64_t max_cell = (1u << kCellBits) - 1;
        key = key << kCellBits | uint64_t(std::min(std::max(x, 0.0), double(max_cell)));
    }
    return key;
}

// The grid cell side: the surface area split into about kTargetCells squares.
double cell_side(const MeshView& m, float lo[3]) {
    float hi[3];
    for (int k = 0; k < 3; ++k) lo[k] = m.vertex_count ? m.positions[k] : 0.0f, hi[k] = lo[k];
    for (uint32_t v = 0; v < m.vertex_count; ++v)
        for (int k = 0; k < 3; ++k)
            lo[k] = std::min(lo[k], m.positions[size_t(v) * 3 + k]),
            hi[k] = std::max(hi[k], m.positions[size_t(v) * 3 + k]);
    double area = 0.0;
    for (uint32_t t = 0; t < m.triangle_count; ++t) {
        const uint32_t* tri = m.indices + size_t(t) * 3;
        const glm::dvec3 a(glm::make_vec3(vertex(m.positions, tri[0])));
        const glm::dvec3 b(glm::make_vec3(vertex(m.positions, tri[1])));
        const glm::dvec3 c(glm::make_vec3(vertex(m.positions, tri[2])));
        area += 0.5 * glm::length(glm::cross(b - a, c - a));
    }
    const double extent =
        std::max({double(hi[0] - lo[0]), double(hi[1] - lo[1]), double(hi[2] - lo[2]), 1e-30});
    // Never so fine that a coordinate overflows its bits.
    const double side = std::sqrt(area / kTargetCells);
    return std::max(side, extent / double((1u << kCellBits) - 2));
}

// Triangles sorted by key (ties by index: deterministic), numbered into clusters.
Status group_triangles(PointClusters* c, const Asset& a, Buffer<uint32_t>* tri_cluster) {
    const uint32_t tcount = a.mesh.triangle_count;
    Buffer<uint64_t> keys = make_buffer<uint64_t>(tcount);
    Buffer<uint32_t> sorted = make_buffer<uint32_t>(tcount);
    *tri_cluster = make_buffer<uint32_t>(tcount);
    if (!keys || !sorted || !*tri_cluster)
        return make_status(StatusCode::out_of_memory, "out of memory for %u clusters", tcount);
    float lo[3];
    const double cell = cell_side(a.mesh, lo);
    for (uint32_t t = 0; t < tcount; ++t) keys[t] = triangle_key(a, t, lo, cell), sorted[t] = t;
    const uint64_t* k = keys.get();
    std::sort(sorted.get(), sorted.get() + tcount,
              [k](uint32_t x, uint32_t y) { return k[x] != k[y] ? k[x] < k[y] : x < y; });
    uint32_t clusters = 0;
    for (uint32_t j = 0; j < tcount; ++j) {
        if (j > 0 && k[sorted[j]] != k[sorted[j - 1]]) ++clusters;
        (*tri_cluster)[sorted[j]] = clusters;
    }
    c->cluster_count = tcount ? clusters + 1 : 0;
    return {};
}

// The points by cluster, a stable bucket sort: each cluster keeps the global coarse-to-fine
// order.
Status sort_points(PointClusters* c, const Asset& a, const uint32_t* tri_cluster) {
    const uint32_t n = a.points.point_count;
    if (!alloc(&c->point_begin, size_t(c->cluster_count) + 1) || !alloc(&c->order, n))
        return make_status(StatusCode::out_of_memory, "out of memory for %u points", n);
    uint32_t* begin = c->point_begin.get();
    std::fill(begin, begin + c->cluster_count + 1, 0u);
    for (uint32_t i = 0; i < n; ++i) ++begin[tri_cluster[a.points.host_triangle[i]] + 1];
    for (uint32_t k = 0; k < c->cluster_count; ++k) begin[k + 1] += begin[k];
    Buffer<uint32_t> fill = make_buffer<uint32_t>(c->cluster_count);
    if (!fill) return make_status(StatusCode::out_of_memory, "out of memory for clusters");
    std::memcpy(fill.get(), begin, size_t(c->cluster_count) * 4);
    for (uint32_t i = 0; i < n; ++i) c->order[fill[tri_cluster[a.points.host_triangle[i]]]++] = i;
    return {};
}

// A CSR list per cluster of unique items: visit(cluster, emit) calls emit(item) for each
// item (repeats allowed); `stamp` has item_count entries.
template <typename Visit>
Status build_lists(uint32_t clusters, uint32_t item_count, Buffer<uint32_t>* begin,
                   Buffer<uint32_t>* items, Visit visit) {
    Buffer<uint32_t> stamp = make_buffer<uint32_t>(item_count);
    if (!stamp || !alloc(begin, size_t(clusters) + 1))
        return make_status(StatusCode::out_of_memory, "out of memory for cluster lists");
    std::fill(stamp.get(), stamp.get() + item_count, 0u);
    uint32_t total = 0;
    for (int pass = 0; pass < 2; ++pass) {
        if (pass == 1 && !alloc(items, total))
            return make_status(StatusCode::out_of_memory, "out of memory for cluster lists");
        uint32_t n = 0;
        for (uint32_t k = 0; k < clusters; ++k) {
            (*begin)[k] = n;
            const uint32_t mark = k + 1 + pass * clusters;
            visit(k, [&](uint32_t item) {
                if (stamp[item] == mark) return;
                stamp[item] = mark;
                if (pass == 1) (*items)[n] = item;
                ++n;
            });
        }
        (*begin)[clusters] = n;
        total = n;
    }
    return {};
}

// Vertices of each cluster's triangles, and the triangles its points and their relevant
// neighbours lie on.
Status cluster_lists(PointClusters* c, const Asset& a, const uint32_t* tri_cluster) {
    const uint32_t tcount = a.mesh.triangle_count;
    Buffer<uint32_t> tri_begin = make_buffer<uint32_t>(size_t(c->cluster_count) + 1);
    Buffer<uint32_t> tris = make_buffer<uint32_t>(tcount);
    if (!tri_begin || !tris) return make_status(StatusCode::out_of_memory, "out of memory");
    std::fill(tri_begin.get(), tri_begin.get() + c->cluster_count + 1, 0u);
    for (uint32_t t = 0; t < tcount; ++t) ++tri_begin[tri_cluster[t] + 1];
    for (uint32_t k = 0; k < c->cluster_count; ++k) tri_begin[k + 1] += tri_begin[k];
    {
        Buffer<uint32_t> fill = make_buffer<uint32_t>(c->cluster_count);
        if (!fill) return make_status(StatusCode::out_of_memory, "out of memory");
        std::memcpy(fill.get(), tri_begin.get(), size_t(c->cluster_count) * 4);
        for (uint32_t t = 0; t < tcount; ++t) tris[fill[tri_cluster[t]]++] = t;
    }
    Status st = build_lists(c->cluster_count, a.mesh.vertex_count, &c->vertex_begin, &c->vertices,
                            [&](uint32_t k, auto emit) {
                                for (uint32_t j = tri_begin[k]; j < tri_begin[k + 1]; ++j)
                                    for (int v = 0; v < 3; ++v)
                                        emit(a.mesh.indices[size_t(tris[j]) * 3 + v]);
                            });
    if (!st.ok()) return st;
    const PointsView& p = a.points;
    return build_lists(
        c->cluster_count, tcount, &c->reach_begin, &c->reach, [&](uint32_t k, auto emit) {
            for (uint32_t j = tri_begin[k]; j < tri_begin[k + 1]; ++j) emit(tris[j]);
            for (uint32_t j = c->point_begin[k]; j < c->point_begin[k + 1]; ++j) {
                const uint32_t i = c->order[j];
                for (uint32_t e = p.neighbour_offsets[i]; e < p.neighbour_offsets[i + 1]; ++e)
                    emit(p.host_triangle[p.neighbours[e]]);
            }
        });
}

// Radius bounds along `order`, as suffix maxima per cluster; which clusters back-face culling
// may skip (single-sided triangles, barycentric weights in [0, 1]).
Status cluster_bounds(PointClusters* c, const Asset& a, const float* radius,
                      const float* rest_radius) {
    const uint32_t n = a.points.point_count;
    if (!alloc(&c->bound, n) || !alloc(&c->line_bound, n) || !alloc(&c->rest_bound, n) ||
        !alloc(&c->single_sided, c->cluster_count))
        return make_status(StatusCode::out_of_memory, "out of memory for %u points", n);
    const PointsView& p = a.points;
    const uint8_t* double_sided = a.sides.triangle_double_sided;
    for (uint32_t k = 0; k < c->cluster_count; ++k) {
        float bound = 0.0f, line = 0.0f, rest = 0.0f;
        bool single = true;
        for (uint32_t j = c->point_begin[k + 1]; j-- > c->point_begin[k];) {
            const uint32_t i = c->order[j];
            const int measure = relevance_measure(a, i);
            if (measure & 1) bound = std::max(bound, radius[i]);
            if (measure & 2) line = std::max(line, radius[i]);
            rest = std::max(rest, rest_radius[i]);
            c->bound[j] = bound;
            c->line_bound[j] = line;
            c->rest_bound[j] = rest;
            const float w = 1.0f - p.bary_u[i] - p.bary_v[i];
            if (!(p.bary_u[i] >= 0.0f && p.bary_v[i] >= 0.0f && w >= 0.0f)) single = false;
            if (double_sided && double_sided[p.host_triangle[i]]) single = false;
        }
        c->single_sided[k] = single;
    }
    return {};
}

// Paintstroke roots the stroke stage reads (runtime/stroke_stage.cpp): run every frame.
Status forced_points(PointClusters* c, const Asset& a) {
    const StrokesView& s = a.strokes;
    if (!alloc(&c->forced, s.stroke_count) || !alloc(&c->forced_bits, c->word_count))
        return make_status(StatusCode::out_of_memory, "out of memory for stroke roots");
    std::fill(c->forced_bits.get(), c->forced_bits.get() + c->word_count, uint64_t(0));
    c->forced_count = 0;
    for (uint32_t i = 0; i < s.stroke_count; ++i) {
        const uint32_t root = s.strokes[i].root_point;
        if (root == format::kNoRootPoint || root >= a.points.point_count) continue;
        c->forced[c->forced_count++] = root;
        c->forced_bits[root >> 6] |= uint64_t(1) << (root & 63);
    }
    return {};
}

Status bind_grams(PointClusters* c, const Asset& a) {
    const MeshView& m = a.mesh;
    c->deforming = a.skinned || a.has_morph();
    if (!c->deforming) return {};
    if (!alloc(&c->bind_gram, size_t(m.triangle_count) * 3) ||
        !alloc(&c->area_ratio, m.triangle_count) || !alloc(&c->edge_ratio, m.triangle_count) ||
        !alloc(&c->reach_split, c->cluster_count))
        return make_status(StatusCode::out_of_memory, "out of memory for %u triangles",
                           m.triangle_count);
    for (uint32_t t = 0; t < m.triangle_count; ++t) {
        const uint32_t* tri = m.indices + size_t(t) * 3;
        const glm::vec3 o = glm::make_vec3(vertex(m.positions, tri[0]));
        const glm::vec3 e1 = glm::make_vec3(vertex(m.positions, tri[1])) - o;
        const glm::vec3 e2 = glm::make_vec3(vertex(m.positions, tri[2])) - o;
        c->bind_gram[size_t(t) * 3] = glm::dot(e1, e1);
        c->bind_gram[size_t(t) * 3 + 1] = glm::dot(e1, e2);
        c->bind_gram[size_t(t) * 3 + 2] = glm::dot(e2, e2);
    }
    // Each cluster's reach: the triangles with a bind area first, the degenerate ones last.
    const float* g = c->bind_gram.get();
    for (uint32_t k = 0; k < c->cluster_count; ++k) {
        uint32_t* first = c->reach.get() + c->reach_begin[k];
        uint32_t* last = c->reach.get() + c->reach_begin[k + 1];
        c->reach_split[k] = uint32_t(
            std::stable_partition(
                first, last, [g](uint32_t t) { return bind_area_defined(g + size_t(t) * 3); }) -
            c->reach.get());
    }
    return {};
}

// The neighbours of each point that its cluster's prefix up to it does not hold.
Status closure_lists(PointClusters* c, const PointsView& p) {
    const uint32_t n = p.point_count;
    Buffer<uint32_t> at = make_buffer<uint32_t>(n), cluster = make_buffer<uint32_t>(n);
    if (!at || !cluster || !alloc(&c->closure_begin, size_t(n) + 1))
        return make_status(StatusCode::out_of_memory, "out of memory for %u points", n);
    for (uint32_t k = 0; k < c->cluster_count; ++k)
        for (uint32_t j = c->point_begin[k]; j < c->point_begin[k + 1]; ++j)
            at[c->order[j]] = j, cluster[c->order[j]] = k;
    for (int pass = 0; pass < 2; ++pass) {
        if (pass == 1 && !alloc(&c->closure, c->closure_begin[n]))
            return make_status(StatusCode::out_of_memory, "out of memory for %u points", n);
        uint32_t count = 0;
        for (uint32_t j = 0; j < n; ++j) {
            c->closure_begin[j] = count;
            const uint32_t i = c->order[j];
            for (uint32_t e = p.neighbour_offsets[i]; e < p.neighbour_offsets[i + 1]; ++e) {
                const uint32_t q = p.neighbours[e];
                if (cluster[q] == cluster[i] && at[q] <= j) continue;  // in every prefix with i
                if (pass == 1) c->closure[count] = q;
                ++count;
            }
        }
        c->closure_begin[n] = count;
    }
    return {};
}

}  // namespace

Status point_clusters_init(PointClusters* c, const Asset& a, const float* baked_radius,
                           const float* rest_radius) {
    *c = PointClusters();
    c->point_count = a.points.point_count;
    c->word_count = (c->point_count + 63) / 64;
    Buffer<uint32_t> tri_cluster;
    Status st = group_triangles(c, a, &tri_cluster);
    if (st.ok()) st = sort_points(c, a, tri_cluster.get());
    if (st.ok()) st = cluster_lists(c, a, tri_cluster.get());
    if (st.ok()) st = cluster_bounds(c, a, baked_radius, rest_radius);
    if (st.ok()) st = forced_points(c, a);
    if (st.ok()) st = bind_grams(c, a);
    if (st.ok()) st = closure_lists(c, a.points);
    if (st.ok() && (!alloc(&c->run, c->point_count) || !alloc(&c->placed, c->point_count) ||
                    !alloc(&c->keep, c->cluster_count) || !alloc(&c->keep_kind, c->cluster_count) ||
                    !alloc(&c->rest, c->point_count) || !alloc(&c->run_bits, c->word_count) ||
                    !alloc(&c->placed_bits, c->word_count)))
        st = make_status(StatusCode::out_of_memory, "out of memory for %u points", c->point_count);
    if (!st.ok()) return st;
    std::fill(c->keep.get(), c->keep.get() + c->cluster_count, 0u);  // the first cut's hint
    c->stats.clusters = c->cluster_count;
    return {};
}

}  // namespace stipple
