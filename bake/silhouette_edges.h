// Edge adjacency for runtime silhouettes (thesis §3.2: edges that connect front- and
// back-facing polygons). Computed on the input mesh welded by position, so UV/normal seams
// do not turn into false silhouette edges.
#pragma once
#include <cstdint>
#include <vector>

#include "bake/raw_scene.h"
#include "runtime/asset_format.h"

namespace stipple::bake {

// 4 entries per edge: vertex a, vertex b (indices into the scene's vertices, taken from
// the first face), first face, second face (format::kNoFace on a boundary). Edges shared by more
// than two faces pair the first two and ignore the rest. Ordered deterministically.
std::vector<uint32_t> silhouette_edges(const RawScene& scene);

}  // namespace stipple::bake
