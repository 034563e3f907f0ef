// The particle tree of view-dependent particles (GI'01 §3; runtime/particle_tree.h,
// docs/particles.md "Parents") from simplification's own merge record (thesis ch. 4,
// bake/point_hierarchy.cpp): during simplification (Alg. 4.1) each removed vertex is recorded
// as merged into the vertex its edge collapsed onto, and during subdivision (Alg. 4.2) each
// new point as split from the nearer endpoint of its edge. GI'01 §3 builds its tree from the
// same merges: "we simply pick one of the merged particles to represent the rest".
//
// Two steps. record_parents() maps the record through the final coarse-to-fine order: a
// point's record parent is the first point of its chain of merges that precedes it (a forest:
// the chain skips points ordered after it or dropped by the point budget). merge_tree_parents()
// then fits that forest to the levels of the runtime's tree (runtime/particle_tree.h: level k
// is the points [4^(k-1), 4^k)), whose folding by projected size needs every child exactly
// one level finer than its parent (GI'01 §3/§4: a node's children are the particles one
// merge finer, and the density target is met by folding whole levels).
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace stipple::bake {

constexpr uint32_t kNoMerge = 0xFFFFFFFFu;  // a vertex not merged (the base mesh's), no parent

// Records that vertex `child` (a creation id of the hierarchy's builder) merged into, or was
// split from, `into`; `merged_into` grows to hold `child` (kNoMerge elsewhere).
inline void record_merge(std::vector<uint32_t>* merged_into, uint32_t child, uint32_t into) {
    if (merged_into->size() <= child) merged_into->resize(size_t(child) + 1, kNoMerge);
    (*merged_into)[child] = into;
}

// A subdivision point v on the split edge (a, b): recorded as split from the endpoint nearer
// to v's final (randomized) position; a on a tie.
template <class Mesh>
void record_split(std::vector<uint32_t>* merged_into, const Mesh& m, typename Mesh::VertexHandle v,
                  typename Mesh::VertexHandle a, typename Mesh::VertexHandle b) {
    const bool nearer_a =
        (m.point(v) - m.point(a)).sqrnorm() <= (m.point(v) - m.point(b)).sqrnorm();
    record_merge(merged_into, uint32_t(v.idx()), uint32_t((nearer_a ? a : b).idx()));
}

// The record through the final order: rank[id] is creation id's place in the hierarchy
// (UINT32_MAX: dropped), order[i] the id at place i. Returns per place i the first point of
// id's chain of merges placed before i, or kNoMerge (the chain ends first: a root).
std::vector<uint32_t> record_parents(const std::vector<uint32_t>& merged_into,
                                     const std::vector<uint32_t>& order,
                                     const std::vector<uint32_t>& rank);

// How merge_tree_parents chose each parent.
struct MergeTreeStats {
    uint32_t record = 0;   // the record parent: one level above
    uint32_t subtree = 0;  // the record parent is coarser: the nearest of the level above in its
                           // subtree
    uint32_t nearest = 0;  // neither (no record parent, or none of its subtree near): the
                           // nearest of the level above, as for the other methods
};

// Parents one level above (point 0: kNoMerge, the one root) from `record_parent`
// (record_parents(), a forest in coarse-to-fine order) and the points' bind-pose positions
// (3 floats per point). A point's parent is its record parent's first ancestor in a coarser
// level when that lies in the level above; where the record skips that level (the point
// merged into one that survived to a much coarser level), it is the nearest point of the level
// above among that ancestor's descendants (of the 16 nearest within twice i's distance to the
// ancestor); failing that, the nearest of the level above (docs/particles.md, "Parents").
std::vector<uint32_t> merge_tree_parents(const std::vector<uint32_t>& record_parent,
                                         const std::vector<float>& positions,
                                         MergeTreeStats* stats = nullptr);

}  // namespace stipple::bake
