// Where the run-time refinement puts a triangle's k-th extra point (runtime/point_refinement.h):
// a fixed barycentric position per (triangle, k), the same every frame.
//
//   - Root cells: the triangle is split by longest-edge bisection into 2^D equal-area root
//     cells, D large enough that slivers become nearly well-shaped cells and large triangles
//     cells of about kRootCellPoints baked points' area. Point k lies in root cell k mod 2^D
//     (bit-reversed path: any prefix spreads over the triangle), as point k / 2^D of its cell.
//   - In a cell: the first kPatternPoints points are a progressive farthest-point pattern
//     (tools/make_refinement_pattern.cpp; one of kPatterns, in one of six corner orders, per
//     triangle, so congruent neighbours differ); further points continue in the cell's four
//     midpoint sub-cells (the digits of Basu & Owen's triangular van der Corput sequence),
//     each with the pattern again from kSubCellStart on.
#pragma once
#include <cstdint>
#include <glm/glm.hpp>

namespace stipple {

// A cell of a triangle's sequence: barycentric (u, v) of its three corners (u weighs the
// triangle's first vertex, v its second).
struct Cell {
    glm::vec2 c[3];
};

// The whole triangle.
constexpr Cell kWholeTriangle = {{glm::vec2(1, 0), glm::vec2(0, 1), glm::vec2(0, 0)}};

// A triangle's 2D isometric frame: A = (0, 0), B = (frame[0], 0), C = (frame[1], frame[2]).
// Maps barycentric differences (du, dv) to lengths in that frame.
glm::mat2 isometric(const float* frame);

// Longest-edge bisection (lengths measured with to_2d) into child `bit` (0 or 1).
Cell bisect(const Cell& cell, const glm::mat2& to_2d, int bit);

// Midpoint subdivision: 0 the central sub-cell, 1-3 the corners.
Cell quarter(const Cell& cell, uint32_t digit);

// Root cell j of 2^depth (path: bits of j, lowest first).
Cell root_cell(const glm::mat2& to_2d, uint32_t depth, uint32_t j);

// Points of a cell's own pattern: all of it in a root cell, from kSubCellStart on in a
// sub-cell (its parent's points already lying there stand in for the first quarter).
uint32_t pattern_points();
uint32_t sub_cell_start();

// Pattern point i of the triangle's variant (pattern and corner order), in `cell`.
glm::vec2 pattern_point(const Cell& cell, uint32_t variant, uint32_t i);

// Number of variants (patterns x 6 corner orders); a triangle's is fixed at load.
uint32_t variant_count();
uint32_t triangle_variant(uint32_t triangle);

// Baked points' worth of area a large triangle's root cells are cut down to.
constexpr float kRootCellPoints = 64.0f;

// Root depth of a triangle of bind `area`, isometric `frame`, longest squared edge
// `longest2`, in a bake of `density` points per unit area (0: no area split).
uint32_t root_depth(float area, float longest2, float density);

// Barycentric (u, v) of the k-th extra point of a triangle.
glm::vec2 refinement_barycentric(const float* frame, uint32_t root_depth, uint32_t variant,
                                 uint32_t k);

}  // namespace stipple
