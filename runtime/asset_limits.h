// Every count limit of a .stip asset, in one place: the bake refuses an input over a limit
// (with a clear error) and the loader refuses an asset over it (LoadError::count_over_limit),
// so whatever the bake writes, the runtime loads. Most limits are what the format can index:
// counts are u32, joint indices u16, and 0xFFFFFFFF marks "no face" and "no deltas".
// Plain constants only; docs/errors.md lists them with the errors that enforce them.
#pragma once
#include <cstdint>

namespace stipple::limits {

// SKIN: joint indices are u16, so joints 0..65535.
constexpr uint32_t kMaxJoints = 65536;
// SKIN: skeleton nodes (parents are i32).
constexpr uint32_t kMaxNodes = 1u << 24;
// MESH: vertices (indices are u32).
constexpr uint32_t kMaxVertices = 0xFFFFFFFFu;
// MESH: triangles; 0xFFFFFFFF is EDGE's "no face".
constexpr uint32_t kMaxTriangles = 0xFFFFFFFEu;
// PNTQ: points (stipple-bake --points takes at most 20,000,000).
constexpr uint32_t kMaxPoints = 1u << 26;
// PNTQ: relevant neighbours per point (a 4-bit count; lists are cut to 15 at bake).
constexpr uint32_t kMaxNeighboursPerPoint = 15;
// CLIP: clips, channels (all clips together), keys per channel.
constexpr uint32_t kMaxClips = 1u << 16;
constexpr uint32_t kMaxChannels = 1u << 24;
constexpr uint32_t kMaxKeys = 1u << 24;
// MRPH: morph targets and weight slots.
constexpr uint32_t kMaxMorphTargets = 1u << 16;
constexpr uint32_t kMaxMorphSlots = 1u << 16;
// STRK: strokes, control points (all strokes together) and control points per stroke.
constexpr uint32_t kMaxStrokes = 1u << 22;
constexpr uint32_t kMaxStrokePoints = 1u << 24;
constexpr uint32_t kMaxPointsPerStroke = 256;
// STRK: every control point coordinate and radius within +-kMaxStrokeCoordinate (object
// units); a surface anchor's barycentrics >= -kStrokeBaryTolerance with u + v <= 1 + it; a
// global normal (snorm8 / 127) all zero or of length 1 +- kStrokeNormalTolerance.
constexpr float kMaxStrokeCoordinate = 1e6f;
constexpr float kStrokeBaryTolerance = 1e-5f;
constexpr float kStrokeNormalTolerance = 0.02f;
// LOOK: parts (triangle part ids are u16).
constexpr uint32_t kMaxParts = 65536;
// File: sections in the table.
constexpr uint32_t kMaxSections = 64;
// File: load_asset_file reads regular files of at most this many bytes (a 20M-point bake with
// a large mesh is a few hundred MB).
constexpr uint64_t kMaxAssetFileBytes = uint64_t(4) << 30;

// Decoded size: without LoadOptions::max_decoded_bytes, an asset may decode into at most
// kDecodedPerFileByte times its file size plus kDecodedFloorBytes (docs/errors.md has the
// ratios measured on the bundled assets).
constexpr uint64_t kDecodedPerFileByte = 16;
constexpr uint64_t kDecodedFloorBytes = uint64_t(1) << 20;

// SKIN: each vertex's 4 weights are in [0, 1] and sum to 1 within this tolerance.
constexpr float kWeightSumTolerance = 1e-3f;
// MESH: a normal is zero (no direction) or of unit length within this tolerance.
constexpr float kNormalLengthTolerance = 1e-3f;

}  // namespace stipple::limits
