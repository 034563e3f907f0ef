#include "bake/level_order.h"

#include <algorithm>
#include <cmath>
#include <queue>
#include <utility>

#include "bake/point_grid.h"

namespace stipple::bake {

namespace {

constexpr int kRelevantNeighbours = 4;
// Normals more than ~120 degrees apart: the other side of a thin sheet, not a neighbour.
constexpr double kSameSideDot = -0.5;
constexpr double kQuarterTurn = 1.5707963267948966;

struct Level {
    const LevelPoints& pts;
    PointGrid grid;
    std::vector<char> placed;

    explicit Level(const LevelPoints& p) : pts(p), placed(p.size(), 0) {}

    const double* at(uint32_t i) const { return &pts.xyz[size_t(i) * 3]; }
    double distance2(uint32_t i, uint32_t j) const {
        double s = 0;
        for (int k = 0; k < 3; ++k) {
            const double d = pts.xyz[size_t(i) * 3 + size_t(k)] - pts.xyz[size_t(j) * 3 + size_t(k)];
            s += d * d;
        }
        return s;
    }
    bool same_side(uint32_t i, uint32_t j) const {
        double s = 0;
        for (int k = 0; k < 3; ++k)
            s += pts.normal[size_t(i) * 3 + size_t(k)] * pts.normal[size_t(j) * 3 + size_t(k)];
        return s > kSameSideDot;
    }

    // Distance from i to the nearest placed point; searches one, then two rings of cells,
    // and reports at most two cells (far enough to go first).
    double nearest_placed(uint32_t i) const {
        double best = 1e300;
        for (int ring = 1; ring <= 2; ++ring) {
            grid.visit(at(i), ring, [&](uint32_t j) {
                if (j != i && placed[j] && same_side(i, j)) best = std::min(best, distance2(i, j));
            });
            if (std::sqrt(best) <= ring * grid.cell()) return std::sqrt(best);
        }
        return std::min(std::sqrt(best), 2 * grid.cell());
    }

    // Greedy farthest-point insertion of [begin, end) with a lazy max-heap: a point's
    // distance to the placed points only shrinks, so a popped point whose refreshed
    // distance still beats the next one is the farthest.
    void insert_farthest_first(uint32_t begin, uint32_t end, std::vector<uint32_t>* order) {
        std::priority_queue<std::pair<double, uint32_t>> heap;
        for (uint32_t i = begin; i < end; ++i) heap.push({1e300, i});
        while (!heap.empty()) {
            const uint32_t i = heap.top().second;
            heap.pop();
            const double d = nearest_placed(i);
            if (!heap.empty() && d < heap.top().first) {
                heap.push({d, i});
                continue;
            }
            placed[i] = 1;
            order->push_back(i);
        }
    }

    // Up to kRelevantNeighbours neighbours of i among the grid's points: the nearest in
    // each quarter of the tangent plane (the first quarter centred on the nearest point),
    // then the nearest of the rest.
    void neighbours_of(uint32_t i, std::vector<std::pair<double, uint32_t>>* near,
                       std::vector<uint32_t>* out) const {
        near->clear();
        grid.visit(at(i), 1, [&](uint32_t j) {
            if (j != i && same_side(i, j)) near->push_back({distance2(i, j), j});
        });
        std::sort(near->begin(), near->end());
        if (near->empty()) return;
        const double* n = &pts.normal[size_t(i) * 3];
        double x[3], y[3];
        for (int k = 0; k < 3; ++k) x[k] = at((*near)[0].second)[k] - at(i)[k];
        const double xn = x[0] * n[0] + x[1] * n[1] + x[2] * n[2];
        for (int k = 0; k < 3; ++k) x[k] -= n[k] * xn;
        y[0] = n[1] * x[2] - n[2] * x[1];
        y[1] = n[2] * x[0] - n[0] * x[2];
        y[2] = n[0] * x[1] - n[1] * x[0];
        uint32_t chosen[kRelevantNeighbours];
        bool taken[kRelevantNeighbours] = {};
        for (const auto& [d2, j] : *near) {
            double u = 0, v = 0;
            for (int k = 0; k < 3; ++k) {
                u += (at(j)[k] - at(i)[k]) * x[k];
                v += (at(j)[k] - at(i)[k]) * y[k];
            }
            // Quarter 0 is centred on the nearest point's direction.
            const double turn = std::atan2(v, u) / kQuarterTurn + 0.5;
            const int q = int(std::floor(turn + 4)) % 4;
            if (!taken[q]) {
                taken[q] = true;
                chosen[q] = j;
            }
        }
        out->clear();
        for (int q = 0; q < kRelevantNeighbours; ++q)
            if (taken[q]) out->push_back(chosen[q]);
        for (const auto& [d2, j] : *near) {
            if (out->size() >= size_t(kRelevantNeighbours)) break;
            if (std::find(out->begin(), out->end(), j) == out->end()) out->push_back(j);
        }
    }
};

}  // namespace

LevelOrder order_levels(const LevelPoints& points, double area) {
    LevelOrder result;
    const uint32_t n = points.size();
    result.order.reserve(n);
    Level level(points);
    std::vector<std::pair<double, uint32_t>> near;
    std::vector<uint32_t> chosen;
    result.neighbour_offsets.assign(size_t(n) + 1, 0);
    uint32_t begin = 0;
    for (uint32_t end : points.level_end) {
        if (end <= begin) continue;
        // Cells of the coarser level's spacing: one ring holds a point's nearest placed
        // points at the start of the level and its neighbours at the level's own spacing.
        const double cell = begin > 0 ? std::sqrt(area / begin) : 2 * std::sqrt(area / end);
        level.grid.build(points.xyz.data(), end, cell);
        level.insert_farthest_first(begin, end, &result.order);
        for (uint32_t i = begin; i < end; ++i) {
            level.neighbours_of(i, &near, &chosen);
            result.neighbours.insert(result.neighbours.end(), chosen.begin(), chosen.end());
            result.neighbour_offsets[i + 1] = uint32_t(result.neighbours.size());
        }
        begin = end;
    }
    for (uint32_t i = begin; i < n; ++i)  // points past the last level: none expected
        result.neighbour_offsets[i + 1] = uint32_t(result.neighbours.size());
    return result;
}

}  // namespace stipple::bake
