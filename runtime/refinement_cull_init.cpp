// refinement_cull_init: the clusters and their load-time bounds (runtime/refinement_cull.h).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/gtc/type_ptr.hpp>

#include "runtime/refinement_cull.h"

namespace stipple {

namespace {

constexpr uint32_t kTrianglesPerCluster = 256;
constexpr uint32_t kNone = 0xFFFFFFFFu;
constexpr uint32_t kSpanPerEdge = kCullSpanPerEdge, kSpanPerTriangle = 3 * kSpanPerEdge;
constexpr float kSlack = kCullSlack;

Status no_memory(uint32_t n) {
    return make_status(StatusCode::out_of_memory,
                       "out of memory for the refinement's culling of %u triangles", n);
}

glm::vec3 vertex(const MeshView& m, uint32_t v) {
    return glm::make_vec3(m.positions + size_t(v) * 3);
}

// indices with every vertex replaced by the first vertex at the same bind position; the pairs
// (vertex, its first) that differ into seam.
bool weld(const MeshView& m, uint32_t* indices, Buffer<uint32_t>* seam, uint32_t* seam_count) {
    Buffer<uint32_t> order = make_buffer<uint32_t>(m.vertex_count);
    Buffer<uint32_t> first = make_buffer<uint32_t>(m.vertex_count);
    if (!order || !first) return false;
    auto less = [&](uint32_t a, uint32_t b) {
        for (int d = 0; d < 3; ++d) {
            const float pa = m.positions[size_t(a) * 3 + d], pb = m.positions[size_t(b) * 3 + d];
            if (pa != pb) return pa < pb;
        }
        return a < b;
    };
    for (uint32_t v = 0; v < m.vertex_count; ++v) order[v] = v;
    std::sort(order.get(), order.get() + m.vertex_count, less);
    uint32_t pairs = 0;
    for (uint32_t j = 0; j < m.vertex_count; ++j) {
        const uint32_t v = order[j];
        const bool same = j > 0 && std::memcmp(m.positions + size_t(v) * 3,
                                               m.positions + size_t(order[j - 1]) * 3, 12) == 0;
        first[v] = same ? first[order[j - 1]] : v;
        pairs += first[v] != v;
    }
    if (!alloc(seam, size_t(pairs) * 2)) return false;
    *seam_count = 0;
    for (uint32_t v = 0; v < m.vertex_count; ++v)
        if (first[v] != v) {
            (*seam)[size_t(*seam_count) * 2] = v;
            (*seam)[size_t(*seam_count) * 2 + 1] = first[v];
            ++*seam_count;
        }
    for (size_t i = 0; i < size_t(m.triangle_count) * 3; ++i) indices[i] = first[m.indices[i]];
    return true;
}

// Render triangles around each render vertex (CSR); mark: per render triangle, the last chain
// search that reached it (one compare instead of a scan of the search's list).
struct Adjacency {
    Buffer<uint32_t> begin, triangle, mark;
    uint32_t triangle_count = 0, search = 0;

    uint32_t next_search() {
        if (++search == 0) {  // wrapped: forget every mark
            std::fill(mark.get(), mark.get() + triangle_count, 0u);
            search = 1;
        }
        return search;
    }
};

bool build_adjacency(const MeshView& m, Adjacency* a) {
    if (!alloc(&a->begin, size_t(m.vertex_count) + 1) ||
        !alloc(&a->triangle, size_t(m.triangle_count) * 3) || !alloc(&a->mark, m.triangle_count))
        return false;
    a->triangle_count = m.triangle_count;
    std::fill(a->mark.get(), a->mark.get() + m.triangle_count, 0u);
    std::fill(a->begin.get(), a->begin.get() + m.vertex_count + 1, 0u);
    for (size_t i = 0; i < size_t(m.triangle_count) * 3; ++i) ++a->begin[m.indices[i] + 1];
    for (uint32_t v = 0; v < m.vertex_count; ++v) a->begin[v + 1] += a->begin[v];
    Buffer<uint32_t> fill = make_buffer<uint32_t>(m.vertex_count);
    if (!fill) return false;
    std::copy(a->begin.get(), a->begin.get() + m.vertex_count, fill.get());
    for (uint32_t t = 0; t < m.triangle_count; ++t)
        for (int k = 0; k < 3; ++k) a->triangle[fill[m.indices[size_t(t) * 3 + k]]++] = t;
    return true;
}

bool has_vertex(const uint32_t* tri, uint32_t v) {
    return tri[0] == v || tri[1] == v || tri[2] == v;
}

// The two vertices triangles s and t share, if they share an edge.
bool shared_edge(const MeshView& m, uint32_t s, uint32_t t, uint32_t* a, uint32_t* b) {
    const uint32_t* ts = m.indices + size_t(s) * 3;
    const uint32_t* tt = m.indices + size_t(t) * 3;
    uint32_t shared[3], count = 0;
    for (int k = 0; k < 3; ++k)
        if (has_vertex(tt, ts[k])) shared[count++] = ts[k];
    if (count < 2) return false;
    *a = shared[0];
    *b = shared[1];
    return true;
}

// The fewest triangles from hx to hy across shared edges, at most kSpanPerEdge of them, into
// seq (hx first); 0 if none.
uint32_t triangle_chain(const MeshView& m, Adjacency& adj, uint32_t hx, uint32_t hy,
                        uint32_t* seq) {
    uint32_t ea, eb;
    if (hx != hy && shared_edge(m, hx, hy, &ea, &eb)) {  // most pairs: neighbours, no search
        seq[0] = hx;
        seq[1] = hy;
        return 2;
    }
    constexpr uint32_t kSeen = 256;
    uint32_t seen[kSeen], parent[kSeen], depth[kSeen], count = 1, head = 0;
    const uint32_t search = adj.next_search();
    seen[0] = hx;
    adj.mark[hx] = search;
    parent[0] = kNone;
    depth[0] = 1;
    auto chain_to = [&](uint32_t at) {  // the chain from hx to seen[at], into seq
        uint32_t n = depth[at];
        for (uint32_t i = at; i != kNone; i = parent[i]) seq[--n] = seen[i];
        return depth[at];
    };
    if (hx == hy) return chain_to(0);
    while (head < count) {
        const uint32_t at = head++;
        if (depth[at] >= kSpanPerEdge) continue;
        const uint32_t* tri = m.indices + size_t(seen[at]) * 3;
        for (int k = 0; k < 3; ++k)
            for (uint32_t e = adj.begin[tri[k]]; e < adj.begin[tri[k] + 1]; ++e) {
                const uint32_t u = adj.triangle[e];
                uint32_t a, b;
                if (adj.mark[u] == search || count == kSeen) continue;  // known, or full
                if (!shared_edge(m, seen[at], u, &a, &b)) continue;
                adj.mark[u] = search;
                seen[count] = u;
                parent[count] = at;
                depth[count++] = depth[at] + 1;
                // Found when reached: breadth first, no later chain is shorter, and this is
                // the one its turn in the queue would have given.
                if (u == hy) return chain_to(count - 1);
            }
    }
    return 0;
}

// The t in [0, 1] that minimises |p - u| + |w - p| for p = a + t (b - a): unfold u and w
// about the edge's line into one plane, on opposite sides, and cross the line where the
// straight segment between them does (the sum is convex in t, so clamping keeps the least).
float best_crossing(glm::vec3 a, glm::vec3 b, glm::vec3 u, glm::vec3 w) {
    const glm::vec3 d = b - a;
    const float len2 = glm::dot(d, d);
    if (!(len2 > 0.0f)) return 0.0f;
    const float tu = glm::dot(u - a, d) / len2, tw = glm::dot(w - a, d) / len2;
    const float ru = glm::length(u - a - tu * d), rw = glm::length(w - a - tw * d);
    const float t = ru + rw > 0.0f ? tu + (tw - tu) * ru / (ru + rw) : 0.5f * (tu + tw);
    return std::clamp(t, 0.0f, 1.0f);
}

// An upper bound on the bind length of a path on the render mesh from x (in triangle hx) to y
// (in hy): straight inside each triangle of the shortest chain between them, crossing each
// shared edge where coordinate descent puts it (any crossing gives a path, so any is an upper
// bound); through a shared vertex when that is shorter. The chain's triangles go to span
// (kNone: unused). Infinity when the hosts are further apart than kSpanPerEdge triangles.
float path_bound(const MeshView& m, Adjacency& adj, glm::vec3 x, uint32_t hx, glm::vec3 y,
                 uint32_t hy, uint32_t* span) {
    for (uint32_t i = 0; i < kSpanPerEdge; ++i) span[i] = kNone;
    span[0] = hx;
    if (hx == hy) return glm::length(y - x);
    float best = INFINITY;
    const uint32_t* tx = m.indices + size_t(hx) * 3;
    const uint32_t* ty = m.indices + size_t(hy) * 3;
    for (int k = 0; k < 3; ++k)
        if (has_vertex(ty, tx[k])) {
            const glm::vec3 v = vertex(m, tx[k]);
            best = std::min(best, glm::length(v - x) + glm::length(y - v));
        }
    uint32_t seq[kSpanPerEdge];
    const uint32_t n = triangle_chain(m, adj, hx, hy, seq);
    if (n < 2) {
        if (best < INFINITY) span[1] = hy;
        return best;
    }
    glm::vec3 a[kSpanPerEdge], b[kSpanPerEdge], q[kSpanPerEdge + 1];
    float s[kSpanPerEdge];
    for (uint32_t i = 1; i < n; ++i) {
        uint32_t va = 0, vb = 0;
        shared_edge(m, seq[i - 1], seq[i], &va, &vb);
        a[i] = vertex(m, va);
        b[i] = vertex(m, vb);
        s[i] = 0.5f;
        q[i] = a[i] + 0.5f * (b[i] - a[i]);
    }
    q[0] = x;
    q[n] = y;
    // Sweeps until no crossing moves by 1e-4 of its edge (any crossings give a bound).
    for (int sweep = 0; sweep < 12; ++sweep) {
        bool moved = false;
        for (uint32_t i = 1; i < n; ++i) {
            const float t = best_crossing(a[i], b[i], q[i - 1], q[i + 1]);
            moved = moved || std::fabs(t - s[i]) > 1e-4f;
            s[i] = t;
            q[i] = a[i] + t * (b[i] - a[i]);
        }
        if (!moved) break;
    }
    float g = 0.0f;
    for (uint32_t i = 0; i < n; ++i) g += glm::length(q[i + 1] - q[i]);
    if (g < best) {
        for (uint32_t i = 0; i < n; ++i) span[i] = seq[i];
        return g;
    }
    span[1] = hy;
    return best;
}

// Lists into out[begin[k] .. begin[k + 1]) the distinct ids(t, 0..per) over cluster k's
// triangles (order[tri_begin[k] .. tri_begin[k + 1])); ids kNone are left out.
template <typename Ids>
bool collect(uint32_t clusters, const uint32_t* order, const uint32_t* tri_begin, uint32_t per,
             uint32_t id_count, Ids ids, Buffer<uint32_t>* begin, Buffer<uint32_t>* out) {
    Buffer<uint32_t> stamp = make_buffer<uint32_t>(size_t(id_count) + 1);
    if (!stamp || !alloc(begin, size_t(clusters) + 1)) return false;
    std::fill(stamp.get(), stamp.get() + id_count + 1, kNone);
    for (int pass = 0; pass < 2; ++pass) {
        uint32_t n = 0;
        for (uint32_t k = 0; k < clusters; ++k) {
            if (pass == 0) (*begin)[k] = n;
            for (uint32_t j = tri_begin[k]; j < tri_begin[k + 1]; ++j)
                for (uint32_t i = 0; i < per; ++i) {
                    const uint32_t id = ids(order[j], i);
                    if (id == kNone || id >= id_count || stamp[id] == k * 2 + uint32_t(pass))
                        continue;
                    stamp[id] = k * 2 + uint32_t(pass);
                    if (pass == 1) (*out)[n] = id;
                    ++n;
                }
        }
        if (pass == 0) {
            (*begin)[clusters] = n;
            if (!alloc(out, n)) return false;
        }
    }
    return true;
}

// Per domain triangle, from its corners' paths over the render mesh (topology: welded).
struct TriangleBounds {
    Buffer<uint32_t> spans;  // kSpanPerTriangle per triangle: render triangles of its paths
    Buffer<float> lower;     // 2 per triangle: lower_t, lower_t / q_t (-1: a corner off host)
    Buffer<float> terms;     // 3 per triangle: refinement_cull's affine bound over lower_t
    Buffer<float> shortest;  // its shortest edge path bound
    glm::vec3 lo{INFINITY}, hi{-INFINITY};  // box of the triangles' centres
    double area = 0.0;
};

constexpr int kEnds[3][2] = {{0, 1}, {0, 2}, {1, 2}};  // edge e of a triangle: its corners

// The path bound of edge e of every domain triangle t into g[t * 3 + e], its render triangles
// into spans + (t * 3 + e) * kSpanPerEdge: once per edge (the triangles on either side copy
// it), from its lower-numbered corner to the other.
bool edge_paths(const MeshView& domain, const MeshView& topology, Adjacency& adj,
                const PointsView& points, float* g, uint32_t* spans) {
    const size_t sides = size_t(domain.triangle_count) * 3;
    Buffer<uint64_t> key = make_buffer<uint64_t>(sides);
    Buffer<uint32_t> order = make_buffer<uint32_t>(sides);
    if (!key || !order) return false;
    for (size_t j = 0; j < sides; ++j) {
        const uint32_t* tri = domain.indices + (j / 3) * 3;
        const uint32_t x = tri[kEnds[j % 3][0]], y = tri[kEnds[j % 3][1]];
        key[j] = uint64_t(std::min(x, y)) << 32 | std::max(x, y);
        order[j] = uint32_t(j);
    }
    std::sort(order.get(), order.get() + sides,
              [&](uint32_t a, uint32_t b) { return key[a] != key[b] ? key[a] < key[b] : a < b; });
    for (size_t r = 0; r < sides;) {
        const uint32_t first = order[r];
        const uint32_t x = uint32_t(key[first] >> 32), y = uint32_t(key[first]);
        uint32_t* span = spans + size_t(first) * kSpanPerEdge;
        g[first] = path_bound(topology, adj, vertex(domain, x), points.host_triangle[x],
                              vertex(domain, y), points.host_triangle[y], span);
        for (++r; r < sides && key[order[r]] == key[first]; ++r) {
            g[order[r]] = g[first];
            std::copy(span, span + kSpanPerEdge, spans + size_t(order[r]) * kSpanPerEdge);
        }
    }
    return true;
}

bool triangle_bounds(const MeshView& domain, const MeshView& topology, Adjacency& adj,
                     const PointsView& points, const float* bind_area, const float* density,
                     const float* phase, TriangleBounds* b) {
    const uint32_t n = domain.triangle_count;
    b->spans = make_buffer<uint32_t>(size_t(n) * kSpanPerTriangle);
    b->lower = make_buffer<float>(size_t(n) * 2);
    b->terms = make_buffer<float>(size_t(n) * 3);
    b->shortest = make_buffer<float>(n);
    Buffer<float> paths = make_buffer<float>(size_t(n) * 3);
    if (!b->spans || !b->lower || !b->terms || !b->shortest || !paths ||
        !edge_paths(domain, topology, adj, points, paths.get(), b->spans.get()))
        return false;
    for (uint32_t t = 0; t < n; ++t) {
        const uint32_t* tri = domain.indices + size_t(t) * 3;
        glm::vec3 p[3];
        bool in = true;  // every corner in its host triangle (barycentric in [0, 1])
        for (int k = 0; k < 3; ++k) {
            p[k] = vertex(domain, tri[k]);
            const float u = points.bary_u[tri[k]], v = points.bary_v[tri[k]];
            in = in && u >= -1e-6f && v >= -1e-6f && 1.0f - u - v >= -1e-6f;
        }
        const glm::vec3 centre = (p[0] + p[1] + p[2]) / 3.0f;
        b->lo = glm::min(b->lo, centre);
        b->hi = glm::max(b->hi, centre);
        const float area = bind_area[t];
        b->area += area > 0.0f ? area : 0.0f;
        const float* g = paths.get() + size_t(t) * 3;
        const float pair = std::min({g[0] * g[1], g[0] * g[2], g[1] * g[2]});
        b->shortest[t] = std::min({g[0], g[1], g[2]});
        const float q = 0.5f * pair / area;  // posed area <= L^2 q bind area
        // Triangles the full stage skips (no bind area) bound nothing: +inf. A corner off its
        // host: -1, the cluster is never skipped.
        const float l = area > 0.0f ? density[t] + phase[t] / area : INFINITY;
        b->lower[size_t(t) * 2] = in ? l : -1.0f;
        b->lower[size_t(t) * 2 + 1] = !in ? -1.0f : area > 0.0f ? (q < INFINITY ? l / q : 0.0f) : l;
        // stretch_t <= s12 + 2 D s1 (|e1| + |e2|) / 2A + 4 D^2 / 2A (refinement_cull), over
        // lower_t: its three coefficients, the edges from the corner that makes them least.
        float edges = INFINITY;
        for (int o = 0; o < 3; ++o)
            edges = std::min(
                edges, glm::length(p[(o + 1) % 3] - p[o]) + glm::length(p[(o + 2) % 3] - p[o]));
        const bool counted = area > 0.0f && l < INFINITY;
        b->terms[size_t(t) * 3] = counted ? 1.0f / l : 0.0f;
        b->terms[size_t(t) * 3 + 1] = counted ? edges / (2.0f * area * l) : 0.0f;
        b->terms[size_t(t) * 3 + 2] = counted ? 1.0f / (2.0f * area * l) : 0.0f;
    }
    return true;
}

// Clusters: cells of a grid over the triangles' centres, ~kTrianglesPerCluster each; order
// lists the triangles cluster by cluster, tri_begin where each cluster starts.
bool cluster_triangles(const MeshView& domain, const TriangleBounds& b, RefinementCull* c,
                       Buffer<uint32_t>* order, Buffer<uint32_t>* tri_begin) {
    const uint32_t n = domain.triangle_count;
    Buffer<uint64_t> key = make_buffer<uint64_t>(n);
    if (!key || !alloc(order, n) || !alloc(tri_begin, size_t(n) + 1) ||
        !alloc(&c->triangle_cluster, n))
        return false;
    const double cells = std::max(1.0, double(n) / kTrianglesPerCluster);
    const float h = float(std::sqrt(std::max(b.area, 1e-30) / cells));
    const glm::vec3 extent = glm::max(b.hi - b.lo, glm::vec3(0.0f));
    const uint64_t ny = uint64_t(extent.y / h) + 1, nz = uint64_t(extent.z / h) + 1;
    for (uint32_t t = 0; t < n; ++t) {
        const uint32_t* tri = domain.indices + size_t(t) * 3;
        const glm::vec3 centre =
            (vertex(domain, tri[0]) + vertex(domain, tri[1]) + vertex(domain, tri[2])) / 3.0f;
        const glm::vec3 cell = glm::floor((centre - b.lo) / h);
        key[t] = (uint64_t(cell.x) * ny + uint64_t(cell.y)) * nz + uint64_t(cell.z);
        (*order)[t] = t;
    }
    std::sort(order->get(), order->get() + n,
              [&](uint32_t x, uint32_t y) { return key[x] != key[y] ? key[x] < key[y] : x < y; });
    uint32_t clusters = 0;
    for (uint32_t j = 0; j < n; ++j) {
        const uint32_t t = (*order)[j];
        if (j == 0 || key[t] != key[(*order)[j - 1]]) (*tri_begin)[clusters++] = j;
        c->triangle_cluster[t] = clusters - 1;
    }
    (*tri_begin)[clusters] = n;
    c->cluster_count = clusters;
    return true;
}

// Per cluster, the least and largest of its triangles' bounds.
void cluster_constants(RefinementCull* c, const TriangleBounds& b, const float* bind_area,
                       const uint32_t* order, const uint32_t* tri_begin) {
    for (uint32_t k = 0; k < c->cluster_count; ++k) {
        float rest = INFINITY, stretched = INFINITY, path = INFINITY, most[3] = {0, 0, 0};
        for (uint32_t j = tri_begin[k]; j < tri_begin[k + 1]; ++j) {
            const uint32_t t = order[j];
            rest = std::min(rest, b.lower[size_t(t) * 2]);
            // refinement_cull_posed's limit (a corner off its host, lower_t -1: the cluster
            // keeps no density bound, the limit is not read)
            c->cross_limit[j] =
                bind_area[t] > 0.0f ? 2.0f * bind_area[t] * b.lower[size_t(t) * 2] : INFINITY;
            stretched = std::min(stretched, b.lower[size_t(t) * 2 + 1]);
            for (int i = 0; i < 3; ++i) most[i] = std::max(most[i], b.terms[size_t(t) * 3 + i]);
            if (bind_area[t] > 0.0f) path = std::min(path, b.shortest[t]);
        }
        for (int i = 0; i < 3; ++i) c->affine[size_t(k) * 3 + i] = most[i] * (1.0f + kSlack);
        c->min_path[k] = path;
        c->lower_rest[k] = rest;
        c->lower_stretch[k] = stretched;
    }
}

}  // namespace

Status refinement_cull_init(RefinementCull* c, const MeshView& domain, const MeshView& host,
                            const PointsView& points, const float* bind_area, const float* density,
                            const float* phase) {
    *c = RefinementCull();
    const uint32_t n = domain.triangle_count;
    if (n == 0 || domain.vertex_count != points.point_count) return {};
    // Topology over welded vertices (seams split vertices that share a position).
    Buffer<uint32_t> welded = make_buffer<uint32_t>(size_t(host.triangle_count) * 3);
    if (!welded || !weld(host, welded.get(), &c->seam, &c->seam_count)) return no_memory(n);
    MeshView topology = host;
    topology.indices = welded.get();
    Adjacency adj;
    TriangleBounds b;
    Buffer<uint32_t>& order = c->triangles;
    Buffer<uint32_t>& tri_begin = c->tri_begin;
    if (!build_adjacency(topology, &adj) ||
        !triangle_bounds(domain, topology, adj, points, bind_area, density, phase, &b) ||
        !cluster_triangles(domain, b, c, &order, &tri_begin))
        return no_memory(n);
    const uint32_t clusters = c->cluster_count;
    c->point_count = points.point_count;
    const uint32_t* hi_idx = host.indices;
    const uint32_t* di = domain.indices;
    const uint32_t* host_of = points.host_triangle;
    const uint32_t* spans = b.spans.get();
    if (!collect(
            clusters, order.get(), tri_begin.get(), 9, host.vertex_count,
            [&](uint32_t t, uint32_t i) {
                return hi_idx[size_t(host_of[di[t * 3 + i / 3]]) * 3 + i % 3];
            },
            &c->host_begin, &c->host_vertex) ||
        !collect(
            clusters, order.get(), tri_begin.get(), kSpanPerTriangle, host.triangle_count,
            [&](uint32_t t, uint32_t i) { return spans[size_t(t) * kSpanPerTriangle + i]; },
            &c->span_begin, &c->span) ||
        !collect(
            clusters, order.get(), tri_begin.get(), 3, points.point_count,
            [&](uint32_t t, uint32_t i) { return di[size_t(t) * 3 + i]; }, &c->corner_begin,
            &c->corner))
        return no_memory(n);
    if (!alloc(&c->lower_stretch, clusters) || !alloc(&c->lower_rest, clusters) ||
        !alloc(&c->affine, size_t(clusters) * 3) || !alloc(&c->min_path, clusters) ||
        !alloc(&c->bind_gram, size_t(host.triangle_count) * 3) || !alloc(&c->active, clusters) ||
        !alloc(&c->ratio_bound, clusters) || !alloc(&c->probed, clusters) ||
        !alloc(&c->density_bound, clusters) || !alloc(&c->cross_limit, n) ||
        !alloc(&c->list, points.point_count) || !alloc(&c->candidate, n) ||
        !alloc(&c->active_list, clusters) || !alloc(&c->refine_list, n) ||
        !alloc(&c->sigma, host.triangle_count) || !alloc(&c->sigma_frame, host.triangle_count) ||
        !alloc(&c->sigma_todo, host.triangle_count) ||
        !alloc(&c->stamp, size_t(points.point_count) / 64 + 1))
        return no_memory(n);
    cluster_constants(c, b, bind_area, order.get(), tri_begin.get());
    for (uint32_t t = 0; t < host.triangle_count; ++t) {
        const uint32_t* tri = host.indices + size_t(t) * 3;
        const glm::vec3 a = vertex(host, tri[0]);
        const glm::vec3 e1 = vertex(host, tri[1]) - a, e2 = vertex(host, tri[2]) - a;
        float* gram = c->bind_gram.get() + size_t(t) * 3;
        gram[0] = glm::dot(e1, e1), gram[1] = glm::dot(e1, e2), gram[2] = glm::dot(e2, e2);
    }
    std::fill(c->stamp.get(), c->stamp.get() + points.point_count / 64 + 1, uint64_t(0));
    std::fill(c->sigma_frame.get(), c->sigma_frame.get() + host.triangle_count, 0u);
    return {};
}

}  // namespace stipple
