// Loading a .stip asset: the file is read into one allocation at load time, every byte is
// validated (sizes, checksums, index ranges, finite values), and the runtime then works on
// typed views into that block. After load_asset() succeeds, nothing the file says can make
// the runtime read or write outside its buffers.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>

#include "anim/anim.h"
#include "runtime/asset_format.h"
#include "runtime/status.h"

namespace stipple {

// Runtime mesh: positions and normals in bind space (animated) or world space (static).
struct MeshView {
    uint32_t vertex_count = 0;
    uint32_t triangle_count = 0;
    const float* positions = nullptr;   // 3 per vertex
    const float* normals = nullptr;     // 3 per vertex
    const uint32_t* indices = nullptr;  // 3 per triangle, each < vertex_count
};

// Point hierarchy (thesis §4.5), structure of arrays, ordered coarse to fine.
struct PointsView {
    uint32_t point_count = 0;
    const uint32_t* host_triangle = nullptr;      // < triangle_count
    const float* bary_u = nullptr;                // weight of the host triangle's first vertex
    const float* bary_v = nullptr;                // weight of its second; third is 1 - u - v
    const float* radius = nullptr;                // relevance radius at bake time (object space)
    const uint32_t* neighbour_offsets = nullptr;  // point_count + 1, non-decreasing
    const uint32_t* neighbours = nullptr;         // relevant neighbours, each < point_count
    uint32_t neighbour_count = 0;
    // The principal curvature direction per point (CURV section, optional; runtime/
    // asset_format.h): angle in the host triangle's tangent frame, in format::
    // kCurvatureAngleStep units, and its confidence in kCurvatureConfidenceStep units, for
    // points [0, curvature_count) (a view extended past the baked points keeps the count of
    // the baked ones). nullptr and 0 without CURV.
    const uint8_t* curvature_angle = nullptr;
    const uint8_t* curvature_confidence = nullptr;
    uint32_t curvature_count = 0;
};

// Edge adjacency for silhouettes: 4 entries per edge (vertex a, vertex b, face 0, face 1 or
// format::kNoFace on a boundary).
struct EdgesView {
    uint32_t edge_count = 0;
    const uint32_t* edges = nullptr;
    // Per edge, built at load from the SIDE section: 1 on a boundary edge whose face is
    // double-sided (an open sheet's rim, drawn from either side); nullptr without SIDE.
    const uint8_t* double_sided_boundary = nullptr;
};

// Double-sided triangles (SIDE section, format version 3): points on them draw from both
// sides with their normal turned toward the viewer (runtime/double_sided.h).
struct SidesView {
    uint32_t run_count = 0;
    const uint32_t* runs = nullptr;  // 2 per run: first triangle, triangle count (ascending)
    uint32_t triangle_count = 0;     // double-sided triangles in all runs
    // Per MESH triangle, 1 if double-sided; expanded from the runs at load. nullptr when no
    // triangle is double-sided.
    const uint8_t* triangle_double_sided = nullptr;
};

// Framing and orientation (BNDS section, format version 3). A box is min xyz, max xyz.
struct BoundsView {
    bool present = false;          // false for version-2 assets: compute from the mesh
    uint32_t up_axis = 0;          // format::kUpY or kUpZ (the input's up axis), 0 if absent
    float rest[6] = {};            // rest pose (static meshes: the mesh)
    const float* clips = nullptr;  // 6 per clip: every pose the clip samples, skinned
};

// Paintstrokes (STRK section, runtime/asset_format.h): records as stored, validated at load
// (counts, runs inside the point array, anchors, host/joint/root indices, finite positions,
// radii > 0, reserved bytes 0).
struct StrokesView {
    uint32_t stroke_count = 0;
    uint32_t point_count = 0;
    const format::StrokeRecord* strokes = nullptr;
    const format::StrokePointRecord* points = nullptr;
    uint32_t max_points_per_stroke = 0;  // the longest stroke's control points
};

// Looks (LOOK section, optional; written by the bake, read by the styles of
// runtime/frame_config.h): the surface's appearance from its materials (thesis ch. 7-8).
// Every pointer is null and every count 0 when the asset has no LOOK section.
struct LooksView {
    // 4 per baked point, RGBA8 (linear): the material's base colour at the point (factor
    // times the base colour texture sampled at the point's barycentric position, times the
    // vertex colour there); nullptr: none (all white).
    const uint8_t* point_colour = nullptr;
    uint32_t part_count = 0;                  // parts (glTF primitives/materials), 0: one part
    const uint16_t* triangle_part = nullptr;  // per MESH triangle, < part_count, or nullptr
    const uint8_t* part_flags = nullptr;      // part_count entries, kPart* bits
    const uint8_t* part_colour = nullptr;     // 4 per part, RGBA8: base colour factor
    // Crease edges (thesis §7.1: faces meeting at more than the bake's crease angle), laid out
    // like EdgesView::edges: vertex a, vertex b, face 0, face 1 (or format::kNoFace).
    uint32_t crease_count = 0;
    const uint32_t* creases = nullptr;
};
enum : uint8_t { kPartTransparent = 1 };  // thesis §7.4: no fill, only dots and lines
static_assert(kPartTransparent == format::kLookPartTransparent, "LOOK part flag");

struct SkinView {
    anim::Skeleton skeleton = {};
    const uint16_t* joints = nullptr;  // 4 per vertex, each < joint_count
    const float* weights = nullptr;    // 4 per vertex
};

// Indices of Asset::section_size.
enum : int {
    kSectionMesh = 0,
    kSectionSkin,
    kSectionClips,
    kSectionPoints,
    kSectionEdges,
    kSectionMorph,
    kSectionBounds,
    kSectionSides,
    kSectionStrokes,
    kSectionLooks,
    kSectionParticles,
    kSectionCurvature,
    kSectionOccluder,
    kSectionCount
};

struct Asset {
    MeshView mesh;
    PointsView points;
    EdgesView edges;  // empty if the asset has no EDGE section
    bool skinned = false;
    SkinView skin;
    uint32_t clip_count = 0;
    const anim::Clip* clips = nullptr;
    size_t file_size = 0;
    bool has_morph() const { return morph.target_count > 0; }
    anim::Morph morph = {};  // morph targets (empty if the asset has no MRPH section)
    SidesView sides;         // empty if no triangle is double-sided
    BoundsView bounds;       // present = false for version-2 assets
    StrokesView strokes;     // empty if the asset has no STRK section
    LooksView looks;         // empty if the asset has no LOOK section
    // The particle tree (PTRE section, docs/particles.md): parent per point, each before its
    // child or format::kNoParticleParent; nullptr without PTRE (the runtime then builds it).
    const uint32_t* particle_parent = nullptr;
    // The depth pass's simplified occluder (OCCL section, optional; runtime/asset_format.h):
    // 3 indices per triangle into the mesh's vertices, and how far it may lie in front of the
    // surface (object units). nullptr and 0 without OCCL.
    const uint32_t* occluder_indices = nullptr;
    uint32_t occluder_triangle_count = 0;
    float occluder_deviation = 0.0f;
    uint16_t version = 0;
    size_t section_size[kSectionCount] = {};  // bytes per section, kSection* order (0: absent)

    // Owned storage: the file bytes and the clip/channel tables built from them.
    std::unique_ptr<uint8_t[]> storage;
    std::unique_ptr<anim::Channel[]> channel_storage;
    std::unique_ptr<anim::Clip[]> clip_storage;
    std::unique_ptr<uint32_t[]> point_storage;  // decoded point stream
    std::unique_ptr<float[]> clip_values;       // decoded clip key values
    std::unique_ptr<anim::MorphTarget[]> morph_target_storage;
    std::unique_ptr<uint8_t[]> side_storage;  // triangle flags, then edge flags
};

// How much a load may take. The loader computes each section's decoded size from counts it
// has checked against the section's bytes and charges it before allocating; an asset whose
// total would pass the limit fails with LoadError::decoded_size_limit (clip channels may
// share key data, so a small file can ask for gigabytes).
struct LoadOptions {
    // Bytes the decoded sections may take beyond the file's own copy. 0: the default,
    // limits::kDecodedPerFileByte times the file size plus limits::kDecodedFloorBytes
    // (runtime/asset_limits.h). A non-zero cap replaces the default, lower or higher.
    uint64_t max_decoded_bytes = 0;
};

// The decoded-size limit a load of `file_size` bytes runs under with `options`.
uint64_t decoded_size_limit(size_t file_size, const LoadOptions& options);

// Reads and validates a whole asset. On failure `out` is left empty and the Status says
// which check failed (Status::error, docs/errors.md); out-of-memory is
// StatusCode::out_of_memory, a NULL path or out LoadError::invalid_argument.
[[nodiscard]] Status load_asset_file(const char* path, Asset* out,
                                     const LoadOptions& options = LoadOptions());
// Validates `size` bytes already in memory; copies them into out->storage. NULL data or
// size 0: LoadError::invalid_argument.
[[nodiscard]] Status load_asset_memory(const void* data, size_t size, Asset* out,
                                       const LoadOptions& options = LoadOptions());

// Section name of a kSection* index ("MESH", ..., "SIDE").
const char* section_name(int section);

// Index of the clip named `name`, or of clip number `name` if it is all digits; -1 if none.
int find_clip(const Asset& asset, const char* name);

}  // namespace stipple
