// Point hierarchies by patch-based token relaxation (thesis ch. 5): one random point per
// polygon (§5.1) relaxed on the surface (Alg. 5.1/5.2), a patch hierarchy by fusion of the
// smallest patch with its neighbours (§5.4), then top-down graph token relaxation (Alg.
// 5.3/5.4): at each level, tokens move between the patch centres of a finer level, pushed
// apart by their neighbours, and are fixed before the next level adds more. Inside a level
// points are ordered farthest first (bake/level_order.h).
#pragma once
#include <cstdint>

#include "bake/base_mesh.h"
#include "bake/point_hierarchy.h"
#include "bake/surface_projection.h"

namespace stipple::bake {

// One point per polygon of `base`, ordered coarse to fine, radius of rank i
// sqrt(area / (i + 1)) (the region of influence the runtime's tone model gives it).
// `stats` gets levels and relax_iterations.
void relax_hierarchy(const InputSurface& surface, const BaseMesh& base,
                     const HierarchyConfig& config, PointHierarchy* out, HierarchyStats* stats);

// The naive baseline (thesis Fig. 5.1): one random point per polygon of `base`, in random
// order, radius of rank i sqrt(area / (i + 1)), no neighbours.
void random_hierarchy(const InputSurface& surface, const BaseMesh& base,
                      const HierarchyConfig& config, PointHierarchy* out);

}  // namespace stipple::bake
