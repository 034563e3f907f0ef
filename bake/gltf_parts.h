// Internal to the glTF importer (bake/gltf_import.cpp and its parts): the types passed
// between the parts, one per part of the glTF 2.0 specification
// (https://registry.khronos.org/glTF/specs/2.0/glTF-2.0.html):
//   gltf_accessors.cpp   §3.6.2 accessors
//   gltf_nodes.cpp       §3.5 nodes: roots, flattening, local and world transforms
//   gltf_primitives.cpp  §3.7.2 primitives: topology, attributes, morph target deltas
//   gltf_skins.cpp       §3.7.3 skins: joints, inverse bind matrices, vertex influences
//   gltf_meshes.cpp      §3.7 meshes: morph weight slots, merging primitives into the scene
//   gltf_animations.cpp  §3.11 animations: channels into clips
// Every part reports failure as a BakeError; messages name the glTF object ("node 3: ...").
#pragma once
#include <tiny_gltf.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "bake/bake_error.h"
#include "bake/gltf_accessors.h"
#include "bake/raw_scene.h"
#include "bake/scene_import.h"
#include "runtime/asset_limits.h"

namespace stipple::bake::gltf {

using tinygltf::Model;

// RawScene::joints is uint16_t; the loader's limit (runtime/asset_limits.h).
constexpr size_t kMaxJoints = limits::kMaxJoints;

inline std::string str(size_t v) {
    return std::to_string(v);
}
inline std::string str(int v) {
    return std::to_string(v);
}

// ---------------------------------------------------------------------------------------
// Nodes (gltf_nodes.cpp)

// The scene's nodes flattened parents-first: output node i is glTF node order[i].
struct NodeTable {
    std::vector<size_t> order;       // glTF node of each output node
    std::vector<int32_t> out_index;  // output node of each glTF node; -1: not in the scene
    std::vector<glm::dmat4> world;   // world matrix of each output node
};

// Appends the default scene's nodes to scene->nodes (parents before children, local TRS)
// and fills `nodes`; transform problems that are only approximated become warnings.
[[nodiscard]] BakeError read_nodes(const Model& model, RawScene* scene, NodeTable* nodes);

// ---------------------------------------------------------------------------------------
// Skins (gltf_skins.cpp)

// Skin 0 (§3.7.3); its joints become joints 0..J-1 of the scene.
struct SkinTable {
    bool present = false;               // skin 0 exists and is usable
    std::vector<uint32_t> joint_nodes;  // output node of each joint
    std::vector<float> inverse_bind;    // 16 per joint, column-major
};

[[nodiscard]] BakeError read_skin(const Model& model, const NodeTable& nodes,
                                  std::vector<std::string>* warnings, SkinTable* skin);

// ---------------------------------------------------------------------------------------
// Primitives (gltf_primitives.cpp)

// One primitive's triangles, compacted to the vertices they use.
struct Primitive {
    std::vector<float> positions;   // 3 per vertex
    std::vector<float> normals;     // 3 per vertex, unit
    std::vector<uint32_t> indices;  // 3 per triangle, local
    std::vector<uint16_t> joints;   // 4 per vertex, when skinned
    std::vector<float> weights;     // 4 per vertex, when skinned
    bool skinned = false;
    // Morph targets (§3.7.2.2), one entry per target of the primitive: POSITION deltas (3
    // per vertex; zeros when the target has none) and NORMAL deltas (3 per vertex, or empty
    // when the target has none or the primitive's normals were not given).
    std::vector<std::vector<float>> target_positions;
    std::vector<std::vector<float>> target_normals;
    // TEXCOORD_n of the material's base colour texture (2 per vertex), when it has one and
    // the import wants looks; else empty.
    std::vector<float> uvs;
    // COLOR_0 (§3.7.2.1), 4 per vertex (alpha 1 for VEC3), when the import wants looks.
    std::vector<float> colours;
};

struct MeshContext {
    const Model& model;
    bool quantized;           // KHR_mesh_quantization is used: integer positions/normals
    size_t skin_joint_count;  // joints of skin 0
    std::vector<std::string>* warnings;
    const ImportOptions* options = nullptr;  // looks: texture coordinates wanted
};

// Reads one primitive (skin attributes too when `want_skin`). *skipped is set (with a
// warning) for primitives that are legal but not triangles or have no positions.
[[nodiscard]] BakeError read_primitive(const MeshContext& ctx, size_t mesh_index, size_t prim_index,
                                       bool want_skin, Primitive* out, bool* skipped);

// Reads every JOINTS_n/WEIGHTS_n set of the vertices `used` (old indices) and keeps the 4
// largest influences per vertex (gltf_skins.cpp). Leaves `out` unskinned if there is none.
[[nodiscard]] BakeError read_skin_attributes(const MeshContext& ctx,
                                             const tinygltf::Primitive& prim,
                                             const std::string& label, size_t vertex_count,
                                             const std::vector<uint32_t>& used, Primitive* out);

// Reorders a skinned primitive's vertices by descending influence count (gltf_skins.cpp).
void sort_by_influence_count(Primitive* prim);

// ---------------------------------------------------------------------------------------
// Meshes (gltf_meshes.cpp)

// Morph weight slots of one output node: [begin, begin + count) of RawScene::morph_weights.
struct MorphSlots {
    uint32_t begin = 0;
    uint32_t count = 0;
};

struct MorphWeightTable {
    std::vector<MorphSlots> slots;     // per output node
    std::vector<float> weights;        // default weight of each slot
    std::vector<uint32_t> slot_nodes;  // output node owning each slot
};

// §3.7.2.2: every node drawing a mesh with morph targets owns one slot per target.
MorphWeightTable assign_morph_slots(const Model& model, const NodeTable& nodes,
                                    std::vector<std::string>* warnings);

// Reads the primitives of every mesh node, in output node order, and appends them to
// `scene` (static: world-baked; animated: skinned or rigidly attached, with morph targets).
// Rigid attachments append joints to skin->joint_nodes / skin->inverse_bind.
// Every primitive's part (gltf_materials.cpp) goes to scene->triangle_part, and with
// options.looks its texture coordinates to scene->uvs.
[[nodiscard]] BakeError merge_meshes(const Model& model, const NodeTable& nodes,
                                     const MorphWeightTable& morph, bool animated,
                                     const ImportOptions& options, SkinTable* skin,
                                     RawScene* scene);

// ---------------------------------------------------------------------------------------
// Materials (gltf_materials.cpp): parts, base colours, textures (§3.9, §3.8)

// Parts made so far, by (material, mesh named in --transparent or -1, -1) for a primitive
// with a material and (-1, mesh, primitive) for one without, and textures by glTF texture.
struct PartTable {
    std::vector<std::array<int, 3>> keys;  // key of each part of RawScene::parts
    std::vector<int> texture_of;           // scene texture of each glTF texture, -1: none yet
};

// The TEXCOORD set the primitive's material samples its base colour texture with, or -1.
int base_colour_texcoord(const Model& model, const tinygltf::Primitive& prim);

// The part of primitive `prim_index` of mesh `mesh_index`, made (with its material's colour,
// alpha mode and decoded texture) the first time. Errors: unsupported (over kMaxParts parts).
[[nodiscard]] BakeError primitive_part(const Model& model, size_t mesh_index, size_t prim_index,
                                       const ImportOptions& options, PartTable* table,
                                       RawScene* scene, uint16_t* part);

// The image loader passed to tinygltf (§3.8): decodes PNG/JPEG to RGBA8 with stb_image when
// `decode` is set, within kMaxTextureSide and kMaxTextureBytes (bake/gltf_file_access.h); an
// image it cannot or may not decode is left empty with a warning (its parts get no texture).
struct ImageDecoding {
    bool decode = false;
    uint64_t bytes = 0;  // decoded so far
    std::vector<std::string>* warnings = nullptr;
};
bool load_image(tinygltf::Image* image, const int index, std::string* err, std::string* warn,
                int req_width, int req_height, const unsigned char* bytes, int size, void* user);

// ---------------------------------------------------------------------------------------
// Animations (gltf_animations.cpp)

// Every animation as a clip; malformed channels are dropped with a warning.
std::vector<RawClip> read_clips(const Model& model, const NodeTable& nodes,
                                const std::vector<MorphSlots>& slots,
                                std::vector<std::string>* warnings);

}  // namespace stipple::bake::gltf
