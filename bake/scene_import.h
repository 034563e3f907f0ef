// Importers that turn files into a RawScene. On any malformed or unsupported input each
// returns a BakeError whose message is one line naming the file and the problem
// ("PATH: ..."), and leaves *out empty.
#pragma once
#include <string>
#include <vector>

#include "bake/bake_error.h"
#include "bake/raw_scene.h"

namespace stipple::bake {

// What an import reads besides geometry, skin and clips (the LOOK section's inputs).
struct ImportOptions {
    // Decode base colour textures and read their texture coordinates (glTF); without it the
    // parts keep their colour factors only and no image is decoded.
    bool looks = false;
    // glTF material or mesh names whose parts are transparent (thesis §7.4), besides the
    // materials with alphaMode BLEND. A name that matches nothing fails the import.
    std::vector<std::string> transparent;
};

// glTF 2.0, .gltf or .glb (tinygltf). Reads every triangle primitive of every mesh node
// of the default scene, the first skin, the node hierarchy and every animation clip.
[[nodiscard]] BakeError import_gltf(const std::string& path, RawScene* out,
                                    const ImportOptions& options = ImportOptions());

// Static meshes: .obj, .ply, .stl (OpenMesh readers). No skin, no clips.
// One part, white and opaque (RawScene::parts empty).
[[nodiscard]] BakeError import_static_mesh(const std::string& path, RawScene* out);

// Every name in options.transparent names a material or a mesh of one of scene.parts; else
// invalid_option, listing the unknown names (bake/surface_looks.cpp).
[[nodiscard]] BakeError check_transparent_names(const ImportOptions& options,
                                                const RawScene& scene);

// Dispatches on the file extension (case-insensitive), then checks the transparent names.
[[nodiscard]] BakeError import_scene(const std::string& path, RawScene* out,
                                     const ImportOptions& options = ImportOptions());

}  // namespace stipple::bake
