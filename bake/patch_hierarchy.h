// The patch hierarchy of thesis §5.4: level 0 is the polygons of the base mesh; each level
// above fuses the smallest unfused patch with the neighbours that keep its bounding box
// smallest, until fewer than 10 patches remain. Each patch's centre is one of its children's
// centres, so it is the centre (relaxed point) of one base polygon, its leaf.
#pragma once
#include <cstdint>
#include <vector>

#include "bake/bake_random.h"
#include "bake/base_mesh.h"

namespace stipple::bake {

constexpr uint32_t kNoPatch = 0xFFFFFFFFu;

struct PatchLevel {
    std::vector<uint32_t> parent;                         // index in the next level up
    std::vector<uint32_t> child_offsets, children;        // indices in the level below
    std::vector<uint32_t> neighbour_offsets, neighbours;  // patches of this level sharing a border
    std::vector<uint32_t> leaf;                           // base polygon holding the centre
    std::vector<double> area;                             // surface area covered
    uint32_t size() const { return uint32_t(leaf.size()); }
};

struct PatchHierarchy {
    std::vector<PatchLevel> levels;  // levels[0]: base polygons

    // Index at `level` of the patch containing patch `index` of level `from` (<= level).
    uint32_t ancestor(int from, uint32_t index, int level) const {
        for (int l = from; l < level; ++l) index = levels[size_t(l)].parent[index];
        return index;
    }
};

// §5.4 patch fusion over the base mesh: `group` is how many neighbours join the smallest
// patch. Stops below 10 patches, or when a level fuses nothing (isolated pieces).
PatchHierarchy fuse_patches(const BaseMesh& base, int group, Rng* rng);

}  // namespace stipple::bake
