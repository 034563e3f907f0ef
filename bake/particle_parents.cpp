#include "bake/particle_parents.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "bake/point_hierarchy_nearest.h"

namespace stipple::bake {

namespace {

constexpr uint32_t kDropped = UINT32_MAX;
// Points of the level above asked whether they descend from the record's ancestor.
constexpr uint32_t kSubtreeCandidates = 16;

// The runtime's levels (runtime/particle_tree.h: particle_level_start): level 0 is point 0,
// level k >= 1 the points [4^(k-1), 4^k).
uint32_t level_of(uint32_t i) {
    uint32_t level = 0;
    for (uint64_t end = 1; end <= i; end *= 4) ++level;
    return level;
}

uint64_t level_start(uint32_t level) {
    return level == 0 ? 0 : uint64_t(1) << (2 * (level - 1));
}

double distance2(const std::vector<double>& xyz, uint32_t i, uint32_t j) {
    double d2 = 0;
    for (int k = 0; k < 3; ++k) {
        const double e = xyz[size_t(i) * 3 + size_t(k)] - xyz[size_t(j) * 3 + size_t(k)];
        d2 += e * e;
    }
    return d2;
}

}  // namespace

std::vector<uint32_t> record_parents(const std::vector<uint32_t>& merged_into,
                                     const std::vector<uint32_t>& order,
                                     const std::vector<uint32_t>& rank) {
    const uint32_t n = uint32_t(order.size());
    auto next = [&](uint32_t id) { return id < merged_into.size() ? merged_into[id] : kNoMerge; };
    // first_placed[id]: the place of the first vertex of id's chain (id included) that the
    // hierarchy kept, or kNoMerge; memoised along dropped vertices (each is walked once).
    constexpr uint32_t kUnknown = kNoMerge - 1;
    std::vector<uint32_t> first_placed(rank.size(), kUnknown);
    std::vector<uint32_t> path;
    auto placed = [&](uint32_t id) {
        path.clear();
        uint32_t found = kNoMerge;
        for (; id != kNoMerge; id = next(id)) {
            if (rank[id] != kDropped) {
                found = rank[id];
                break;
            }
            if (first_placed[id] != kUnknown) {
                found = first_placed[id];
                break;
            }
            path.push_back(id);
        }
        for (uint32_t d : path) first_placed[d] = found;
        return found;
    };
    // Coarse after fine: parent[p] for p > i is known, and it is the first of p's chain
    // placed before p, so every vertex it skips is placed after p > i (or dropped).
    std::vector<uint32_t> parent(n, kNoMerge);
    for (uint32_t i = n; i-- > 0;) {
        uint32_t p = placed(next(order[i]));
        while (p != kNoMerge && p > i) p = parent[p];
        parent[i] = p;
    }
    return parent;
}

std::vector<uint32_t> merge_tree_parents(const std::vector<uint32_t>& record_parent,
                                         const std::vector<float>& positions,
                                         MergeTreeStats* stats) {
    const uint32_t n = uint32_t(record_parent.size());
    std::vector<uint32_t> parent(n, kNoMerge);
    MergeTreeStats st;
    const std::vector<double> xyz(positions.begin(), positions.begin() + size_t(n) * 3);
    NearestPoints above;
    std::vector<std::pair<double, uint32_t>> found;
    const auto any = [](uint32_t) { return true; };
    for (uint32_t level = 1; level_start(level) < n; ++level) {
        const uint32_t first = uint32_t(level_start(level)),
                       end = uint32_t(std::min<uint64_t>(level_start(level + 1), n)),
                       above_first = uint32_t(level_start(level - 1));
        above.build(xyz.data() + size_t(above_first) * 3, first - above_first);
        for (uint32_t i = first; i < end; ++i) {
            // The record's first ancestor in a coarser level.
            uint32_t a = record_parent[i];
            while (a != kNoMerge && a >= first) a = record_parent[a];
            if (a != kNoMerge && a >= above_first) {
                parent[i] = a;
                ++st.record;
                continue;
            }
            // The nearest points of the level above, nearest first (within twice i's distance
            // to a, if any).
            const double* q = xyz.data() + size_t(i) * 3;
            const double reach = a == kNoMerge ? INFINITY : 4.0 * distance2(xyz, i, a);
            above.nearest(q, kSubtreeCandidates, reach, any, &found);
            uint32_t chosen = kNoMerge;
            if (a != kNoMerge) {
                // a lies further up: the nearest of those whose ancestor at a's level is a
                // (every parent set so far is one level up, so that is level - 1 - level_of(a)
                // steps). Bounded by kSubtreeCandidates, so a far ancestor costs no more.
                const uint32_t steps = level - 1 - level_of(a);
                for (size_t k = 0; k < found.size() && chosen == kNoMerge; ++k) {
                    uint32_t x = above_first + found[k].second;
                    for (uint32_t s = 0; s < steps; ++s) x = parent[x];
                    if (x == a) chosen = above_first + found[k].second;
                }
            }
            if (chosen != kNoMerge) {
                parent[i] = chosen;
                ++st.subtree;
                continue;
            }
            if (found.empty()) above.nearest(q, 1, INFINITY, any, &found);  // beyond the reach
            parent[i] = found.empty() ? 0 : above_first + found[0].second;
            ++st.nearest;
        }
    }
    if (stats) *stats = st;
    return parent;
}

}  // namespace stipple::bake
