// Importers that turn files into a RawScene. On any malformed or unsupported input each
// returns a BakeError whose message is one line naming the file and the problem
// ("PATH: ..."), and leaves *out empty.
#pragma once
#include <string>

#include "bake/bake_error.h"
#include "bake/raw_scene.h"

namespace stipple::bake {

// glTF 2.0, .gltf or .glb (tinygltf). Reads every triangle primitive of every mesh node
// of the default scene, the first skin, the node hierarchy and every animation clip.
[[nodiscard]] BakeError import_gltf(const std::string& path, RawScene* out);

// Static meshes: .obj, .ply, .stl (OpenMesh readers). No skin, no clips.
[[nodiscard]] BakeError import_static_mesh(const std::string& path, RawScene* out);

// Dispatches on the file extension (case-insensitive).
[[nodiscard]] BakeError import_scene(const std::string& path, RawScene* out);

}  // namespace stipple::bake
