#include "bake/sample_elimination.h"

#include <OpenMesh/Core/Geometry/VectorT.hh>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <functional>
#include <queue>
#include <utility>

#include "bake/bake_random.h"
#include "bake/level_order.h"
#include "bake/point_grid.h"
#include "runtime/asset_format.h"  // kNoFace

namespace stipple::bake {

namespace {

using Vec3 = OpenMesh::Vec3d;

// Yuksel 2015, weighted sample elimination: sample i weighs the sum over j of
// (1 - d_ij / (2 r_max))^alpha, alpha = 8, for d_ij < 2 r_max, where r_max =
// sqrt(A / (2 sqrt(3) N)) is the disk radius of the densest packing of N disks on area A (a
// 2D domain: the surface); weight limiting: distances under 2 r_min, r_min = r_max (1 -
// (N / M)^gamma) beta, count as 2 r_min (the paper's defaults, as in its cySampleElimination).
constexpr double kBeta = 0.65, kGamma = 1.5;  // alpha = 8: weight_between squares thrice
// Candidates per point. More make the finest level more even and leave the coarser ones as
// they are (nn CV of all 20k points, bunny: 3 -> 0.091, 4 -> 0.078, 5 -> 0.071; 1k-12k
// points: 0.10-0.13 for all three); 4 is the middle ground for time and memory.
constexpr uint64_t kOversampling = 4;
// Memory at the first elimination is ~140 bytes per candidate: past 2M points, the
// candidates stay at this many, or 2 per point if that is more.
constexpr uint64_t kCandidateCap = 8000000;
// Normals more than ~120 degrees apart: the two sides of a thin sheet (an ear, a fin),
// which must each get their own points, so they neither repel nor are neighbours.
constexpr double kSameSideDot = -0.5;

struct Triangles {
    std::vector<Vec3> corner;  // 3 per triangle
    std::vector<Vec3> normal;  // unit, 0 if degenerate
    std::vector<double> area;
    double total = 0;
};

Triangles triangles_of(const RawScene& s) {
    Triangles t;
    const uint32_t n = s.triangle_count();
    t.corner.resize(size_t(n) * 3);
    t.normal.resize(n);
    t.area.resize(n);
    for (uint32_t f = 0; f < n; ++f) {
        for (int k = 0; k < 3; ++k) {
            const float* p = &s.positions[size_t(s.indices[size_t(f) * 3 + size_t(k)]) * 3];
            t.corner[size_t(f) * 3 + size_t(k)] = Vec3(p[0], p[1], p[2]);
        }
        const Vec3* c = &t.corner[size_t(f) * 3];
        const Vec3 cross = (c[1] - c[0]) % (c[2] - c[0]);
        const double len = cross.norm();
        t.normal[f] = len > 0 ? cross / len : Vec3(0, 0, 0);
        t.area[f] = 0.5 * len;
        t.total += t.area[f];
    }
    return t;
}

// Samples on the input surface, structure of arrays.
struct Samples {
    std::vector<double> xyz;  // 3 per sample
    std::vector<uint32_t> host;
    std::vector<float> u, v;  // barycentric weights of the host's 1st and 2nd corner
    // 1: a sample of the surface continued across its boundary (add_ghosts), never a point.
    std::vector<uint8_t> ghost;
    uint32_t size() const { return uint32_t(host.size()); }
    uint32_t reals() const {
        return size() - uint32_t(std::count(ghost.begin(), ghost.end(), uint8_t(1)));
    }
    void reserve(size_t n) {
        xyz.reserve(n * 3);
        host.reserve(n);
        u.reserve(n);
        v.reserve(n);
        ghost.reserve(n);
    }
    void push(const Samples& from, uint32_t i) {
        xyz.insert(xyz.end(), from.xyz.begin() + std::ptrdiff_t(i) * 3,
                   from.xyz.begin() + std::ptrdiff_t(i) * 3 + 3);
        host.push_back(from.host[i]);
        u.push_back(from.u[i]);
        v.push_back(from.v[i]);
        ghost.push_back(from.ghost[i]);
    }
    // Keeps sample order[k] at k (order: a permutation of a subset).
    void select(const std::vector<uint32_t>& order) {
        Samples s;
        s.reserve(order.size());
        for (uint32_t i : order) s.push(*this, i);
        *this = std::move(s);
    }
};

// `count` samples uniform in area: triangle t gets floor or ceil of count * area_t / A
// (systematic sampling along the running sum of areas, one random offset), each uniform
// inside its triangle. Stratifying by triangle keeps the samples' density even at the
// scale of the triangles, which elimination would otherwise have to repair.
Samples sample_surface(const Triangles& t, uint64_t count, Rng* rng) {
    Samples c;
    c.reserve(count);
    const double scale = double(count) / t.total, offset = rng->uniform();
    double running = 0;
    uint64_t made = 0;
    for (uint32_t f = 0; f < uint32_t(t.area.size()); ++f) {
        running += t.area[f] * scale;
        const uint64_t upto = std::min<uint64_t>(count, uint64_t(std::floor(running + offset)));
        const Vec3* corner = &t.corner[size_t(f) * 3];
        for (; made < upto; ++made) {
            const double r1 = std::sqrt(rng->uniform()), r2 = rng->uniform();
            const double a = 1 - r1, b = r1 * (1 - r2);
            const Vec3 p = corner[0] * a + corner[1] * b + corner[2] * (1 - a - b);
            c.xyz.insert(c.xyz.end(), {p[0], p[1], p[2]});
            c.host.push_back(f);
            c.u.push_back(float(a));
            c.v.push_back(float(b));
            c.ghost.push_back(0);
        }
    }
    return c;
}

// Open surfaces. Where a surface ends, its samples have fewer neighbours, weigh less and
// outlive the others: every prefix is denser along the boundary (a plane at 20k points:
// 1.5-1.7x the mean density within half a spacing of its border, docs/hierarchy.md). Yuksel
// 2015 notes this for bounded domains. Here the surface is continued across its boundary,
// `width` deep, by its mirror image, sampled independently: "ghost" samples, eliminated like
// the others, that never become points. The samples near a boundary then have the
// neighbours they would have if the surface went on. (Mirroring the real samples instead,
// in their weights, is not enough: a sample sees its neighbours' images but not its own, so
// the samples on the edge, whose images are themselves, count double for their neighbours
// and crowd the edge (4.8x within 1/8 spacing); counting its own image too empties a band of
// a quarter spacing along the edge. Measured, docs/hierarchy.md.)
//
// The boundary: the edges of one face once the input is welded by exact position (as
// bake/silhouette_edges.h does, so UV and normal seams are not edges of one face). Each has the
// unit direction in its face's plane, perpendicular to the edge, pointing away from the
// face: the normal of the plane the surface near it is mirrored across. Degenerate faces'
// edges are left out (no direction; they have no samples).
struct Boundary {
    std::vector<Vec3> a, b, out, face_normal;
    std::vector<uint32_t> face;
    double length = 0;
    // Per triangle, the triangles across its edges (kNoFace: none), 3 each; only if there
    // is a boundary.
    std::vector<uint32_t> across;
    uint32_t size() const { return uint32_t(a.size()); }
};

// Open-addressing hash tables (linear probing) for welding and edge matching: O(n), and the
// results do not depend on the table's order (everything is emitted in face order).
uint64_t mix(uint64_t x) {
    x ^= x >> 33;
    x *= 0xFF51AFD7ED558CCDull;
    x ^= x >> 33;
    x *= 0xC4CEB9FE1A85EC53ull;
    return x ^ (x >> 33);
}

size_t table_size(size_t n) {
    size_t size = 16;
    while (size < 2 * n) size *= 2;
    return size;
}

// Vertex classes by exact position (-0 and +0 alike), as bake/silhouette_edges.h welds.
std::vector<uint32_t> weld_by_position(const RawScene& s) {
    const size_t n = s.vertex_count();
    struct Slot {
        uint32_t bits[3];
        uint32_t id = 0xFFFFFFFFu;
    };
    std::vector<Slot> table(table_size(n));
    const size_t mask = table.size() - 1;
    std::vector<uint32_t> welded(n);
    uint32_t next = 0;
    for (size_t v = 0; v < n; ++v) {
        uint32_t bits[3];
        for (int k = 0; k < 3; ++k) {
            const float x = s.positions[v * 3 + size_t(k)] + 0.0f;  // -0 -> +0
            std::memcpy(&bits[k], &x, 4);
        }
        size_t h = size_t(mix(uint64_t(bits[0]) << 32 ^ uint64_t(bits[1]) << 16 ^ bits[2])) & mask;
        while (table[h].id != 0xFFFFFFFFu &&
               !(table[h].bits[0] == bits[0] && table[h].bits[1] == bits[1] &&
                 table[h].bits[2] == bits[2]))
            h = (h + 1) & mask;
        if (table[h].id == 0xFFFFFFFFu) {
            std::memcpy(table[h].bits, bits, sizeof bits);
            table[h].id = next++;
        }
        welded[v] = table[h].id;
    }
    return welded;
}

Boundary boundary_of(const RawScene& s, const Triangles& t) {
    Boundary e;
    const uint32_t faces = uint32_t(s.triangle_count());
    const std::vector<uint32_t> welded = weld_by_position(s);
    // Every edge of positive length: how many faces it has, and the first two.
    struct Slot {
        uint64_t key = ~0ull;
        uint32_t first = 0, second = 0, count = 0;
    };
    std::vector<Slot> table(table_size(size_t(faces) * 3 / 2 + 1));
    const size_t mask = table.size() - 1;
    // Pass 1: count; pass 2 (in face order): boundary edges and the faces across.
    std::vector<uint32_t> at(size_t(faces) * 3, 0xFFFFFFFFu);
    for (uint32_t f = 0; f < faces; ++f)
        for (int k = 0; k < 3; ++k) {
            const uint32_t a = welded[s.indices[size_t(f) * 3 + size_t(k)]];
            const uint32_t b = welded[s.indices[size_t(f) * 3 + size_t((k + 1) % 3)]];
            if (a == b) continue;
            const uint64_t key = uint64_t(std::min(a, b)) << 32 | std::max(a, b);
            size_t h = size_t(mix(key)) & mask;
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

constexpr uint32_t kNoEdge = 0xFFFFFFFFu;

// Appends to *s the ghosts of the boundary: samples at `density` per unit area, uniform on
// the triangles within `width` of a boundary edge (the same systematic sampling as the
// surface's, with their own random numbers), each mirrored across the plane of its nearest
// boundary edge. Nearest over the surface: each triangle near the boundary gets the edge
// nearest to its centroid, passed on from triangle to neighbouring triangle (nearest first,
// Dijkstra), so that another part that passes near an edge is not mirrored; a sample takes
// the nearest of its triangle's, its neighbours' and its own boundary edges. Edges count only
// on the sample's side of the surface (normals less than ~120 degrees apart) and within 45
// degrees of the edge's face's inward direction. A ghost is dropped where a real sample lies
// beyond the plane nearer to it than the plane (give or take the spacing of the samples
// tested): there the surface goes on (a crack, a part that meets another, a concave corner,
// the far side of a hole), and the mirror image would lie on it.
void add_ghosts(const Triangles& t, const Boundary& edges, double density, double width, Rng* rng,
                Samples* s) {
    if (edges.size() == 0 || !(width > 0)) return;
    const uint32_t faces = uint32_t(t.area.size());
    auto segment_point = [&](uint32_t e, const Vec3& p, double* h) {
        const Vec3 ab = edges.b[e] - edges.a[e];
        const double len2 = ab.sqrnorm();
        *h = len2 > 0 ? std::clamp(((p - edges.a[e]) | ab) / len2, 0.0, 1.0) : 0.0;
        return edges.a[e] + ab * *h;
    };
    auto same_side = [&](uint32_t f, uint32_t e) {
        return (t.normal[f] | edges.face_normal[e]) > kSameSideDot;
    };
    // Triangles within `width` of the boundary over the surface, each with its edge.
    std::vector<uint32_t> label(faces, kNoEdge);
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
    auto offer = [&](uint32_t f, uint32_t e) {
        if (!(t.area[f] > 0) || !same_side(f, e)) return;
        double h;
        const double d = (segment_point(e, centre[f], &h) - centre[f]).norm();
        if (d > reach[f] || d > best[f] || (d == best[f] && e >= label[f])) return;
        best[f] = d;
        label[f] = e;
        open.push({d, f});
    };
    std::vector<uint32_t> own_first(size_t(faces) + 1, 0), own(edges.size());
    for (uint32_t e = 0; e < edges.size(); ++e) ++own_first[edges.face[e] + 1];
    for (uint32_t f = 0; f < faces; ++f) own_first[f + 1] += own_first[f];
    {
        std::vector<uint32_t> at(own_first.begin(), own_first.end() - 1);
        for (uint32_t e = 0; e < edges.size(); ++e) own[at[edges.face[e]]++] = e;
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
    // The edges cut into pieces at most width / 2 long, each with the real samples beyond
    // its plane that could hide one of its ghosts: the samples thinned to a spacing of
    // about width / 8 (every m-th of the systematic sampling is an even sampling too).
    std::vector<double> piece_xyz;
    std::vector<uint32_t> first_piece(size_t(edges.size()) + 1, 0);
    for (uint32_t e = 0; e < edges.size(); ++e) {
        const Vec3 ab = edges.b[e] - edges.a[e];
        const uint32_t k = uint32_t(std::max(1.0, std::ceil(ab.norm() / (0.5 * width))));
        for (uint32_t q = 0; q < k; ++q) {
            const Vec3 c = edges.a[e] + ab * ((q + 0.5) / k);
            piece_xyz.insert(piece_xyz.end(), {c[0], c[1], c[2]});
        }
        first_piece[e + 1] = first_piece[e] + k;
    }
    const uint32_t n = s->size();
    const uint32_t stride =
        uint32_t(std::max(1.0, std::floor(double(n) / (64 * t.total / (width * width)))));
    const double slack = std::sqrt(t.total * stride / double(n));
    std::vector<double> thin_xyz;
    std::vector<uint32_t> thin_host;
    for (uint32_t i = 0; i < n; i += stride) {
        thin_host.push_back(s->host[i]);
        thin_xyz.insert(thin_xyz.end(), s->xyz.begin() + std::ptrdiff_t(i) * 3,
                        s->xyz.begin() + std::ptrdiff_t(i) * 3 + 3);
    }
    // A ghost is within 1.04 width of its piece's midpoint, and looks as far as width + slack.
    const double look = 2.05 * width + slack;
    PointGrid thinned;
    thinned.build(thin_xyz.data(), uint32_t(thin_host.size()), look);
    // Each piece's list is sorted by the distance beyond the plane: a ghost `depth` beyond it
    // is hidden only by samples less than 2 depth + slack beyond.
    std::vector<uint32_t> beyond_first(size_t(first_piece.back()) + 1, 0);
    std::vector<std::pair<double, uint32_t>> beyond;
    for (uint32_t e = 0; e < edges.size(); ++e)
        for (uint32_t k = first_piece[e]; k < first_piece[e + 1]; ++k) {
            const Vec3 mid(piece_xyz[size_t(k) * 3], piece_xyz[size_t(k) * 3 + 1],
                           piece_xyz[size_t(k) * 3 + 2]);
            thinned.visit(&piece_xyz[size_t(k) * 3], 1, [&](uint32_t j) {
                const Vec3 r(thin_xyz[size_t(j) * 3], thin_xyz[size_t(j) * 3 + 1],
                             thin_xyz[size_t(j) * 3 + 2]);
                const double past = (r - edges.a[e]) | edges.out[e];
                if (past > 1e-9 * width && same_side(thin_host[j], e) &&
                    (r - mid).sqrnorm() <= look * look)
                    beyond.push_back({past, j});
            });
            std::sort(beyond.begin() + beyond_first[k], beyond.end());
            beyond_first[k + 1] = uint32_t(beyond.size());
        }
    // The sources: systematic sampling over the triangles near the boundary, then mirrored.
    const double offset = rng->uniform();
    double running = 0;
    uint64_t made = 0;
    std::vector<uint32_t> candidates;
    for (uint32_t f = 0; f < faces; ++f) {
        if (label[f] == kNoEdge) continue;
        running += t.area[f] * density;
        const uint64_t upto = uint64_t(std::floor(running + offset));
        candidates.assign(own.begin() + own_first[f], own.begin() + own_first[f + 1]);
        candidates.push_back(label[f]);
        for (int k = 0; k < 3; ++k) {
            const uint32_t g = edges.across[size_t(f) * 3 + size_t(k)];
            if (g != format::kNoFace && label[g] != kNoEdge) candidates.push_back(label[g]);
        }
        const Vec3* corner = &t.corner[size_t(f) * 3];
        for (; made < upto; ++made) {
            const double r1 = std::sqrt(rng->uniform()), r2 = rng->uniform();
            const double a = 1 - r1, b = r1 * (1 - r2);
            const Vec3 p = corner[0] * a + corner[1] * b + corner[2] * (1 - a - b);
            uint32_t edge = kNoEdge;
            double edge_d2 = width * width, edge_h = 0;
            for (uint32_t e : candidates) {
                if (!same_side(f, e)) continue;
                double h;
                const Vec3 v = p - segment_point(e, p, &h);
                const double d2 = v.sqrnorm();
                if (d2 > edge_d2 || (d2 == edge_d2 && e >= edge)) continue;
                if (-(v | edges.out[e]) + 1e-9 * width < std::fabs(v | edges.face_normal[e]))
                    continue;  // not on the surface this edge bounds
                edge = e;
                edge_d2 = d2;
                edge_h = h;
            }
            if (edge == kNoEdge) continue;
            const double depth = -((p - edges.a[edge]) | edges.out[edge]);
            const Vec3 g = p + edges.out[edge] * (2 * depth);
            const uint32_t pieces = first_piece[edge + 1] - first_piece[edge];
            const uint32_t k = first_piece[edge] + std::min(pieces - 1, uint32_t(edge_h * pieces));
            bool hidden = false;
            for (uint32_t j = beyond_first[k];
                 j < beyond_first[k + 1] && beyond[j].first < 2 * depth + slack && !hidden; ++j) {
                const size_t r = size_t(beyond[j].second) * 3;
                hidden = (Vec3(thin_xyz[r], thin_xyz[r + 1], thin_xyz[r + 2]) - g).norm() <
                         depth + slack;
            }
            if (hidden) continue;
            s->xyz.insert(s->xyz.end(), {g[0], g[1], g[2]});
            s->host.push_back(f);
            s->u.push_back(float(a));
            s->v.push_back(float(b));
            s->ghost.push_back(1);
        }
    }
}

// Max-heap of samples by weight (ties: the higher index first, so the result does not
// depend on the standard library), with the position of each sample for decrease-key. The
// weights live in the heap's entries, so a sift reads neighbouring memory, not a weight
// array at random; 4-ary: a node's children share a cache line, and the heap is half as
// deep as a binary one. (Measured at 1M points, 4M samples: elimination 25 % faster than
// with a binary heap over a weight array; a lazy heap that re-sifts stale tops instead of
// sifting every lowered neighbour is 35 % slower.)
class WeightHeap {
  public:
    explicit WeightHeap(const std::vector<double>& weight) {
        const uint32_t n = uint32_t(weight.size());
        heap_.resize(n);
        at_.resize(n);
        for (uint32_t i = 0; i < n; ++i) {
            heap_[i] = Entry{weight[i], i};
            at_[i] = i;
        }
        for (size_t k = n / 4 + 1; k-- > 0;) sift_down(k);
    }
    uint32_t pop() {
        const uint32_t top = heap_[0].id;
        const Entry last = heap_.back();
        heap_.pop_back();
        if (!heap_.empty()) {
            heap_[0] = last;
            at_[last.id] = 0;
            sift_down(0);
        }
        return top;
    }
    // Weights only fall as neighbours go.
    void lower(uint32_t i, double by) {
        const uint32_t k = at_[i];
        heap_[k].weight -= by;
        sift_down(k);
    }

  private:
    struct alignas(16) Entry {
        double weight;
        uint32_t id;
    };
    static bool above(const Entry& a, const Entry& b) {
        return a.weight > b.weight || (a.weight == b.weight && a.id > b.id);
    }
    void sift_down(size_t k) {
        const Entry e = heap_[k];
        const size_t n = heap_.size();
        for (;;) {
            const size_t first = 4 * k + 1;
            if (first >= n) break;
            size_t child = first;
            for (size_t c = first + 1; c < std::min(first + 4, n); ++c)
                if (above(heap_[c], heap_[child])) child = c;
            if (!above(heap_[child], e)) break;
            heap_[k] = heap_[child];
            at_[heap_[k].id] = uint32_t(k);
            k = child;
        }
        heap_[k] = e;
        at_[e.id] = uint32_t(k);
    }
    std::vector<Entry> heap_;
    std::vector<uint32_t> at_;
};

// Spreads the low 21 bits of x to every third bit (a Morton code's one coordinate).
uint64_t spread_bits(uint64_t x) {
    x &= 0x1FFFFF;
    x = (x | x << 32) & 0x1F00000000FFFFull;
    x = (x | x << 16) & 0x1F0000FF0000FFull;
    x = (x | x << 8) & 0x100F00F00F00F00Full;
    x = (x | x << 4) & 0x10C30C30C30C30C3ull;
    x = (x | x << 2) & 0x1249249249249249ull;
    return x;
}

// Reorders the samples by the cell of a grid of size `cell` they fall in, cells in Morton
// order (ties keep their order), so that samples near on the surface are near in memory
// during an elimination (measured: a few per cent faster than cells in row order).
void sort_by_cell(double cell, Samples* s) {
    const uint32_t n = s->size();
    double lo[3] = {1e300, 1e300, 1e300};
    for (uint32_t i = 0; i < n; ++i)
        for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], s->xyz[size_t(i) * 3 + size_t(k)]);
    std::vector<std::pair<uint64_t, uint32_t>> keyed(n);
    for (uint32_t i = 0; i < n; ++i) {
        uint64_t key = 0;
        for (int k = 0; k < 3; ++k) {
            const double x = std::floor((s->xyz[size_t(i) * 3 + size_t(k)] - lo[k]) / cell);
            key |= spread_bits(uint64_t(std::min(x, 2097151.0))) << k;
        }
        keyed[i] = {key, i};
    }
    std::sort(keyed.begin(), keyed.end());
    std::vector<uint32_t> order(n);
    for (uint32_t i = 0; i < n; ++i) order[i] = keyed[i].second;
    s->select(order);
}

// One elimination (Yuksel 2015, the greedy algorithm with a heap): from the samples *s down to
// `target` real ones, the one of largest weight first, subtracting its contribution from its
// neighbours' weights. Ghosts (add_ghosts) go the same way but do not count. *s keeps the
// survivors, ghosts too (sorted by cell); `gone`, if not null, gets the real others in the
// order they went. Reports progress as phase "eliminate" going from `from` to `to`.
void eliminate(const Triangles& t, double area, uint32_t target, Samples* s, Samples* gone,
               const HierarchyConfig& config, float from, float to) {
    const uint32_t n = s->size(), reals = s->reals();
    if (reals <= target) return;
    config.report("eliminate", from);
    const double r_max = std::sqrt(area / (2 * std::sqrt(3.0) * double(target)));
    const double d_max = 2 * r_max;
    const double d_min = d_max * (1 - std::pow(double(target) / double(reals), kGamma)) * kBeta;
    sort_by_cell(d_max, s);
    const double* xyz = s->xyz.data();
    const uint32_t* host = s->host.data();
    PointGrid grid;
    grid.build(xyz, n, d_max);
    const double inv_d_max = 1 / d_max, d_max2 = d_max * d_max;
    auto weight_between = [&](uint32_t i, uint32_t j) {
        double d2 = 0;
        for (int k = 0; k < 3; ++k) {
            const double e = xyz[size_t(i) * 3 + size_t(k)] - xyz[size_t(j) * 3 + size_t(k)];
            d2 += e * e;
        }
        if (d2 >= d_max2 || (t.normal[host[i]] | t.normal[host[j]]) <= kSameSideDot) return 0.0;
        double w = 1 - std::max(std::sqrt(d2), d_min) * inv_d_max;
        w *= w;
        w *= w;
        return w * w;  // alpha = 8
    };
    // Weights, and the samples within d_max of each (CSR), so that an elimination updates
    // only those. Samples are sorted by cell: the 27 cells around a cell are gathered once
    // for all of its samples.
    std::vector<double> weight(n, 0.0);
    std::vector<uint32_t> near_offsets(size_t(n) + 1, 0), near, around;
    near.reserve(size_t(n) * 16);
    int64_t cell[3] = {-1, -1, -1};
    for (uint32_t i = 0; i < n; ++i) {
        bool same = true;
        for (int k = 0; k < 3; ++k) {
            const int64_t ck = grid.cell_of(xyz[size_t(i) * 3 + size_t(k)], k);
            same = same && ck == cell[k];
            cell[k] = ck;
        }
        if (!same) {
            around.clear();
            grid.visit(&xyz[size_t(i) * 3], 1, [&](uint32_t j) { around.push_back(j); });
        }
        for (uint32_t j : around) {
            if (j == i) continue;
            const double w = weight_between(i, j);
            if (w == 0) continue;
            weight[i] += w;
            near.push_back(j);
        }
        near_offsets[i + 1] = uint32_t(near.size());
    }
    std::vector<char> alive(n, 1);
    std::vector<uint32_t> went;
    went.reserve(reals - target);
    WeightHeap heap(weight);
    std::vector<double>().swap(weight);
    const uint8_t* ghost = s->ghost.data();
    for (uint32_t left = reals; left > target;) {
        if ((left & 0xFFFF) == 0)
            config.report("eliminate",
                          from + (to - from) * float(reals - left) / float(reals - target));
        const uint32_t i = heap.pop();
        alive[i] = 0;
        if (!ghost[i]) {  // ghosts go like the others, but are not part of the order
            went.push_back(i);
            --left;
        }
        for (uint32_t k = near_offsets[i]; k < near_offsets[i + 1]; ++k) {
            const uint32_t j = near[k];
            if (alive[j]) heap.lower(j, weight_between(i, j));
        }
    }
    if (gone) {
        gone->reserve(went.size());
        for (uint32_t i : went) gone->push(*s, i);
    }
    std::vector<uint32_t> kept;
    kept.reserve(n - (reals - target));
    for (uint32_t i = 0; i < n; ++i)
        if (alive[i]) kept.push_back(i);
    s->select(kept);
}

// How deep the surface is continued across its boundary: 2 spacings of the 512-point prefix
// (or of all the points, if fewer), at most a strip of half the surface's area. The ghosts'
// own boundary is as crowded as any and must stay out of the real samples' reach at every
// prefix that matters: a prefix is even at the boundary once the width is about half its
// spacing or more (square, 0-0.5 spacing band, 60 / 125 / 250 / 500 points, width in
// spacings of 512: 1/2 -> 0.63 / 0.66 / 0.85 / 1.00, 1 -> 0.88 / 1.01 / 1.07 / 1.00,
// 2 -> 1.13 / 0.97 / 1.02 / 1.03). The ghosts cost (boundary length x width) / area more
// samples, fewer where they are hidden: 34 % on SimpleSkin (a 1 x 2 plane), 5 % on
// teapot.obj (its openings), 2 % on the bunny (holes in its base).
constexpr double kGhostSpacings = 2, kGhostPrefix = 512;

double ghost_width(double area, double boundary_length, uint32_t points) {
    const double w = kGhostSpacings * std::sqrt(area / std::min(double(points), kGhostPrefix));
    return std::min(w, 0.5 * area / boundary_length);
}

}  // namespace

void eliminate_hierarchy(const RawScene& scene, const HierarchyConfig& config, PointHierarchy* out,
                         HierarchyStats* stats) {
    Rng rng{config.seed};
    const Triangles t = triangles_of(scene);
    const uint32_t n = config.point_count;
    const uint64_t count = std::max<uint64_t>(
        n, std::min<uint64_t>(uint64_t(n) * kOversampling,
                              std::max<uint64_t>(kCandidateCap, 2 * uint64_t(n))));
    config.report("sample", 0);
    Samples s = sample_surface(t, count, &rng);
    const Boundary boundary = boundary_of(scene, t);
    if (boundary.size() > 0) {
        Rng ghost_rng{config.seed ^ 0x67686F7374ull};  // its own numbers: "ghost"
        add_ghosts(t, boundary, double(count) / t.total, ghost_width(t.total, boundary.length, n),
                   &ghost_rng, &s);
    }
    // Down to the point count; the eliminated samples are not points.
    // The first elimination is ~3/4 of the work, the halvings the rest.
    eliminate(t, t.total, n, &s, nullptr, config, 0.0f, 0.75f);
    // Progressive sampling (Yuksel 2015): halve the survivors again and again, each time with
    // the weights of the smaller set (r_max grows by sqrt 2 per halving). Read backwards, a halving
    // from m to m / 2 gives ranks m - 1 down to m / 2: the last sample to go is the first after the
    // survivors.
    std::vector<Samples> halvings;
    std::vector<uint32_t> level_end;
    for (uint32_t reals = s.reals(); reals > 1; reals = s.reals()) {
        level_end.push_back(reals);
        halvings.emplace_back();
        const float done = 0.75f + 0.25f * (1.0f - float(reals) / float(n));
        eliminate(t, t.total, reals / 2, &s, &halvings.back(), config, done,
                  0.75f + 0.25f * (1.0f - float(reals / 2) / float(n)));
    }
    if (s.reals() == 1) level_end.push_back(1);
    std::reverse(level_end.begin(), level_end.end());
    Samples points;  // coarse to fine
    for (uint32_t i = 0; i < s.size(); ++i)
        if (!s.ghost[i]) points.push(s, i);
    for (size_t h = halvings.size(); h-- > 0;)
        for (uint32_t k = halvings[h].size(); k-- > 0;) points.push(halvings[h], k);
    std::vector<Samples>().swap(halvings);

    config.report("neighbours", 0);
    LevelPoints lp;
    lp.level_end = level_end;
    lp.xyz = points.xyz;
    lp.normal.reserve(size_t(points.size()) * 3);
    for (uint32_t host : points.host)
        lp.normal.insert(lp.normal.end(),
                         {t.normal[host][0], t.normal[host][1], t.normal[host][2]});
    const LevelOrder neighbours = relevant_neighbours(lp, t.total);
    *out = PointHierarchy();
    out->host_triangle = points.host;
    out->bary_u = points.u;
    out->bary_v = points.v;
    out->radius.resize(points.size());
    for (uint32_t i = 0; i < points.size(); ++i)  // the region of an even (i + 1)-point prefix
        out->radius[i] = float(std::sqrt(t.total / double(i + 1)));
    out->neighbour_offsets = neighbours.neighbour_offsets;
    out->neighbours = neighbours.neighbours;
    if (stats) stats->levels = uint32_t(level_end.size());
    config.report("neighbours", 1);
}

}  // namespace stipple::bake
