// Offline ("raw") scene: what an importer produces and the asset writer consumes.
// Plain std containers; this header is bake-only (never included by runtime/ or anim/).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace stipple::bake {

enum class RawPath : uint8_t { translation = 0, rotation = 1, scale = 2 };
enum class RawInterp : uint8_t { step = 0, linear = 1 };

// One node of the scene graph. Nodes are stored parents-before-children, so a single
// forward pass computes world transforms. Rotation is a unit quaternion (x, y, z, w).
struct RawNode {
    int32_t parent = -1;
    float translation[3] = {0, 0, 0};
    float rotation[4] = {0, 0, 0, 1};
    float scale[3] = {1, 1, 1};
    std::string name;
};

// One animated property of one node: key times (seconds, strictly increasing) and
// values (3 floats per key for translation/scale, 4 for rotation xyzw).
struct RawChannel {
    uint32_t node = 0;
    RawPath path = RawPath::translation;
    RawInterp interp = RawInterp::linear;
    std::vector<float> times;
    std::vector<float> values;
};

struct RawClip {
    std::string name;
    float duration = 0.0f;  // last key time over all channels
    std::vector<RawChannel> channels;
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
struct RawScene {
    std::vector<float> positions;  // 3 per vertex
    std::vector<float> normals;    // 3 per vertex, unit length (computed if the input has none)
    std::vector<uint32_t> indices; // 3 per triangle, all < vertex count

    std::vector<uint16_t> joints;  // 4 per vertex, indices into joint_nodes
    std::vector<float> weights;    // 4 per vertex, sum 1

    std::vector<RawNode> nodes;          // parents before children
    std::vector<uint32_t> joint_nodes;   // node index of each joint
    std::vector<float> inverse_bind;     // 16 per joint, column-major
    std::vector<RawClip> clips;

    std::vector<std::string> warnings;   // things skipped or repaired, for the bake log

    size_t vertex_count() const { return positions.size() / 3; }
    size_t triangle_count() const { return indices.size() / 3; }
    bool animated() const { return !joint_nodes.empty(); }
};

}  // namespace stipple::bake
