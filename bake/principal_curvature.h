// Principal curvature directions at the points of the hierarchy, for the curvature
// orientation field of view-dependent particles (GI'01 §1: "others rasterize normal and
// curvature information from a 3-D model" to orient strokes; thesis §2.5: an orientation is
// stored on the surface so it turns with it). Per-face second fundamental forms from the
// change of the vertex normals along the edges, averaged into per-vertex tensors
// (Rusinkiewicz, "Estimating curvatures and their derivatives on triangle meshes", 3DPVT
// 2004), smoothed over the 1-ring, interpolated at each point's barycentric position and
// projected into its host triangle's tangent frame (runtime/stroke_anchor.h's surface_frame,
// the frame of the random field). The stored direction is a line (mod 180 degrees): the
// direction of the principal curvature of larger magnitude (across a tube: around it).
#pragma once
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "bake/point_hierarchy.h"
#include "bake/raw_scene.h"

namespace stipple::bake {

struct CurvatureConfig {
    // Rounds of averaging each vertex's tensor with its 1-ring's (a scan's noise turns raw
    // per-vertex directions by tens of degrees from one vertex to the next).
    int smoothing = 2;
};

// Curvature tensors per vertex of the mesh welded by position (bake/position_weld.h, so
// seams split for normals or UVs do not cut it): symmetric 3x3 in object space, in the
// vertex's tangent plane (II = sum k_i d_i d_i^T). weld maps a scene vertex to its vertex.
struct VertexCurvature {
    std::vector<uint32_t> weld;
    std::vector<glm::mat3> tensor;
    // Curvatures well below this are flat for the confidence: that of a sphere whose diameter
    // is the mesh's bounding-box diagonal.
    float flat = 0.0f;
};
VertexCurvature vertex_curvature(const RawScene& scene, const CurvatureConfig& config);

// The principal direction at barycentric (u, v) of `triangle`, unquantised.
struct PointCurvature {
    float angle = 0.0f;       // radians in [0, pi), in the host's tangent frame
    float k_major = 0.0f;     // the larger |principal curvature|, along `angle`
    float k_minor = 0.0f;     // the smaller one, across it
    float confidence = 0.0f;  // (k_major - k_minor) / (k_major + k_minor + flat)
};
PointCurvature point_curvature(const RawScene& scene, const VertexCurvature& vertices,
                               uint32_t triangle, float u, float v);

// The CURV section's contents (runtime/asset_format.h): per point, the angle in
// format::kCurvatureAngleStep units and the confidence in kCurvatureConfidenceStep units.
struct BakedCurvature {
    std::vector<uint8_t> angle, confidence;
    bool empty() const { return angle.empty(); }
};
BakedCurvature bake_curvature(const RawScene& scene, const PointHierarchy& points,
                              const CurvatureConfig& config = CurvatureConfig());

}  // namespace stipple::bake
