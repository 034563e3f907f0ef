// Silhouette lines (thesis §3.2): edges between a front-facing and a back-facing triangle
// in the current pose, plus boundary edges of front-facing triangles (of any triangle when it
// is double-sided: EdgesView::double_sided_boundary), drawn as ink lines over the depth pass.
#pragma once
#include <cstdint>
#include <glm/glm.hpp>

#include "runtime/asset.h"

namespace stipple {

// front[t] = 1 if triangle t faces the eye (counter-clockwise front faces, glTF).
void triangle_facing(uint32_t triangle_count, const uint32_t* indices, const float* positions,
                     const glm::vec3& eye, uint8_t* front);

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
