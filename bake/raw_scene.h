// Offline ("raw") scene: what an importer produces and the asset writer consumes.
// Plain std containers; this header is bake-only (never included by runtime/ or anim/).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace stipple::bake {

// Same values as anim::Path / anim::Interp (glTF 2.0 §3.11 target paths and samplers).
enum class RawPath : uint8_t { translation = 0, rotation = 1, scale = 2, weights = 3 };
enum class RawInterp : uint8_t { step = 0, linear = 1, cubic_spline = 2 };

// One node of the scene graph. Nodes are stored parents-before-children, so a single
// forward pass computes world transforms. Rotation is a unit quaternion (x, y, z, w).
struct RawNode {
    int32_t parent = -1;
    float translation[3] = {0, 0, 0};
    float rotation[4] = {0, 0, 0, 1};
    float scale[3] = {1, 1, 1};
    std::string name;
};

// One animated property of one node: key times (seconds, strictly increasing) and values.
// A key's value is `width` floats: 3 for translation/scale, 4 for rotation (x, y, z, w),
// weight_count for weights. STEP/LINEAR: values = times.size() * width. CUBICSPLINE:
// values = times.size() * 3 * width, glTF's layout kept as is: per key the in-tangent, the
// value, the out-tangent (Appendix C; tangents are per second, not yet scaled by the key gap).
// LINEAR/STEP rotation keys are normalised by the importer; CUBICSPLINE values are kept
// exactly as in the file (the sampler normalises its result).
// A weights channel animates the morph weight slots [weight_begin, weight_begin +
// weight_count) of RawScene::morph_weights, the slots of `node`'s mesh instance; both are 0
// for the other paths.
struct RawChannel {
    uint32_t node = 0;
    RawPath path = RawPath::translation;
    RawInterp interp = RawInterp::linear;
    std::vector<float> times;
    std::vector<float> values;
    uint32_t weight_begin = 0;
    uint32_t weight_count = 0;
};

struct RawClip {
    std::string name;
    float duration = 0.0f;  // last key time over all channels
    std::vector<RawChannel> channels;
};

// One morph target of one primitive of the merged mesh (glTF 2.0 §3.7.2.2): deltas for the
// contiguous vertex range [vertex_begin, vertex_begin + vertex_count) (the whole primitive
// as imported), scaled at runtime by morph weight slot `weight`:
//   position = base + sum over targets of morph weight[target.weight] * position delta
// (normals likewise, renormalised after skinning). A mesh with N targets drawn by a node
// owns N consecutive slots; each of its primitives contributes up to N targets, target i
// of every primitive using slot (first slot of the node) + i. Targets whose deltas are all
// zero are not stored. Deltas are in the same space as `positions` (bind space or node
// space, see RawScene).
struct RawMorphTarget {
    uint32_t weight = 0;  // index into RawScene::morph_weights
    uint32_t vertex_begin = 0;
    uint32_t vertex_count = 0;
    std::vector<float> position_deltas;  // 3 * vertex_count
    std::vector<float> normal_deltas;    // 3 * vertex_count, or empty (no NORMAL deltas)
};

// A decoded base colour texture (glTF 2.0 §3.8 images, §3.9.2 baseColorTexture) with its
// sampler's wrap modes (§3.8.4.2, GL enums: 10497 REPEAT, 33071 CLAMP_TO_EDGE, 33648
// MIRRORED_REPEAT). RGBA8 as stored in the file (sRGB colour, linear alpha), row 0 at v = 0.
struct RawTexture {
    uint32_t width = 0, height = 0;
    std::vector<uint8_t> rgba;  // 4 * width * height
    int wrap_s = 10497, wrap_t = 10497;
};

// One part of the surface (thesis §7.4: the unit a look, such as transparency, applies to):
// one glTF material, or one primitive that has no material. The names are the glTF names
// (empty when the file gives none).
struct RawPart {
    std::string material_name;
    std::vector<std::string> mesh_names;  // meshes with triangles in the part
    float colour[4] = {1, 1, 1, 1};       // baseColorFactor, linear RGBA
    int32_t texture = -1;                 // index into RawScene::textures, or -1
    bool blend = false;                   // alphaMode BLEND (§3.9.6)
    bool transparent = false;             // drawn by stipples only (blend, or --transparent)
};

// The whole input, flattened into one triangle mesh.
//
// If the scene is animated (it has a skin or clips), vertices are skinned at runtime:
// every vertex has 4 joint indices into `joint_nodes` and 4 weights summing to 1.
//   - skinned primitives keep their bind-space positions and their skin's weights
//     (renormalised); the skin's joints come first in `joint_nodes`;
//   - unskinned primitives of a mesh node are attached rigidly: their node is
//     appended to `joint_nodes` with an identity inverse bind matrix, positions stay
//     in the node's local space, and joints = (j,0,0,0), weights = (1,0,0,0).
// If the scene is static (no skin, no clips), positions are in world space and
// `joints`, `weights`, `joint_nodes`, `inverse_bind` and `clips` are empty.
//
// Skinned primitives have their vertices sorted by influence count (4, 3, 2, 1 non-zero
// weights), so the skinning job's blocks mostly run the cheaper kernels.
//
// Morph targets (animated scenes only; a static scene has its default weights applied to
// `positions`/`normals` and no targets): `morph_targets` over the merged vertex array,
// `morph_weights` the default weight of every slot (node.weights, else mesh.weights, else
// 0), `morph_weight_nodes` the node owning each slot (slots of one node are consecutive).
// The runtime applies them before skinning; weights channels animate the slots.
struct RawScene {
    std::vector<float> positions;   // 3 per vertex
    std::vector<float> normals;     // 3 per vertex, unit length (computed if the input has none)
    std::vector<uint32_t> indices;  // 3 per triangle, all < vertex count

    std::vector<uint16_t> joints;  // 4 per vertex, indices into joint_nodes
    std::vector<float> weights;    // 4 per vertex, sum 1

    std::vector<RawNode> nodes;         // parents before children
    std::vector<uint32_t> joint_nodes;  // node index of each joint
    std::vector<float> inverse_bind;    // 16 per joint, column-major
    std::vector<RawClip> clips;

    std::vector<RawMorphTarget> morph_targets;
    std::vector<float> morph_weights;          // default weight per slot
    std::vector<uint32_t> morph_weight_nodes;  // node (index into nodes) owning each slot

    // Per triangle: 1 if the surface is double-sided (glTF material.doubleSided, or the
    // bake's --double-sided on): its points draw from both sides. Empty: none is.
    std::vector<uint8_t> double_sided;
    // The input's up axis, recorded in the asset (format::kUpY, kUpZ). The scene itself is
    // always Y-up once apply_up_axis() has run (bake/scene_orientation.h).
    uint32_t up_axis = 1;

    // Looks (issue 9): the parts with their materials, the part of every triangle (empty
    // when there is one part or none), texture coordinates (2 per vertex, of the set the
    // vertex's part samples; empty when no part has a texture) and the decoded textures.
    // No parts (OBJ/PLY/STL): the whole mesh is one white opaque part.
    std::vector<RawPart> parts;
    std::vector<uint16_t> triangle_part;
    std::vector<float> uvs;
    std::vector<RawTexture> textures;
    // Vertex colours (glTF COLOR_0, which multiplies the base colour, §3.9.2; PLY/OBJ vertex
    // colours, sRGB-decoded): 4 per vertex, linear RGBA; empty when the input has none.
    std::vector<float> colours;

    std::vector<std::string> warnings;  // things skipped or repaired, for the bake log

    size_t vertex_count() const { return positions.size() / 3; }
    size_t triangle_count() const { return indices.size() / 3; }
    bool animated() const { return !joint_nodes.empty(); }
};

}  // namespace stipple::bake
