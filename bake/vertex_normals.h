// Runtime mesh normals by shading style (thesis §7.1): flat (face normals), smooth
// (Gouraud/Phong: shared across all faces at a vertex) or auto (smooth within regions,
// split at sharp edges whose dihedral angle exceeds a threshold, so one asset holds rounded
// and sharp parts). Points take their normal by barycentric interpolation of these vertex
// normals at runtime (Alg. 6.3 getNormal), so the mesh normals decide the style.
#pragma once
#include <string>

#include "bake/raw_scene.h"

namespace stipple::bake {

enum class NormalMode { input, flat, smooth, automatic };

struct NormalConfig {
    NormalMode mode = NormalMode::automatic;
    float crease_degrees = 40.0f;  // auto: faces meeting at more than this are split
};

// Parses "input", "flat", "smooth" or "auto".
bool parse_normal_mode(const std::string& text, NormalMode* out);

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
