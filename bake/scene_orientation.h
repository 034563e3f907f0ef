// Up axis of the input (issue 7, item 6). The runtime is Y-up, like glTF by its spec (§3.4:
// +Y up, the front facing +Z); scanned and CAD meshes (PLY, STL) are often Z-up and would
// lie on their side. The bake turns a Z-up input upright once and records which axis the
// input used in the asset (BNDS section, docs/format.md).
#pragma once
#include <cstdint>
#include <string>

#include "bake/raw_scene.h"

namespace stipple::bake {

// Parses "y" or "z" into format::kUpY / kUpZ.
[[nodiscard]] bool parse_up_axis(const std::string& text, uint32_t* out);

// format::kUpZ: rotates the scene -90 degrees about +X, (x, y, z) -> (x, z, -y), so +Z
// becomes +Y and a Z-up model's front (-Y, as Blender and most Z-up tools face it) becomes
// +Z, towards the default camera. Static scenes have their positions and normals rotated;
// animated ones get a new root node holding the rotation (every node index shifts by one),
// so bind-space data, skins and clips stay as imported. kUpY leaves the scene as it is.
// Both record the axis in scene->up_axis.
void apply_up_axis(uint32_t up_axis, RawScene* scene);

}  // namespace stipple::bake
