// The .stip asset: one little-endian binary file holding everything the runtime needs.
// See docs/format.md for the byte layout. Shared by the bake's writer and the runtime's
// loader; plain constants and POD records only.
#pragma once
#include <cstddef>
#include <cstdint>

#include "runtime/crc32.h"

namespace stipple::format {

constexpr char kMagic[4] = {'S', 'T', 'I', 'P'};
constexpr uint16_t kVersion = 3;
constexpr uint16_t kOldestVersion = 2;   // version 2 lacks BNDS and SIDE; the loader still reads it
constexpr uint16_t kEndianTag = 0xFEFF;  // reads as 0xFFFE on a big-endian machine
constexpr uint32_t kSectionAlign = 16;

constexpr uint32_t fourcc(char a, char b, char c, char d) {
    return uint32_t(uint8_t(a)) | uint32_t(uint8_t(b)) << 8 | uint32_t(uint8_t(c)) << 16 |
           uint32_t(uint8_t(d)) << 24;
}
constexpr uint32_t kTagMesh = fourcc('M', 'E', 'S', 'H');
constexpr uint32_t kTagSkin = fourcc('S', 'K', 'I', 'N');
constexpr uint32_t kTagClips = fourcc('C', 'L', 'I', 'P');
constexpr uint32_t kTagEdges = fourcc('E', 'D', 'G', 'E');
constexpr uint32_t kTagPointStream = fourcc('P', 'N', 'T', 'Q');  // the point hierarchy, coded
constexpr uint32_t kTagMorph = fourcc('M', 'R', 'P', 'H');        // morph targets
constexpr uint32_t kTagBounds = fourcc('B', 'N', 'D', 'S');       // v3: up axis, rest/clip bounds
constexpr uint32_t kTagSides = fourcc('S', 'I', 'D', 'E');        // v3: double-sided triangle runs
constexpr uint32_t kTagStrokes = fourcc('S', 'T', 'R', 'K');      // paintstrokes (GI'98)
constexpr uint32_t kTagParticles = fourcc('P', 'T', 'R', 'E');    // the particle tree (GI'01)
constexpr uint32_t kTagLooks = fourcc('L', 'O', 'O', 'K');        // colours, parts, creases
constexpr uint32_t kTagCurvature = fourcc('C', 'U', 'R', 'V');    // principal directions (GI'01)
constexpr uint32_t kTagOccluder = fourcc('O', 'C', 'C', 'L');     // the depth pass's occluder
constexpr uint32_t kNoFace = 0xFFFFFFFFu;                         // second face of a boundary edge

struct FileHeader {  // 32 bytes at offset 0
    char magic[4];
    uint16_t version;
    uint16_t endian_tag;
    uint32_t section_count;
    uint32_t table_crc;  // CRC-32 of the section table
    uint64_t file_size;
    uint64_t reserved;
};
static_assert(sizeof(FileHeader) == 32, "header layout");

struct SectionEntry {  // section_count entries right after the header
    uint32_t tag;
    uint32_t crc;     // CRC-32 of the section's bytes
    uint64_t offset;  // from the start of the file, kSectionAlign-aligned
    uint64_t size;
};
static_assert(sizeof(SectionEntry) == 24, "section entry layout");

struct ClipRecord {        // one per clip in the CLIP section
    uint32_t name_offset;  // into the name pool, NUL-terminated
    uint32_t channel_begin;
    uint32_t channel_count;
    float duration;
};
static_assert(sizeof(ClipRecord) == 16, "clip layout");

// CLIP section: key times are stored once per distinct time array and indexed;
// values are 16-bit codes over a per-column [min, max] range (a column is one float of a
// key's value: width floats, or 3 * width for CUBICSPLINE's in-tangent/value/out-tangent).
struct ChannelRecordV2 {
    uint32_t node;
    uint8_t path;    // 0 translation, 1 rotation, 2 scale, 3 weights
    uint8_t interp;  // 0 step, 1 linear, 2 cubic spline
    uint16_t reserved;
    uint32_t key_count;
    uint32_t time_array;     // index into the time array table
    uint32_t weight_begin;   // weights path: first morph slot
    uint32_t weight_count;   // weights path: slots animated (the value width)
    uint32_t codes_offset;   // into the u16 code pool: key_count * columns codes, key-major
    uint32_t ranges_offset;  // into the float range pool: 2 floats (min, max) per column
};
struct TimeArrayRecord {
    uint32_t offset;  // into the float time pool
    uint32_t count;
};
static_assert(sizeof(ChannelRecordV2) == 32 && sizeof(TimeArrayRecord) == 8, "clip v2 layout");

// MRPH section: one record per morph target.
struct MorphTargetRecord {
    uint32_t weight;  // slot
    uint32_t vertex_begin;
    uint32_t vertex_count;
    uint32_t position_offset;  // into the delta float pool (3 * vertex_count floats)
    uint32_t normal_offset;    // likewise, or 0xFFFFFFFF for no normal deltas
};
static_assert(sizeof(MorphTargetRecord) == 20, "morph layout");
constexpr uint32_t kNoDeltas = 0xFFFFFFFFu;

// BNDS section (version 3): how the bake oriented the scene and where it goes.
//   u32 up_axis, u32 clip_count, f32 rest[6], f32 clips[6 * clip_count]
// Each box is min xyz then max xyz, in the runtime's (Y-up) space.
constexpr uint32_t kUpY = 1;  // the input was Y-up (glTF by its spec): kept as is
constexpr uint32_t kUpZ = 2;  // the input was Z-up: rotated at bake so +Z became +Y

// SIDE section (version 3): u32 run_count, then run_count (first triangle, triangle count)
// pairs, ascending and non-overlapping: the double-sided triangles of the MESH section.

// STRK section (optional; version 3 files may carry it): paintstroke data (GI'98 §3).
//   u32 stroke_count, u32 point_count, StrokeRecord[stroke_count], StrokePointRecord[point_count]
// Strokes are ordered so that their roots follow the point hierarchy's coarse-to-fine order
// where they have one (fur); each stroke's control points are a contiguous run.
enum StrokeAnchor : uint8_t {
    kAnchorSurface = 0,  // host triangle + barycentrics; points in its tangent frame (below)
    kAnchorObject = 1,   // points in object (bind) space, moved by nothing
    kAnchorJoint = 2,    // points in bind space, moved by one joint's skin matrix
};
constexpr uint32_t kNoRootPoint = 0xFFFFFFFFu;
struct StrokeRecord {            // 32 bytes
    uint32_t first_point;        // into the StrokePointRecord array
    uint32_t point_count;        // >= 2
    uint8_t anchor;              // StrokeAnchor
    uint8_t reserved[3];         // 0
    uint32_t host;               // surface: triangle (< MESH triangles); joint: joint (< joints)
    float bary_u, bary_v;        // surface: weights of the host's first and second vertex
    uint32_t root_point;         // the hierarchy point the root sits on (LOD), or kNoRootPoint
    uint8_t op_centre, op_edge;  // breadthwise opacity (eq. 5), 0..255 -> [0, 1]
    uint16_t reserved2;          // 0
};
static_assert(sizeof(StrokeRecord) == 32, "stroke layout");
// A control point. Surface anchor: position and global normal in the host's tangent frame at
// the root: x along the host's first edge (v1 - v0, made orthogonal to the normal), y = z × x,
// z the interpolated vertex normal; lengths in object units (not scaled by the triangle, so a
// stroke keeps its shape when the surface stretches). Object and joint anchors: bind space.
struct StrokePointRecord {  // 28 bytes
    float position[3];
    float radius;             // > 0
    uint8_t colour[3];        // sRGB-free linear 0..255
    uint8_t reflectance;      // 0..255 -> [0, 1]
    uint8_t op_min, op_max;   // eq. 3, 0..255 -> [0, 1]
    uint8_t global_depth;     // §5.3 d_gl, 0..255 -> [0, 1]
    uint8_t reserved;         // 0
    int8_t global_normal[3];  // §5.3 N_gl, snorm8 (all 0: no global shading)
    uint8_t reserved2;        // 0
};
static_assert(sizeof(StrokePointRecord) == 28, "stroke point layout");

// LOOK section (optional; version 3 files may carry it): the surface's looks (thesis ch. 7-8).
//   LooksHeader, u32 creases[4 * crease_count] (vertex a, vertex b, face 0, face 1),
//   u8 point_colour[4 * point_colour_count] (RGBA8, linear), u8 part_colour[4 * part_count]
//   (RGBA8), u16 triangle_part[triangle_part_count], u8 part_flags[part_count] (kLookPart*)
// Each array is aligned to its element size by the order alone: no padding anywhere.
// point_colour_count is 0 or the PNTQ point count; triangle_part_count is 0 (with
// part_count 0: one part) or the MESH triangle count (with part_count >= 1).
struct LooksHeader {  // 20 bytes
    uint32_t point_colour_count;
    uint32_t part_count;
    uint32_t triangle_part_count;
    uint32_t crease_count;
    uint32_t reserved;  // 0
};
static_assert(sizeof(LooksHeader) == 20, "looks header layout");
constexpr uint8_t kLookPartTransparent = 1;  // thesis §7.4: the part draws no fill
constexpr uint8_t kLookPartKnownFlags = kLookPartTransparent;

// PTRE section (optional; version 3 files may carry it): the particle tree of view-dependent
// particles (runtime/particle_tree.h, docs/particles.md).
//   u32 point_count (= the PNTQ section's), u32 parent[point_count]
// parent[i] is a point before i (coarser), or kNoParticleParent for a root; point 0 is a root.
constexpr uint32_t kNoParticleParent = 0xFFFFFFFFu;

// CURV section (optional; version 3 files may carry it): each point's principal curvature
// direction, the orientation field of view-dependent particles (bake/principal_curvature.h,
// docs/particles.md).
//   u32 point_count (= the PNTQ section's), u8 angle[point_count], u8 confidence[point_count]
// angle: the direction of the larger |curvature| in the host triangle's tangent frame
// (runtime/stroke_anchor.h's surface_frame: x along the first edge), a line, so modulo pi, in
// steps of pi / 256; confidence: (|k1| - |k2|) / (|k1| + |k2| + floor) in steps of 1 / 255.
constexpr float kCurvatureAngleStep = 3.14159265358979f / 256.0f;
constexpr float kCurvatureConfidenceStep = 1.0f / 255.0f;

// OCCL section (optional; version 3 files may carry it): the depth pass's simplified occluder
// (bake/occluder.h, runtime/renderer_occluder.cpp), triangles over the MESH section's vertices.
//   u32 triangle_count (1 .. the MESH triangle count), f32 deviation (finite, >= 0; object
//   units: how far the occluder may lie in front of the surface), u32 index[3 * triangle_count]
// Every index < the MESH vertex count.

// Section checksums: crc32() of runtime/crc32.h.

}  // namespace stipple::format
