// Ordering inside the levels of a relaxation hierarchy (thesis §5.3, "radius per level").
// Token relaxation fixes *which* points make up each level (4–5× more than the level
// above), not their order; but the runtime draws prefixes, and the tone model gives the
// point of rank i a region of influence area / (i + 1) (runtime/stipple_size.h), so a
// prefix that ends inside a level must be evenly spread as well. Inside each level, points
// are therefore inserted farthest first (greedy farthest-point insertion against the coarser
// levels and the points of the level already inserted) — the same rule by which subdivision
// places "new points roughly in the middle of existing points" (§4.5).
#pragma once
#include <cstdint>
#include <vector>

namespace stipple::bake {

struct LevelPoints {
    std::vector<double> xyz;          // 3 per point, levels coarse to fine
    std::vector<double> normal;       // 3 per point, unit surface normal
    std::vector<uint32_t> level_end;  // number of points up to and including each level
    uint32_t size() const { return uint32_t(xyz.size() / 3); }
};

struct LevelOrder {
    std::vector<uint32_t> order;              // point ids, coarse to fine, each prefix even
    std::vector<uint32_t> neighbour_offsets;  // per point id (size() + 1)
    std::vector<uint32_t> neighbours;         // relevant neighbours, as point ids
    uint64_t candidates = 0;  // work counter: points the neighbour searches examined
};

// Orders every level farthest first and gives each point up to 4 relevant neighbours among
// the points of its level and the coarser ones: the nearest in each quarter of the tangent
// plane, so their mean distance follows a stretch in any direction alike (Alg. 6.4).
// Points whose normals face away (the other side of a thin sheet) are never neighbours.
LevelOrder order_levels(const LevelPoints& points, double area);

// The same relevant neighbours for points already in their final order (`order` of the
// result is the identity): each point of a level chooses among the points of its level and
// the coarser ones (bake/sample_elimination.h, whose levels are the halving stages).
LevelOrder relevant_neighbours(const LevelPoints& points, double area);

}  // namespace stipple::bake
