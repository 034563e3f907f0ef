#include "runtime/particle_tree.h"

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>

#include "runtime/spatial_grid.h"

namespace stipple {

bool particle_parents_valid(uint32_t count, const uint32_t* parent) {
    if (count > 0 && !parent) return false;
    for (uint32_t i = 0; i < count; ++i)
        if (parent[i] != kNoParent && parent[i] >= i) return false;
    return true;
}

Status particle_tree_build(ParticleTree* tree, uint32_t count, const uint32_t* parent) {
    *tree = ParticleTree();
    if (!particle_parents_valid(count, parent))
        return make_status(StatusCode::invalid_argument,
                           "particle tree: a parent does not precede its child");
    uint32_t roots = 0;
    for (uint32_t i = 0; i < count; ++i) roots += parent[i] == kNoParent;
    tree->child_begin = make_buffer<uint32_t>(size_t(count) + 1);
    tree->children = make_buffer<uint32_t>(count - roots);
    tree->roots = make_buffer<uint32_t>(roots);
    if (!tree->child_begin || !tree->children || !tree->roots)
        return make_status(StatusCode::out_of_memory, "out of memory for a particle tree");
    uint32_t* begin = tree->child_begin.get();
    std::fill(begin, begin + count + 1, 0u);
    for (uint32_t i = 0; i < count; ++i)
        if (parent[i] != kNoParent) ++begin[parent[i] + 1];
    for (uint32_t i = 0; i < count; ++i) begin[i + 1] += begin[i];
    // Children in ascending order: visit them in index order, each into its parent's next slot
    // (the counts are consumed and rebuilt: begin[p] walks to the start of p + 1's row).
    uint32_t r = 0;
    for (uint32_t i = 0; i < count; ++i) {
        if (parent[i] == kNoParent)
            tree->roots[r++] = i;
        else
            tree->children[begin[parent[i]]++] = i;
    }
    for (uint32_t i = count; i > 0; --i) begin[i] = begin[i - 1];
    begin[0] = 0;
    tree->count = count;
    tree->parent = parent;
    tree->root_count = roots;
    return {};
}

namespace {

glm::vec3 point_at(const float* p, uint32_t i) {
    return glm::vec3(p[i * 3], p[i * 3 + 1], p[i * 3 + 2]);
}

// One level's points [base, base + n) in a grid (items are offsets from base).
struct LevelGrid {
    SpatialGrid grid;
    uint32_t base = 0;
};

// Keeps the nearest point in `cell`'s bucket if it is nearer than *best_d2 (ties: the smaller
// index). A point hashed there from another cell is a fair candidate too.
void visit_cell(const LevelGrid& g, const glm::ivec3& cell, const glm::vec3& p, uint32_t* best,
                float* best_d2) {
    const SpatialGrid& grid = g.grid;
    const uint32_t b = grid.bucket(cell);
    for (uint32_t k = grid.start[b]; k < grid.start[b + 1]; ++k) {
        const uint32_t j = grid.items[k];
        const glm::vec3 d = grid.point(j) - p;
        const float d2 = glm::dot(d, d);
        if (d2 < *best_d2 || (d2 == *best_d2 && g.base + j < *best)) {
            *best_d2 = d2;
            *best = g.base + j;
        }
    }
}

// Rings of cells searched for a first candidate, and in all (to confirm the nearest).
constexpr int kRings = 3, kFarRings = 16;

// The nearest of the level's points to p, searched ring by ring of cells around p's cell until
// no nearer point can lie further out: giving up after `empty_rings` rings without a candidate
// or kFarRings in all, or where the rings pass max_distance. kNoParent if none was found.
uint32_t nearest_in(const LevelGrid& g, const glm::vec3& p, int empty_rings, float max_distance) {
    const SpatialGrid& grid = g.grid;
    const glm::ivec3 c = grid.at(p);
    uint32_t best = kNoParent;
    float best_d2 = max_distance * max_distance;
    const float last =
        std::min(float(std::max(empty_rings, kFarRings)), max_distance / grid.cell + 1.0f);
    for (int r = 0; float(r) <= last; ++r) {
        const float reach = float(r - 1) * grid.cell;  // nothing nearer lies in ring r or beyond
        if (best != kNoParent && reach > 0.0f && reach * reach >= best_d2) break;
        if (best == kNoParent && r > empty_rings) break;
        for (int z = -r; z <= r; ++z)
            for (int y = -r; y <= r; ++y) {
                // Only the shell: every x on the ring's faces, else its two ends.
                const bool face = z == -r || z == r || y == -r || y == r;
                const int step = face || r == 0 ? 1 : 2 * r;
                for (int x = -r; x <= r; x += step)
                    visit_cell(g, c + glm::ivec3(x, y, z), p, &best, &best_d2);
            }
    }
    return best;
}

// Largest side of the points' bounding box (0 for fewer than two distinct points).
float extent_of(uint32_t count, const float* positions) {
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (uint32_t i = 0; i < count; ++i) {
        lo = glm::min(lo, point_at(positions, i));
        hi = glm::max(hi, point_at(positions, i));
    }
    const glm::vec3 e = hi - lo;
    const float side = std::max(e.x, std::max(e.y, e.z));
    return std::isfinite(side) ? side : 0.0f;
}

}  // namespace

uint32_t particle_level_start(uint32_t i) {
    uint32_t start = 1;
    while (start <= i / 4) start *= 4;
    return i == 0 ? 0 : start;
}

Status particle_parents(uint32_t count, const float* positions, float max_distance,
                        uint32_t* out_parent, uint32_t first) {
    if (count == 0 || first >= count) return {};
    if (first == 0) out_parent[0] = kNoParent;
    const float extent = extent_of(count, positions);
    if (!(extent > 0.0f)) {  // all points at one place (or not finite): all children of 0
        for (uint32_t i = std::max(first, 1u); i < count; ++i) out_parent[i] = 0;
        return {};
    }
    // Level k's points in a grid whose cell is about their spacing on a surface (4 extent /
    // sqrt(n): a few points per cell, so the nearest is usually within the 27 cells around).
    // A point of level k + 1 searches level k's grid a few rings of cells around it; where that
    // finds nothing (a point far from the coarser ones: a gap, a separate piece, points filling
    // a volume) the coarser levels, whose cells are twice as wide each, give a distance to
    // search level k out to, else the parent found there is taken (a level is skipped). Exact
    // unless the nearest point of level k lies more than 16 cells away.
    constexpr int kMaxLevels = 17;
    LevelGrid grids[kMaxLevels];
    int levels = 0;
    for (uint64_t end = 1; levels < kMaxLevels; end *= 4) {  // level k: [4^(k-1), 4^k)
        const uint32_t base = uint32_t(end / 4),
                       n = uint32_t(std::min<uint64_t>(end, count)) - base;
        grids[levels].base = base;
        if (!grids[levels++].grid.build(positions + size_t(base) * 3, n,
                                        4.0f * extent / std::sqrt(float(n)), nullptr))
            return make_status(StatusCode::out_of_memory, "out of memory for a particle tree");
        if (end >= count) break;
    }
    int level = 0;  // the level above point i's
    for (uint32_t i = std::max(first, 1u); i < count; ++i) {
        while (level + 1 < levels && (uint64_t(1) << (2 * (level + 1))) <= i) ++level;
        const glm::vec3 p = point_at(positions, i);
        uint32_t parent = nearest_in(grids[level], p, level <= 1 ? 1 << 20 : kRings, max_distance);
        for (int l = level - 1; l >= 0 && parent == kNoParent; --l) {
            parent = nearest_in(grids[l], p, l <= 1 ? 1 << 20 : kRings, max_distance);
            if (parent == kNoParent) continue;
            const glm::vec3 d = point_at(positions, parent) - p;
            const uint32_t nearer =
                nearest_in(grids[level], p, kFarRings, std::sqrt(glm::dot(d, d)));
            if (nearer != kNoParent) parent = nearer;
        }
        out_parent[i] = parent;
    }
    return {};
}

}  // namespace stipple
