#include "bake/level_order.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <queue>
#include <utility>

#include "bake/point_grid.h"
#include "bake/point_hierarchy_nearest.h"

namespace stipple::bake {

namespace {

constexpr int kRelevantNeighbours = 4;
// Normals more than ~120 degrees apart: the other side of a thin sheet, not a neighbour.
constexpr double kSameSideDot = -0.5;
constexpr double kQuarterTurn = 1.5707963267948966;
// Candidates a point chooses its neighbours from in a crowded place (kCrowdedCandidates):
// its nearest, so the search stays O(log n) per point whatever the surface.
constexpr uint32_t kCrowdedNeighbours = 16;

// One level's search structure: the points up to the level's end copied in the order of
// their grid cells ("slots"), so that a search reads neighbouring memory, not points spread
// over the whole hierarchy at random (a prefix of an even order is spread on purpose; with
// the searches made in cell order too, the neighbours of 1M points take 1.7x less time).
struct Level {
    const LevelPoints& pts;
    PointGrid grid;                          // over the slots
    std::vector<uint32_t> id_of, slot_of;    // slot -> point, point -> slot
    std::vector<double> xyz, normal;         // per slot
    std::vector<char> placed_point, placed;  // per point / per slot
    NearestPoints crowded;                   // over the slots, built when first needed
    bool crowded_built = false;
    std::vector<char> crowded_slot;  // per slot: its cells hold > kCrowdedCandidates points
    mutable std::vector<std::pair<double, uint32_t>> crowded_near;
    mutable uint64_t examined = 0;  // work counter of nearest_placed()

    explicit Level(const LevelPoints& p) : pts(p), placed_point(p.size(), 0) {}

    // The points [0, end) with cells of size `cell`.
    void build(uint32_t end, double cell) {
        PointGrid by_point;
        by_point.build(pts.xyz.data(), end, cell);
        id_of = by_point.order();
        slot_of.assign(end, 0);
        xyz.resize(size_t(end) * 3);
        normal.resize(size_t(end) * 3);
        placed.resize(end);
        for (uint32_t s = 0; s < end; ++s) {
            const uint32_t i = id_of[s];
            slot_of[i] = s;
            for (int k = 0; k < 3; ++k) {
                xyz[size_t(s) * 3 + size_t(k)] = pts.xyz[size_t(i) * 3 + size_t(k)];
                normal[size_t(s) * 3 + size_t(k)] = pts.normal[size_t(i) * 3 + size_t(k)];
            }
            placed[s] = placed_point[i];
        }
        grid.build(xyz.data(), end, cell);  // the same cells, now in slot order
        crowded_built = false;
        // Slots whose 27 cells hold more than kCrowdedCandidates points (counted once per
        // cell: slots are in cell order) search through the kd-tree instead.
        crowded_slot.assign(end, 0);
        int64_t cell_at[3] = {-1, -1, -1};
        size_t count = 0;
        for (uint32_t s = 0; s < end; ++s) {
            bool same = true;
            for (int k = 0; k < 3; ++k) {
                const int64_t ck = grid.cell_of(at(s)[k], k);
                same = same && ck == cell_at[k];
                cell_at[k] = ck;
            }
            if (!same) {
                count = 0;
                grid.visit(at(s), 1, [&](uint32_t) { ++count; });
            }
            crowded_slot[s] = count > kCrowdedCandidates;
            if (crowded_slot[s] && !crowded_built) crowded.build(xyz.data(), end);
            crowded_built = crowded_built || crowded_slot[s];
        }
        for (uint32_t s = 0; s < end && crowded_built; ++s)
            if (placed[s]) crowded.mark(s);
    }

    const double* at(uint32_t s) const { return &xyz[size_t(s) * 3]; }
    double distance2(uint32_t s, uint32_t t) const {
        double d2 = 0;
        for (int k = 0; k < 3; ++k) {
            const double d = xyz[size_t(s) * 3 + size_t(k)] - xyz[size_t(t) * 3 + size_t(k)];
            d2 += d * d;
        }
        return d2;
    }
    bool same_side(uint32_t s, uint32_t t) const {
        double d = 0;
        for (int k = 0; k < 3; ++k)
            d += normal[size_t(s) * 3 + size_t(k)] * normal[size_t(t) * 3 + size_t(k)];
        return d > kSameSideDot;
    }

    // Distance from slot s to the nearest placed point; searches one, then two rings of
    // cells, and reports at most two cells (far enough to go first).
    double nearest_placed(uint32_t s) const {
        if (crowded_slot[s]) {  // the same, through the kd-tree
            std::vector<std::pair<double, uint32_t>>& near = crowded_near;
            const double reach = 2 * grid.cell();
            crowded.nearest_marked(
                at(s), 1, reach * reach,
                [&](uint32_t t) { return t != s && placed[t] && same_side(s, t); }, &near);
            examined += kCrowdedNeighbours;
            return near.empty() ? reach : std::sqrt(near[0].first);
        }
        double best = 1e300;
        for (int ring = 1; ring <= 2; ++ring) {
            grid.visit(at(s), ring, [&](uint32_t t) {
                ++examined;
                if (t != s && placed[t] && same_side(s, t)) best = std::min(best, distance2(s, t));
            });
            if (std::sqrt(best) <= ring * grid.cell()) return std::sqrt(best);
        }
        return std::min(std::sqrt(best), 2 * grid.cell());
    }

    // Greedy farthest-point insertion of the points [begin, end) with a lazy max-heap: a
    // point's distance to the placed points only shrinks, so a popped point whose refreshed
    // distance still beats the next one is the farthest.
    void insert_farthest_first(uint32_t begin, uint32_t end, std::vector<uint32_t>* order) {
        std::priority_queue<std::pair<double, uint32_t>> heap;
        for (uint32_t i = begin; i < end; ++i) heap.push({1e300, i});
        while (!heap.empty()) {
            const uint32_t i = heap.top().second;
            heap.pop();
            const double d = nearest_placed(slot_of[i]);
            if (!heap.empty() && d < heap.top().first) {
                heap.push({d, i});
                continue;
            }
            placed[slot_of[i]] = 1;
            placed_point[i] = 1;
            if (crowded_built) crowded.mark(slot_of[i]);
            order->push_back(i);
        }
    }

    // Up to kRelevantNeighbours neighbours of point i among the grid's points: the nearest
    // in each quarter of the tangent plane (the first quarter centred on the nearest point),
    // then the nearest of the rest. Writes point ids. `around`: the slots of the 27 cells
    // around i's; more than kCrowdedCandidates of them: i chooses among its
    // kCrowdedNeighbours nearest (within two cells) instead.
    void neighbours_of(uint32_t i, const std::vector<uint32_t>& around,
                       std::vector<std::pair<double, uint32_t>>* near, std::vector<uint32_t>* out) {
        const uint32_t s = slot_of[i];
        near->clear();
        if (crowded_slot[s]) {
            const double reach = 2 * grid.cell();
            crowded.nearest(
                at(s), kCrowdedNeighbours, reach * reach,
                [&](uint32_t t) { return t != s && same_side(s, t); }, near);
        } else {
            for (uint32_t t : around)
                if (t != s && same_side(s, t)) near->push_back({distance2(s, t), t});
        }
        std::sort(near->begin(), near->end());
        out->clear();
        if (near->empty()) return;
        const double* n = &normal[size_t(s) * 3];
        double x[3], y[3];
        for (int k = 0; k < 3; ++k) x[k] = at((*near)[0].second)[k] - at(s)[k];
        const double xn = x[0] * n[0] + x[1] * n[1] + x[2] * n[2];
        for (int k = 0; k < 3; ++k) x[k] -= n[k] * xn;
        y[0] = n[1] * x[2] - n[2] * x[1];
        y[1] = n[2] * x[0] - n[0] * x[2];
        y[2] = n[0] * x[1] - n[1] * x[0];
        uint32_t chosen[kRelevantNeighbours];
        bool taken[kRelevantNeighbours] = {};
        for (const auto& [d2, t] : *near) {
            double u = 0, v = 0;
            for (int k = 0; k < 3; ++k) {
                u += (at(t)[k] - at(s)[k]) * x[k];
                v += (at(t)[k] - at(s)[k]) * y[k];
            }
            // Quarter 0 is centred on the nearest point's direction.
            const double turn = std::atan2(v, u) / kQuarterTurn + 0.5;
            const int q = int(std::floor(turn + 4)) % 4;
            if (!taken[q]) {
                taken[q] = true;
                chosen[q] = t;
            }
        }
        for (int q = 0; q < kRelevantNeighbours; ++q)
            if (taken[q]) out->push_back(chosen[q]);
        for (const auto& [d2, t] : *near) {
            if (out->size() >= size_t(kRelevantNeighbours)) break;
            if (std::find(out->begin(), out->end(), t) == out->end()) out->push_back(t);
        }
        for (uint32_t& t : *out) t = id_of[t];
    }
};

// Both entry points: levels one after the other, each on a grid of the points up to its end,
// optionally ordered farthest first, then every point of the level gets its neighbours.
LevelOrder by_levels(const LevelPoints& points, double area, bool farthest_first) {
    LevelOrder result;
    const uint32_t n = points.size();
    result.order.reserve(n);
    Level level(points);
    std::vector<std::pair<double, uint32_t>> near;
    std::vector<uint32_t> chosen, found, around;
    std::vector<uint8_t> found_count;
    result.neighbour_offsets.assign(size_t(n) + 1, 0);
    uint32_t begin = 0;
    for (uint32_t end : points.level_end) {
        if (end <= begin) continue;
        // Cells of the coarser level's spacing: one ring holds a point's nearest placed
        // points at the start of the level and its neighbours at the level's own spacing.
        const double cell = begin > 0 ? std::sqrt(area / begin) : 2 * std::sqrt(area / end);
        level.build(end, cell);
        if (farthest_first) {
            level.insert_farthest_first(begin, end, &result.order);
        } else {
            for (uint32_t i = begin; i < end; ++i) result.order.push_back(i);
        }
        // Searched in cell order (neighbouring searches read neighbouring memory), written in
        // point order.
        found.assign(size_t(end - begin) * kRelevantNeighbours, 0);
        found_count.assign(end - begin, 0);
        int64_t cell_at[3] = {-1, -1, -1};  // the cell `around` was gathered for
        for (uint32_t slot = 0; slot < end; ++slot) {
            const uint32_t i = level.id_of[slot];
            if (i < begin) continue;
            bool same = true;
            for (int k = 0; k < 3; ++k) {
                const int64_t ck = level.grid.cell_of(level.at(slot)[k], k);
                same = same && ck == cell_at[k];
                cell_at[k] = ck;
            }
            const bool crowded = level.crowded_slot[slot];
            if (!same) {  // slots are in cell order: once per cell
                around.clear();
                if (!crowded)
                    level.grid.visit(level.at(slot), 1, [&](uint32_t t) { around.push_back(t); });
                result.candidates += around.size();
            }
            result.candidates += crowded ? kCrowdedNeighbours : around.size();
            level.neighbours_of(i, around, &near, &chosen);
            std::copy(chosen.begin(), chosen.end(),
                      found.begin() + std::ptrdiff_t(i - begin) * kRelevantNeighbours);
            found_count[i - begin] = uint8_t(chosen.size());
        }
        for (uint32_t i = begin; i < end; ++i) {
            const auto first = found.begin() + std::ptrdiff_t(i - begin) * kRelevantNeighbours;
            result.neighbours.insert(result.neighbours.end(), first,
                                     first + found_count[i - begin]);
            result.neighbour_offsets[i + 1] = uint32_t(result.neighbours.size());
        }
        begin = end;
    }
    result.candidates += level.examined;
    for (uint32_t i = begin; i < n; ++i) {  // points past the last level: none expected
        result.order.push_back(i);
        result.neighbour_offsets[i + 1] = uint32_t(result.neighbours.size());
    }
    return result;
}

}  // namespace

LevelOrder order_levels(const LevelPoints& points, double area) {
    return by_levels(points, area, true);
}

LevelOrder relevant_neighbours(const LevelPoints& points, double area) {
    return by_levels(points, area, false);
}

}  // namespace stipple::bake
