// Silhouette lines (thesis §3.2): edges between a front-facing and a back-facing triangle
// in the current pose, plus boundary edges of front-facing triangles (of any triangle when it
// is double-sided: EdgesView::double_sided_boundary), drawn as ink lines over the depth pass.
#pragma once
#include <cstdint>
#include <glm/glm.hpp>

#include "runtime/asset.h"

namespace stipple {

// Triangle facing (triangle_facing's flags): toward the eye, away from it, or away from it but
// nearly edge-on (the depth pass keeps those: runtime/renderer_front.cpp).
constexpr uint8_t kFacingBack = 0, kFacingFront = 1, kFacingEdgeOn = 2;

// front[t] = kFacingFront (1) if triangle t faces the eye (counter-clockwise front faces,
// glTF), else kFacingBack (0), or kFacingEdgeOn when it is within about 0.9 degrees of edge-on.
// `padded`: positions has runtime/point_simd.h's kSimdPadFloats floats readable past its last
// vertex (the pipeline's posed vertices), so the AVX2 kernel may run (the same flags).
void triangle_facing(uint32_t triangle_count, const uint32_t* indices, const float* positions,
                     const glm::vec3& eye, uint8_t* front, bool padded = false);

// Writes the endpoints of every silhouette edge (6 floats per line) into `out_lines`, which
// must hold edges.edge_count * 6 floats; returns the number of lines.
uint32_t silhouette_lines(const EdgesView& edges, const uint8_t* front, const float* positions,
                          float* out_lines);

// Crease lines (thesis §8.2: sharp edges drawn over the stipples to bring out shape; §7.1's
// sharp edges where flat shading separates the light): every crease edge (LooksView::creases,
// laid out like EdgesView::edges) with at least one adjacent face toward the eye, 6 floats per
// line into `out_lines` (room for looks.crease_count lines); returns the number of lines.
uint32_t crease_lines(const LooksView& looks, const uint8_t* front, const float* positions,
                      float* out_lines);

}  // namespace stipple
