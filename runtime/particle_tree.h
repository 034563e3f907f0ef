// The particle tree of view-dependent particles (GI'01 §3) on the point hierarchy: each point's
// parent is the coarser point it merges into when the hierarchy is cut above it, so unfolding a
// particle adds its children and folding removes them (GI'01 §2 stage 1, Figure 2). Because
// the hierarchy is stored coarse to fine, a parent always precedes its children:
// parent[i] < i, or kNoParent for a root. The parent keeps its own position when it unfolds
// ("we simply pick one of the merged particles to represent the rest", GI'01 §3), which is
// what a point of the hierarchy does: it stays when finer points are added.
#pragma once
#include <cstdint>

#include "runtime/memory.h"
#include "runtime/status.h"

namespace stipple {

constexpr uint32_t kNoParent = 0xFFFFFFFFu;

// Children lists of a parent array (compressed rows, children ascending).
struct ParticleTree {
    uint32_t count = 0;
    const uint32_t* parent = nullptr;  // count entries: < own index, or kNoParent
    Buffer<uint32_t> child_begin;      // count + 1
    Buffer<uint32_t> children;         // count - root_count
    Buffer<uint32_t> roots;            // root_count, ascending
    uint32_t root_count = 0;
};

// True when every parent[i] is kNoParent or < i (a forest in coarse-to-fine order; point 0 is
// always a root).
bool particle_parents_valid(uint32_t count, const uint32_t* parent);

// Builds the children lists of `parent` (kept by pointer, not copied). Fails with
// invalid_argument if the parents are not valid, out_of_memory.
[[nodiscard]] Status particle_tree_build(ParticleTree* tree, uint32_t count,
                                         const uint32_t* parent);

// The levels of the particle tree: level 0 is point 0, level k >= 1 the points [4^(k-1), 4^k),
// so each level has three times as many points as all coarser ones together and its spacing
// on the surface is about half theirs (a point's relevance radius halves every level). The
// first point of i's level (0 for point 0).
uint32_t particle_level_start(uint32_t i);

// The parent rule of the runtime and of the eliminate, relax and random bakes (the hierarchy's
// order is all it needs; a simplify bake stores its own merge record fitted to the same
// levels, bake/particle_parents.h, docs/particles.md "Parents"): each point's
// parent is the nearest point of the level above its own (ties to the smaller index) in the
// given pose: the point it is merged into when the hierarchy is cut above its level, as a
// vertex merge gathers nearby vertices into one (GI'01 Figure 2). Children are thus one level
// finer than their parent, half its spacing, so folding and unfolding by a node's projected
// size regulates the density of what is drawn (GI'01 §2). Point 0 is the root; a point
// farther than `max_distance` from every coarser point (a separate piece of a scattered model)
// is a root too, and one with no point of the level above nearby takes the nearest of a
// coarser level. `positions`: 3 floats per point. Time O(n) on surface samples (a grid per
// level). Points before `first` keep out_parent as it is (a stored tree continued by
// temporary particles, runtime/particle_temporary.h). Fails with out_of_memory.
[[nodiscard]] Status particle_parents(uint32_t count, const float* positions, float max_distance,
                                      uint32_t* out_parent, uint32_t first = 0);

}  // namespace stipple
