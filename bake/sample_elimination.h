// Point hierarchies by progressive weighted sample elimination (C. Yuksel, "Sample
// Elimination for Generating Poisson Disk Sample Sets", Eurographics 2015): many random
// samples, uniform in area over the input triangles, are eliminated one at a time, the most
// crowded first, down to the point count; then again from n to n/2, n/2 to n/4, ... (the
// paper's progressive sampling). Read backwards, the eliminations are a coarse-to-fine
// order whose every prefix is evenly spread over the *surface*, whatever its triangulation:
// points are never tied to input vertices or edge midpoints, so long thin triangles, fans
// and rings of slivers leave no trace (docs/hierarchy.md, "Why simplify lines points up").
// An open surface is continued across its boundary (edges of one face) by "ghost" samples
// that are eliminated like the others but never become points, so that no prefix is denser
// along the boundary (docs/hierarchy.md, "Open surfaces"); a closed mesh has none.
//
// The thesis's requirements of a hierarchy (§3.1.1, §4.5) are kept: each point is hosted on
// an input triangle with barycentrics, the point of rank i gets the region area / (i + 1)
// (radius sqrt(area / (i + 1)), as §5.3's "radius per level", spread by rank), and its
// relevant neighbours are the nearest points of its own halving stage and the coarser ones,
// one per quarter of the tangent plane (bake/level_order.h), for Alg. 6.4.
#pragma once
#include "bake/point_hierarchy.h"

namespace stipple::bake {

// Builds `config.point_count` points on the triangles of `scene` (degenerate triangles get
// none). `stats` (may be null) gets skipped_faces (the degenerate triangles) and levels (the
// halving stages). Deterministic for a given seed. Errors: malformed_input when every
// triangle is degenerate.
[[nodiscard]] BakeError eliminate_hierarchy(const RawScene& scene, const HierarchyConfig& config,
                                            PointHierarchy* out, HierarchyStats* stats);

}  // namespace stipple::bake
