#include "bake/sample_ghosts.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <queue>
#include <utility>

#include "bake/point_hierarchy_nearest.h"
#include "bake/position_weld.h"
#include "runtime/asset_format.h"  // kNoFace

namespace stipple::bake::elimination {

namespace {

constexpr uint32_t kNoEdge = 0xFFFFFFFFu;

// The boundary edges seen from the triangles and samples near them.
struct EdgeGeometry {
    const Triangles& t;
    const Boundary& edges;

    // The point of edge e nearest to p; *h its parameter along the edge, in [0, 1].
    Vec3 segment_point(uint32_t e, const Vec3& p, double* h) const {
        const Vec3 ab = edges.b[e] - edges.a[e];
        const double len2 = ab.sqrnorm();
        *h = len2 > 0 ? std::clamp(((p - edges.a[e]) | ab) / len2, 0.0, 1.0) : 0.0;
        return edges.a[e] + ab * *h;
    }
    bool same_side(uint32_t f, uint32_t e) const {
        return (t.normal[f] | edges.face_normal[e]) > kSameSideDot;
    }
};

// Per triangle within `width` of the boundary over the surface, its nearest edge (from its
// centroid); and each triangle's own boundary edges.
struct NearestEdges {
    std::vector<uint32_t> label;      // per triangle; kNoEdge: farther than width
    std::vector<uint32_t> own_first;  // per triangle, its run in `own` (faces + 1 entries)
    std::vector<uint32_t> own;        // boundary edges, grouped by their face
};

// The nearest edge passed on from triangle to neighbouring triangle, nearest first
// (Dijkstra), so that another part that passes near an edge is not labelled with it.
NearestEdges nearest_edges(const EdgeGeometry& geo, double width) {
    const Triangles& t = geo.t;
    const Boundary& edges = geo.edges;
    const uint32_t faces = uint32_t(t.area.size());
    NearestEdges out;
    out.label.assign(faces, kNoEdge);
    std::vector<double> reach(faces, 0), best(faces, 1e300);
    std::vector<Vec3> centre(faces);
    for (uint32_t f = 0; f < faces; ++f) {
        const Vec3* c = &t.corner[size_t(f) * 3];
        centre[f] = (c[0] + c[1] + c[2]) / 3;
        reach[f] = width + std::max({(c[0] - centre[f]).norm(), (c[1] - centre[f]).norm(),
                                     (c[2] - centre[f]).norm()});
    }
    using Entry = std::pair<double, uint32_t>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> open;
    std::vector<uint32_t>& label = out.label;
    auto offer = [&](uint32_t f, uint32_t e) {
        if (!(t.area[f] > 0) || !geo.same_side(f, e)) return;
        double h;
        const double d = (geo.segment_point(e, centre[f], &h) - centre[f]).norm();
        if (d > reach[f] || d > best[f] || (d == best[f] && e >= label[f])) return;
        best[f] = d;
        label[f] = e;
        open.push({d, f});
    };
    out.own_first.assign(size_t(faces) + 1, 0);
    out.own.resize(edges.size());
    for (uint32_t e = 0; e < edges.size(); ++e) ++out.own_first[edges.face[e] + 1];
    for (uint32_t f = 0; f < faces; ++f) out.own_first[f + 1] += out.own_first[f];
    {
        std::vector<uint32_t> at(out.own_first.begin(), out.own_first.end() - 1);
        for (uint32_t e = 0; e < edges.size(); ++e) out.own[at[edges.face[e]]++] = e;
    }
    for (uint32_t e = 0; e < edges.size(); ++e) offer(edges.face[e], e);
    while (!open.empty()) {
        const auto [d, f] = open.top();
        open.pop();
        if (d != best[f]) continue;
        for (int k = 0; k < 3; ++k) {
            const uint32_t g = edges.across[size_t(f) * 3 + size_t(k)];
            if (g != format::kNoFace) offer(g, label[f]);
        }
    }
    return out;
}

// The real samples that may hide a ghost: the samples thinned to a spacing of about
// width / 8 (every m-th of the systematic sampling is an even sampling too), in a kd-tree;
// and the edges cut into pieces at most width / 2 long, whose midpoints bound how far from
// its piece a ghost looks. (A list per piece of the samples beyond its plane, as before, holds
// O(samples) entries per piece where much surface crowds a little volume, as around the
// edge of a non-manifold star: quadratic. The tree answers the same question per ghost.)
struct Hiders {
    std::vector<uint32_t> first_piece;  // per edge, its run of pieces (edges + 1 entries)
    std::vector<double> piece_xyz;      // the pieces' midpoints, 3 each
    std::vector<double> thin_xyz;       // the thinned samples, 3 each
    std::vector<uint32_t> thin_host;
    NearestPoints tree;  // over thin_xyz
    // Per edge: more thinned samples near its midpoint than many sheets of surface put there
    // (kCrowdedSheets): much surface in little volume, the rim of a non-manifold star. It
    // gets no pieces and its ghosts are dropped: the surface there is crowded by other
    // surface anyway, and testing them would cost O(samples) each.
    std::vector<uint8_t> crowded;
    double slack = 0;  // their spacing
    double look = 0;   // a ghost's hiders lie within this of its piece's midpoint
};

// A sheet of surface through a ball of radius 4 slack holds about 16 pi thinned samples;
// more than kCrowdedSheets times that around an edge's midpoint is crowded.
constexpr double kCrowdedSheets = 16;

void crowded_edges(const Boundary& edges, Hiders* h) {
    h->crowded.assign(edges.size(), 0);
    if (h->thin_host.empty()) return;
    const double radius = std::min(h->look, 4 * h->slack);
    const double ratio = radius / h->slack;
    const uint32_t limit = uint32_t(kCrowdedSheets * 3.14159 * ratio * ratio);
    for (uint32_t e = 0; e < edges.size(); ++e) {
        const Vec3 mid = (edges.a[e] + edges.b[e]) * 0.5;
        h->crowded[e] = h->tree.count_within(mid.data(), radius * radius, limit) > limit;
    }
}

// The uncrowded edges cut into pieces: their midpoints, 3 each; first_piece per edge.
void edge_pieces(const Boundary& edges, double width, Hiders* hiders) {
    hiders->first_piece.assign(size_t(edges.size()) + 1, 0);
    for (uint32_t e = 0; e < edges.size(); ++e) {
        const Vec3 ab = edges.b[e] - edges.a[e];
        const uint32_t k =
            hiders->crowded[e] ? 0 : uint32_t(std::max(1.0, std::ceil(ab.norm() / (0.5 * width))));
        for (uint32_t q = 0; q < k; ++q) {
            const Vec3 c = edges.a[e] + ab * ((q + 0.5) / k);
            hiders->piece_xyz.insert(hiders->piece_xyz.end(), {c[0], c[1], c[2]});
        }
        hiders->first_piece[e + 1] = hiders->first_piece[e] + k;
    }
}

void hiders_of(const EdgeGeometry& geo, const Samples& s, double width, Hiders* out) {
    const uint32_t n = s.size();
    const uint32_t stride =
        uint32_t(std::max(1.0, std::floor(double(n) / (64 * geo.t.total / (width * width)))));
    out->slack = std::sqrt(geo.t.total * stride / double(n));
    for (uint32_t i = 0; i < n; i += stride) {
        out->thin_host.push_back(s.host[i]);
        out->thin_xyz.insert(out->thin_xyz.end(), s.xyz.begin() + std::ptrdiff_t(i) * 3,
                             s.xyz.begin() + std::ptrdiff_t(i) * 3 + 3);
    }
    // A ghost is within 1.04 width of its piece's midpoint, and looks as far as width + slack.
    out->look = 2.05 * width + out->slack;
    out->tree.build(out->thin_xyz.data(), uint32_t(out->thin_host.size()));
    crowded_edges(geo.edges, out);
    edge_pieces(geo.edges, width, out);
}

// The nearest of the `candidates` edges to p (in triangle f) within `width` that bounds the
// surface p is on; kNoEdge if none. *edge_h gets its parameter along the edge.
uint32_t nearest_candidate(const EdgeGeometry& geo, uint32_t f, const Vec3& p,
                           const std::vector<uint32_t>& candidates, double width, double* edge_h) {
    const Boundary& edges = geo.edges;
    uint32_t edge = kNoEdge;
    double edge_d2 = width * width;
    *edge_h = 0;
    for (uint32_t e : candidates) {
        if (!geo.same_side(f, e)) continue;
        double h;
        const Vec3 v = p - geo.segment_point(e, p, &h);
        const double d2 = v.sqrnorm();
        if (d2 > edge_d2 || (d2 == edge_d2 && e >= edge)) continue;
        if (-(v | edges.out[e]) + 1e-9 * width < std::fabs(v | edges.face_normal[e]))
            continue;  // not on the surface this edge bounds
        edge = e;
        edge_d2 = d2;
        *edge_h = h;
    }
    return edge;
}

// Is the ghost g, `depth` beyond the plane of `edge` at parameter edge_h, on a real surface
// there? A thinned real sample near its piece (within `look` of the midpoint), on its side of
// the surface and beyond the plane (by less than 2 depth + slack: nearer it cannot hide it),
// lies nearer to g than depth + slack.
bool is_hidden(const EdgeGeometry& geo, const Hiders& hiders, uint32_t edge, double edge_h,
               double depth, double width, const Vec3& g) {
    const Boundary& edges = geo.edges;
    if (hiders.crowded[edge]) return true;
    const uint32_t pieces = hiders.first_piece[edge + 1] - hiders.first_piece[edge];
    const uint32_t k = hiders.first_piece[edge] + std::min(pieces - 1, uint32_t(edge_h * pieces));
    const Vec3 mid(hiders.piece_xyz[size_t(k) * 3], hiders.piece_xyz[size_t(k) * 3 + 1],
                   hiders.piece_xyz[size_t(k) * 3 + 2]);
    const double reach = depth + hiders.slack;
    return hiders.tree.any(g.data(), reach * reach * (1 + 1e-9), [&](uint32_t j) {
        const size_t r3 = size_t(j) * 3;
        const Vec3 r(hiders.thin_xyz[r3], hiders.thin_xyz[r3 + 1], hiders.thin_xyz[r3 + 2]);
        const double past = (r - edges.a[edge]) | edges.out[edge];
        return past > 1e-9 * width && past < 2 * depth + hiders.slack &&
               geo.same_side(hiders.thin_host[j], edge) &&
               (r - mid).sqrnorm() <= hiders.look * hiders.look && (r - g).norm() < reach;
    });
}

// The edges a sample of triangle f may be mirrored across: the triangle's own boundary
// edges, its label and its neighbours' labels.
void candidate_edges(const Boundary& edges, const NearestEdges& near, uint32_t f,
                     std::vector<uint32_t>* candidates) {
    candidates->assign(near.own.begin() + near.own_first[f],
                       near.own.begin() + near.own_first[f + 1]);
    candidates->push_back(near.label[f]);
    for (int k = 0; k < 3; ++k) {
        const uint32_t g = edges.across[size_t(f) * 3 + size_t(k)];
        if (g != format::kNoFace && near.label[g] != kNoEdge) candidates->push_back(near.label[g]);
    }
}

}  // namespace

Boundary boundary_of(const RawScene& s, const Triangles& t) {
    Boundary e;
    const uint32_t faces = uint32_t(s.triangle_count());
    const std::vector<uint32_t> welded = weld_by_position(s);
    // Every edge of positive length: how many faces it has, and the first two.
    struct Slot {
        uint64_t key = ~0ull;
        uint32_t first = 0, second = 0, count = 0;
    };
    std::vector<Slot> table(hash_table_size(size_t(faces) * 3 / 2 + 1));
    const size_t mask = table.size() - 1;
    // Pass 1: count; pass 2 (in face order): boundary edges and the faces across.
    std::vector<uint32_t> at(size_t(faces) * 3, 0xFFFFFFFFu);
    for (uint32_t f = 0; f < faces; ++f)
        for (int k = 0; k < 3; ++k) {
            const uint32_t a = welded[s.indices[size_t(f) * 3 + size_t(k)]];
            const uint32_t b = welded[s.indices[size_t(f) * 3 + size_t((k + 1) % 3)]];
            if (a == b) continue;
            const uint64_t key = uint64_t(std::min(a, b)) << 32 | std::max(a, b);
            size_t h = size_t(hash_mix(key)) & mask;
            while (table[h].count && table[h].key != key) h = (h + 1) & mask;
            Slot& x = table[h];
            x.key = key;
            if (x.count == 0) x.first = f;
            if (x.count == 1) x.second = f;
            ++x.count;
            at[size_t(f) * 3 + size_t(k)] = uint32_t(h);
        }
    std::vector<uint32_t> across(size_t(faces) * 3, format::kNoFace);
    for (uint32_t f = 0; f < faces; ++f)
        for (int k = 0; k < 3; ++k) {
            if (at[size_t(f) * 3 + size_t(k)] == 0xFFFFFFFFu) continue;
            const Slot& x = table[at[size_t(f) * 3 + size_t(k)]];
            if (x.count == 2) {  // manifold: the face across
                across[size_t(f) * 3 + size_t(k)] = x.first == f ? x.second : x.first;
                continue;
            }
            if (x.count != 1) continue;  // non-manifold: neither boundary nor across
            const Vec3 n = t.normal[f];
            if (!(n.sqrnorm() > 0)) continue;
            const Vec3* c = &t.corner[size_t(f) * 3];
            const Vec3 a = c[k], b = c[(k + 1) % 3];
            Vec3 out = (b - a) % n;
            if (!(out.norm() > 0)) continue;
            out /= out.norm();
            if ((out | ((c[0] + c[1] + c[2]) / 3 - a)) > 0) out = -out;
            e.a.push_back(a);
            e.b.push_back(b);
            e.out.push_back(out);
            e.face_normal.push_back(n);
            e.face.push_back(f);
            e.length += (b - a).norm();
        }
    if (e.size() > 0) e.across = std::move(across);
    return e;
}

void add_ghosts(const Triangles& t, const Boundary& edges, double density, double width, Rng* rng,
                Samples* s) {
    if (edges.size() == 0 || !(width > 0)) return;
    const EdgeGeometry geo{t, edges};
    const NearestEdges near = nearest_edges(geo, width);
    Hiders hiders;
    hiders_of(geo, *s, width, &hiders);
    // The sources: systematic sampling over the triangles near the boundary, then mirrored.
    const double offset = rng->uniform();
    double running = 0;
    uint64_t made = 0;
    std::vector<uint32_t> candidates;
    for (uint32_t f = 0; f < uint32_t(t.area.size()); ++f) {
        if (near.label[f] == kNoEdge) continue;
        running += t.area[f] * density;
        const uint64_t upto = uint64_t(std::floor(running + offset));
        candidate_edges(edges, near, f, &candidates);
        const Vec3* corner = &t.corner[size_t(f) * 3];
        for (; made < upto; ++made) {
            const double r1 = std::sqrt(rng->uniform()), r2 = rng->uniform();
            const double a = 1 - r1, b = r1 * (1 - r2);
            const Vec3 p = corner[0] * a + corner[1] * b + corner[2] * (1 - a - b);
            double edge_h = 0;
            const uint32_t edge = nearest_candidate(geo, f, p, candidates, width, &edge_h);
            if (edge == kNoEdge) continue;
            const double depth = -((p - edges.a[edge]) | edges.out[edge]);
            const Vec3 g = p + edges.out[edge] * (2 * depth);
            if (is_hidden(geo, hiders, edge, edge_h, depth, width, g)) continue;
            s->xyz.insert(s->xyz.end(), {g[0], g[1], g[2]});
            s->host.push_back(f);
            s->u.push_back(float(a));
            s->v.push_back(float(b));
            s->ghost.push_back(1);
        }
    }
}

constexpr double kGhostSpacings = 2, kGhostPrefix = 512;

double ghost_width(double area, double boundary_length, uint32_t points) {
    const double w = kGhostSpacings * std::sqrt(area / std::min(double(points), kGhostPrefix));
    return std::min(w, 0.5 * area / boundary_length);
}

}  // namespace stipple::bake::elimination
