#include "bake/patch_hierarchy.h"

#include <algorithm>
#include <numeric>

namespace stipple::bake {

namespace {

// §5.4: "we stop when we have less than 10 patches at a certain level".
constexpr uint32_t kTopPatches = 10;

struct Boxes {
    std::vector<double> area;
    std::vector<Vec3d> lo, hi;
};

Boxes base_boxes(const BaseMesh& base) {
    Boxes b;
    const uint32_t n = base.face_count();
    b.area.resize(n);
    b.lo.resize(n);
    b.hi.resize(n);
    for (uint32_t f = 0; f < n; ++f) {
        b.area[f] = base.area(f);
        b.lo[f] = b.hi[f] = base.corner(f, 0);
        for (int k = 1; k < 3; ++k) {
            b.lo[f].minimize(base.corner(f, k));
            b.hi[f].maximize(base.corner(f, k));
        }
    }
    return b;
}

PatchLevel base_level(const BaseMesh& base) {
    PatchLevel level;
    const uint32_t n = base.face_count();
    level.parent.assign(n, kNoPatch);
    level.leaf.resize(n);
    std::iota(level.leaf.begin(), level.leaf.end(), 0u);
    level.neighbour_offsets.assign(size_t(n) + 1, 0);
    for (uint32_t f = 0; f < n; ++f) {
        for (int k = 0; k < 3; ++k) {
            const uint32_t g = base.across[size_t(f) * 3 + size_t(k)];
            if (g != kNoFace) level.neighbours.push_back(g);
        }
        level.neighbour_offsets[f + 1] = uint32_t(level.neighbours.size());
    }
    return level;
}

// One fusion step (§5.4): patches in increasing area (the binary search tree of the
// thesis, which only ever yields its smallest element), each still unfused one taking up
// to `group` unfused neighbours, greedily the one that keeps the fused bounding box's
// diagonal shortest. Returns the next level; fills `below.parent` and `boxes` for it.
PatchLevel fuse_level(PatchLevel* below, Boxes* boxes, int group, Rng* rng) {
    const uint32_t n = below->size();
    std::vector<uint32_t> order(n);
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(),
                     [&](uint32_t a, uint32_t b) { return boxes->area[a] < boxes->area[b]; });
    PatchLevel up;
    Boxes next;
    up.child_offsets.push_back(0);
    std::vector<uint32_t> members;
    for (uint32_t id : order) {
        if (below->parent[id] != kNoPatch) continue;
        const uint32_t fused = up.size();
        members.assign(1, id);
        below->parent[id] = fused;
        Vec3d lo = boxes->lo[id], hi = boxes->hi[id];
        while (members.size() < size_t(group) + 1) {
            uint32_t best = kNoPatch;
            double best_span = 1e300;
            for (uint32_t c : members)
                for (uint32_t k = below->neighbour_offsets[c]; k < below->neighbour_offsets[c + 1];
                     ++k) {
                    const uint32_t nb = below->neighbours[k];
                    if (below->parent[nb] != kNoPatch) continue;
                    Vec3d l = lo, h = hi;
                    l.minimize(boxes->lo[nb]);
                    h.maximize(boxes->hi[nb]);
                    const double span = (h - l).norm();
                    if (span < best_span || (span == best_span && nb < best)) {
                        best_span = span;
                        best = nb;
                    }
                }
            if (best == kNoPatch) break;
            below->parent[best] = fused;
            members.push_back(best);
            lo.minimize(boxes->lo[best]);
            hi.maximize(boxes->hi[best]);
        }
        double area = 0;
        for (uint32_t c : members) area += boxes->area[c];
        up.children.insert(up.children.end(), members.begin(), members.end());
        up.child_offsets.push_back(uint32_t(up.children.size()));
        up.leaf.push_back(below->leaf[members[rng->below(members.size())]]);
        next.area.push_back(area);
        next.lo.push_back(lo);
        next.hi.push_back(hi);
    }
    // Neighbours of a fused patch: the parents of its children's neighbours.
    up.parent.assign(up.size(), kNoPatch);
    up.neighbour_offsets.assign(size_t(up.size()) + 1, 0);
    std::vector<uint32_t> around;
    for (uint32_t p = 0; p < up.size(); ++p) {
        around.clear();
        for (uint32_t k = up.child_offsets[p]; k < up.child_offsets[p + 1]; ++k) {
            const uint32_t c = up.children[k];
            for (uint32_t j = below->neighbour_offsets[c]; j < below->neighbour_offsets[c + 1]; ++j)
                if (below->parent[below->neighbours[j]] != p)
                    around.push_back(below->parent[below->neighbours[j]]);
        }
        std::sort(around.begin(), around.end());
        around.erase(std::unique(around.begin(), around.end()), around.end());
        up.neighbours.insert(up.neighbours.end(), around.begin(), around.end());
        up.neighbour_offsets[p + 1] = uint32_t(up.neighbours.size());
    }
    *boxes = std::move(next);
    return up;
}

}  // namespace

PatchHierarchy fuse_patches(const BaseMesh& base, int group, Rng* rng) {
    PatchHierarchy h;
    Boxes boxes = base_boxes(base);
    h.levels.push_back(base_level(base));
    h.levels.back().area = boxes.area;
    while (h.levels.back().size() >= kTopPatches) {
        PatchLevel up = fuse_level(&h.levels.back(), &boxes, group, rng);
        if (up.size() == h.levels.back().size()) {  // nothing fused: isolated pieces
            std::fill(h.levels.back().parent.begin(), h.levels.back().parent.end(), kNoPatch);
            break;
        }
        up.area = boxes.area;
        h.levels.push_back(std::move(up));
    }
    return h;
}

}  // namespace stipple::bake
