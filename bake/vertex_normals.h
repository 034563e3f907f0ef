// Runtime mesh normals by shading style (thesis §7.1): flat (face normals), smooth
// (Gouraud/Phong: shared across all faces at a vertex) or auto (smooth within regions,
// split at sharp edges whose dihedral angle exceeds a threshold, so one asset holds rounded
// and sharp parts). Points take their normal by barycentric interpolation of these vertex
// normals at runtime (Alg. 6.3 getNormal), so the mesh normals decide the style.
//
// Also the bake's one area-weighted normal computation, used by every importer (vertex
// normals where the input has none) and by assign_normals (per smoothing group).
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "bake/raw_scene.h"

namespace stipple::bake {

enum class NormalMode { input, flat, smooth, automatic };

struct NormalConfig {
    NormalMode mode = NormalMode::automatic;
    float crease_degrees = 40.0f;  // auto: faces meeting at more than this are split
};

// Area-weighted normal of triangle `t` (indices[3t..3t+2]): (p1 - p0) x (p2 - p0), whose
// length is twice the triangle's area, in double precision.
std::array<double, 3> face_normal(const std::vector<float>& positions,
                                  const std::vector<uint32_t>& indices, size_t t);

// Area-weighted vertex normals: each vertex gets the sum of the face normals of its
// triangles, normalised (Max, "Weights for Computing Vertex Normals from Facet Normals",
// JGT 1999, the area-weighted variant). A vertex whose triangles all have zero area gets +z.
void compute_vertex_normals(const std::vector<float>& positions,
                            const std::vector<uint32_t>& indices, std::vector<float>* normals);

// Parses "input", "flat", "smooth" or "auto".
[[nodiscard]] bool parse_normal_mode(const std::string& text, NormalMode* out);

// Flips every triangle (and normal) of a mesh whose faces point inwards: a closed mesh
// with a negative signed volume. Scanned OBJ/PLY/STL files use either winding; the stipple
// renderer needs outward faces (back-facing points are not drawn). Meshes whose signed
// volume is below 1% of their bounding box's (open surfaces) are left alone. Returns true if
// it flipped.
bool orient_outward(RawScene* scene);

// Rewrites scene->normals, duplicating vertices (with their skin data) where one vertex
// needs several normals. Triangles keep their indices' order and count, so point host
// triangles are unaffected. Returns the number of vertices added.
size_t assign_normals(const NormalConfig& config, RawScene* scene);

}  // namespace stipple::bake
