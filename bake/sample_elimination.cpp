#include "bake/sample_elimination.h"

#include <OpenMesh/Core/Geometry/VectorT.hh>
#include <algorithm>
#include <cmath>
#include <cstddef>

#include "bake/bake_random.h"
#include "bake/level_order.h"
#include "bake/point_grid.h"

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
    uint32_t size() const { return uint32_t(host.size()); }
    void reserve(size_t n) {
        xyz.reserve(n * 3);
        host.reserve(n);
        u.reserve(n);
        v.reserve(n);
    }
    void push(const Samples& from, uint32_t i) {
        xyz.insert(xyz.end(), from.xyz.begin() + std::ptrdiff_t(i) * 3,
                   from.xyz.begin() + std::ptrdiff_t(i) * 3 + 3);
        host.push_back(from.host[i]);
        u.push_back(from.u[i]);
        v.push_back(from.v[i]);
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
        }
    }
    return c;
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
// `target`, the one of largest weight first, subtracting its contribution from its neighbours'
// weights. *s keeps the survivors (sorted by cell); `gone`, if not null, gets the others in the
// order they went. Reports progress as phase "eliminate" going from `from` to `to`.
void eliminate(const Triangles& t, double area, uint32_t target, Samples* s, Samples* gone,
               const HierarchyConfig& config, float from, float to) {
    const uint32_t n = s->size();
    if (n <= target) return;
    config.report("eliminate", from);
    const double r_max = std::sqrt(area / (2 * std::sqrt(3.0) * double(target)));
    const double d_max = 2 * r_max;
    const double d_min = d_max * (1 - std::pow(double(target) / double(n), kGamma)) * kBeta;
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
    went.reserve(n - target);
    WeightHeap heap(weight);
    std::vector<double>().swap(weight);
    for (uint32_t left = n; left > target; --left) {
        if ((left & 0xFFFF) == 0)
            config.report("eliminate", from + (to - from) * float(n - left) / float(n - target));
        const uint32_t i = heap.pop();
        alive[i] = 0;
        went.push_back(i);
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
    kept.reserve(target);
    for (uint32_t i = 0; i < n; ++i)
        if (alive[i]) kept.push_back(i);
    s->select(kept);
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
    // Down to the point count; the eliminated samples are not points.
    // The first elimination is ~3/4 of the work, the halvings the rest.
    eliminate(t, t.total, n, &s, nullptr, config, 0.0f, 0.75f);
    // Progressive sampling (Yuksel 2015): halve the survivors again and again, each time with
    // the weights of the smaller set (r_max grows by sqrt 2 per halving). Read backwards, a halving
    // from m to m / 2 gives ranks m - 1 down to m / 2: the last sample to go is the first after the
    // survivors.
    std::vector<Samples> halvings;
    std::vector<uint32_t> level_end;
    while (s.size() > 1) {
        level_end.push_back(s.size());
        halvings.emplace_back();
        const float done = 0.75f + 0.25f * (1.0f - float(s.size()) / float(n));
        eliminate(t, t.total, s.size() / 2, &s, &halvings.back(), config, done,
                  0.75f + 0.25f * (1.0f - float(s.size() / 2) / float(n)));
    }
    if (s.size() == 1) level_end.push_back(1);
    std::reverse(level_end.begin(), level_end.end());
    Samples points = s;  // coarse to fine
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
