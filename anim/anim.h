// Skeletal animation runtime: clip sampling, local-to-model transforms and linear blend
// skinning. Jobs are plain functions over caller-owned arrays (ozz-animation style):
// nothing here allocates, throws or keeps state between calls.
#pragma once
#include <cstdint>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace stipple::anim {

// A node's local transform. Rotation is stored x, y, z, w (glTF order), unit length.
struct Trs {
    float translation[3];
    float rotation[4];
    float scale[3];
};

enum class Path : uint8_t { translation = 0, rotation = 1, scale = 2 };
enum class Interp : uint8_t { step = 0, linear = 1 };

// One animated property of one node. `times` holds key_count strictly increasing seconds;
// `values` holds key_count * (3 or 4) floats. Views into the loaded asset.
struct Channel {
    uint32_t node;
    Path path;
    Interp interp;
    uint32_t key_count;  // >= 1
    const float* times;
    const float* values;
};

struct Clip {
    const char* name;   // NUL-terminated
    float duration;     // seconds, >= 0
    uint32_t channel_count;
    const Channel* channels;
};

// Node hierarchy and skin. parents[i] < i (or -1 for roots): one forward pass suffices.
struct Skeleton {
    uint32_t node_count;
    const int32_t* parents;        // node_count
    const Trs* rest;               // node_count, the bind/rest local transforms
    uint32_t joint_count;
    const uint32_t* joint_nodes;   // joint_count, each < node_count
    const float* inverse_bind;     // joint_count * 16, column-major
};

// Writes the clip's pose at `time` into `locals` (node_count entries). Nodes the clip does
// not animate are set to their rest transform. Time is clamped to [0, duration]; pass
// fmod(time, duration) to loop. Rotations are slerped on the shortest path and
// normalised (glTF 2.0 "Animation Samplers"); STEP holds the earlier key.
void sample_clip(const Skeleton& skeleton, const Clip& clip, float time, Trs* locals);

// Copies the rest pose into `locals` (node_count entries).
void rest_pose(const Skeleton& skeleton, Trs* locals);

// model[i] = model[parent[i]] * local[i] (node_count entries).
void local_to_model(const Skeleton& skeleton, const Trs* locals, glm::mat4* model);

// skin[j] = model[joint_nodes[j]] * inverse_bind[j] (joint_count entries).
void joint_matrices(const Skeleton& skeleton, const glm::mat4* model, glm::mat4* skin);

// Linear blend skinning of positions and normals, 4 influences per vertex.
// in/out positions and normals are 3 floats per vertex; joints/weights 4 per vertex.
// Normals are transformed by the blended matrix's upper 3x3 and renormalised (exact for
// rigid and uniformly scaled joints, the glTF convention).
struct SkinJob {
    uint32_t vertex_count;
    const glm::mat4* skin;     // joint matrices
    uint32_t joint_count;      // entries in skin; joint indices >= this are treated as 0
    const uint16_t* joints;    // vertex_count * 4
    const float* weights;      // vertex_count * 4
    const float* in_positions; // vertex_count * 3
    const float* in_normals;   // vertex_count * 3
    float* out_positions;      // vertex_count * 3
    float* out_normals;        // vertex_count * 3
};
void skin_lbs(const SkinJob& job);

}  // namespace stipple::anim
