// Serialises a baked scene into the .stip format (runtime/asset_format.h, docs/format.md).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "bake/bake_error.h"
#include "bake/occluder.h"
#include "bake/point_hierarchy.h"
#include "bake/principal_curvature.h"
#include "bake/raw_scene.h"
#include "bake/stroke_data.h"
#include "bake/surface_looks.h"

namespace stipple::bake {

// Builds the whole file in memory (byte-identical for identical inputs). A STRK section is
// written only when `strokes` holds any, a LOOK section only when `looks` says anything: an
// asset without either is the same bytes as before those sections existed.
// A PTRE section (the particle tree, docs/particles.md) only when `particle_parents` holds one
// parent per point. A CURV section (principal curvature directions, bake/principal_curvature.h)
// only when `curvature` holds one direction per point. An OCCL section (the depth pass's
// occluder, bake/occluder.h) only when `occluder` holds triangles.
std::vector<uint8_t> encode_asset(const RawScene& scene, const PointHierarchy& points,
                                  const BakedStrokes& strokes = BakedStrokes(),
                                  const BakedLooks& looks = BakedLooks(),
                                  const std::vector<uint32_t>& particle_parents = {},
                                  const BakedCurvature& curvature = BakedCurvature(),
                                  const BakedOccluder& occluder = BakedOccluder());

// Writes to `path` through a uniquely named temporary file, fsync and a rename
// (bake/atomic_file.h), so a failed bake never leaves a partial asset or a temp file behind.
// Errors: io, naming the cause.
[[nodiscard]] BakeError write_asset(const std::string& path, const std::vector<uint8_t>& bytes);

}  // namespace stipple::bake
