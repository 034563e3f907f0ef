#include "bake/sample_elimination.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>

#include "bake/bake_random.h"
#include "bake/level_order.h"
#include "bake/point_grid.h"
#include "bake/point_hierarchy_nearest.h"
#include "bake/sample_ghosts.h"
#include "bake/surface_samples.h"

namespace stipple::bake {

namespace {

using namespace elimination;

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

// The weight one sample adds to another (Yuksel 2015): (1 - d / d_max)^8 within d_max,
// distances under d_min counting as d_min; 0 between the two sides of a thin sheet.
struct SampleWeighting {
    const Triangles& t;
    const double* xyz;
    const uint32_t* host;
    double d_min, d_max;
    double inv_d_max = 1 / d_max, d_max2 = d_max * d_max;

    bool same_side(uint32_t i, uint32_t j) const {
        return (t.normal[host[i]] | t.normal[host[j]]) > kSameSideDot;
    }
    double operator()(uint32_t i, uint32_t j) const {
        double d2 = 0;
        for (int k = 0; k < 3; ++k) {
            const double e = xyz[size_t(i) * 3 + size_t(k)] - xyz[size_t(j) * 3 + size_t(k)];
            d2 += e * e;
        }
        if (d2 >= d_max2 || !same_side(i, j)) return 0.0;
        double w = 1 - std::max(std::sqrt(d2), d_min) * inv_d_max;
        w *= w;
        w *= w;
        return w * w;  // alpha = 8
    }
};

// The samples within d_max of each sample, with a non-zero weight (CSR).
struct NearLists {
    std::vector<uint32_t> offsets;  // n + 1
    std::vector<uint32_t> near;
};

// Neighbours a sample keeps in a crowded place (kCrowdedCandidates): its nearest, so that
// the lists, and the work of an elimination, stay linear in the samples whatever the surface.
constexpr uint32_t kCrowdedNeighbours = 8;

// Weights, and the samples within d_max of each, so that an elimination updates only
// those. Samples are sorted by cell: the 27 cells around a cell are gathered once for all
// of its samples. Where those cells hold more than kCrowdedCandidates samples (much surface
// in little volume: the pages of a non-manifold star around their edge), a sample weighs and
// keeps only its kCrowdedNeighbours nearest within d_max (a kd-tree query, O(log n)); on a
// surface nothing changes (the bundled assets' cells hold at most 114; a list holds ~15).
std::vector<double> initial_weights(const SampleWeighting& weight_between, uint32_t n,
                                    const PointGrid& grid, NearLists* lists, HierarchyStats* st) {
    const double* xyz = weight_between.xyz;
    std::vector<double> weight(n, 0.0);
    std::vector<uint32_t> around;
    std::vector<std::pair<double, uint32_t>> nearest;
    NearestPoints crowded;
    bool crowded_built = false;
    lists->offsets.assign(size_t(n) + 1, 0);
    lists->near.reserve(size_t(n) * 16);
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
            st->neighbour_candidates += around.size();
        }
        if (around.size() > kCrowdedCandidates) {
            if (!crowded_built) crowded.build(xyz, n);
            crowded_built = true;
            crowded.nearest(
                &xyz[size_t(i) * 3], kCrowdedNeighbours, weight_between.d_max2,
                [&](uint32_t j) { return j != i && weight_between.same_side(i, j); }, &nearest);
            for (const auto& [d2, j] : nearest) {
                weight[i] += weight_between(i, j);
                lists->near.push_back(j);
            }
            st->neighbour_candidates += nearest.size();
        } else {
            for (uint32_t j : around) {
                if (j == i) continue;
                const double w = weight_between(i, j);
                if (w == 0) continue;
                weight[i] += w;
                lists->near.push_back(j);
            }
            st->neighbour_candidates += around.size();
        }
        lists->offsets[i + 1] = uint32_t(lists->near.size());
    }
    return weight;
}

// One elimination (Yuksel 2015, the greedy algorithm with a heap): from the samples *s down to
// `target` real ones, the one of largest weight first, subtracting its contribution from its
// neighbours' weights. Ghosts (add_ghosts) go the same way but do not count. *s keeps the
// survivors, ghosts too (sorted by cell); `gone`, if not null, gets the real others in the
// order they went. Reports progress as phase "eliminate" going from `from` to `to`.
void eliminate(const Triangles& t, double area, uint32_t target, Samples* s, Samples* gone,
               const HierarchyConfig& config, float from, float to, HierarchyStats* st) {
    const uint32_t n = s->size(), reals = s->reals();
    if (reals <= target) return;
    config.report("eliminate", from);
    const double r_max = std::sqrt(area / (2 * std::sqrt(3.0) * double(target)));
    const double d_max = 2 * r_max;
    const double d_min = d_max * (1 - std::pow(double(target) / double(reals), kGamma)) * kBeta;
    sort_by_cell(d_max, s);
    PointGrid grid;
    grid.build(s->xyz.data(), n, d_max);
    const SampleWeighting weight_between{t, s->xyz.data(), s->host.data(), d_min, d_max};
    NearLists lists;
    std::vector<char> alive(n, 1);
    std::vector<uint32_t> went;
    went.reserve(reals - target);
    WeightHeap heap(initial_weights(weight_between, n, grid, &lists, st));
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
        for (uint32_t k = lists.offsets[i]; k < lists.offsets[i + 1]; ++k) {
            const uint32_t j = lists.near[k];
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

// Degenerate triangles get no samples (counted in st->skipped_faces); a mesh of only those
// has no surface to sample.
BakeError check_surface(const Triangles& t, HierarchyStats* st) {
    double area = 0;
    for (size_t f = 0; f < t.area.size(); ++f) {
        const Vec3* c = &t.corner[f * 3];
        const double twice = ((c[1] - c[0]) % (c[2] - c[0])).norm();
        st->skipped_faces += twice == 0;
        area += twice;
    }
    if (!(area > 0)) {
        return bake_error(BakeErrorCode::malformed_input, "mesh has no non-degenerate triangles");
    }
    return BakeError();
}

}  // namespace

BakeError eliminate_hierarchy(const RawScene& scene, const HierarchyConfig& config,
                              PointHierarchy* out, HierarchyStats* stats) {
    Rng rng{config.seed};
    const Triangles t = triangles_of(scene);
    HierarchyStats st;
    const BakeError surface = check_surface(t, &st);
    if (!surface.ok()) return surface;
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
    eliminate(t, t.total, n, &s, nullptr, config, 0.0f, 0.75f, &st);
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
                  0.75f + 0.25f * (1.0f - float(reals / 2) / float(n)), &st);
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
    st.neighbour_candidates += neighbours.candidates;
    *out = PointHierarchy();
    out->host_triangle = points.host;
    out->bary_u = points.u;
    out->bary_v = points.v;
    out->radius.resize(points.size());
    for (uint32_t i = 0; i < points.size(); ++i)  // the region of an even (i + 1)-point prefix
        out->radius[i] = float(std::sqrt(t.total / double(i + 1)));
    out->neighbour_offsets = neighbours.neighbour_offsets;
    out->neighbours = neighbours.neighbours;
    st.levels = uint32_t(level_end.size());
    if (stats) *stats = st;
    config.report("neighbours", 1);
    return BakeError();
}

}  // namespace stipple::bake
