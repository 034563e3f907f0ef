// Importers that turn files into a RawScene. Each returns false and sets *error to one
// line naming the problem (and the file) on any malformed or unsupported input.
#pragma once
#include <string>

#include "raw_scene.h"

namespace stipple::bake {

// glTF 2.0, .gltf or .glb (tinygltf). Reads every triangle primitive of every mesh node
// of the default scene, the first skin, the node hierarchy and every animation clip.
bool import_gltf(const std::string& path, RawScene* out, std::string* error);

// Static meshes: .obj, .ply, .stl (OpenMesh readers). No skin, no clips.
bool import_static_mesh(const std::string& path, RawScene* out, std::string* error);

// Dispatches on the file extension (case-insensitive).
bool import_scene(const std::string& path, RawScene* out, std::string* error);

}  // namespace stipple::bake
