// Nearest-triangle queries over a triangle soup in one pose, for the occluder's measured
// deviation (bake/occluder.h): a dense uniform grid, each triangle listed in every cell its
// bounding box touches (compressed rows: cell_start / items), searched ring by ring.
#pragma once
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace stipple::bake {

struct TriangleGrid {
    glm::vec3 origin{0.0f};
    float cell = 1.0f;
    glm::ivec3 dims{0};
    std::vector<uint32_t> cell_start;  // dims.x * dims.y * dims.z + 1
    std::vector<uint32_t> items;       // triangle numbers, cell after cell
    std::vector<glm::vec3> corners;    // 3 per triangle, in `tris` order
};

// The grid of `tris` (3 vertex indices per triangle into `positions`, 3 floats per vertex).
// Cells are twice the triangles' mean edge, coarsened so the grid has at most 2^22 cells.
TriangleGrid build_triangle_grid(const float* positions, const std::vector<uint32_t>& tris);

// The distance from p to the nearest triangle of the grid when p lies on `side` of it
// (`side` * the triangle's winding normal . (p - nearest point) > 0); 0 when p lies on the
// other side, or when no triangle is within 6 cells.
float one_sided_gap(const TriangleGrid& grid, glm::vec3 p, float side);

}  // namespace stipple::bake
