// A triangulation of the baked points themselves, built at load: the domain the run-time
// refinement continues the hierarchy on (runtime/point_refinement.h).
//
// The render mesh is a poor domain for refinement: game meshes are slivers, fans and rings of
// long thin triangles, and regular meshes repeat one cell pattern. The finest level of an even
// bake is evenly spread over the surface whatever the mesh, so the triangles between its
// points are nearly equilateral. Their corners are baked points: extra points placed inside
// them (away from their edges and corners) fill the holes between the baked points, so the
// hierarchy continues without handing over to a second point set. Corners move with their
// host triangles every frame; a point inside lies on the plane of its three corners (the
// chord, at most spacing^2 / (8 * curvature radius) off the surface).
//
// Construction: for each point, its neighbours within 2.2 spacings that lie on the same sheet
// (normals agree, offset mostly in the tangent plane) and are reachable along the surface
// (through connected triangles of the mesh, so an arm is never joined to the torso beside it)
// are projected onto its tangent plane;
// the point's Voronoi cell among them (half-plane clipping) gives its Delaunay neighbours in
// angular order, and consecutive pairs make triangles. Each triangle is kept once, from its
// lowest-indexed corner. Where the cell reaches the search box (an open boundary) no triangle
// is made.
#pragma once
#include <cstdint>
#include <memory>

#include "runtime/asset.h"
#include "runtime/memory.h"

namespace stipple {

// Total area of a mesh's triangles (degenerate or non-finite ones count 0).
double surface_area(const MeshView& mesh);

struct PointTriangulation {
    uint32_t triangle_count = 0;
    Buffer<uint32_t> indices;  // 3 per triangle, each < the point count
};

// `positions`/`normals`: count points, 3 floats each (bind pose, unit normals); `area`: the
// surface area they cover. With `surface` (the bind-pose mesh) and each point's host triangle
// on it, points are joined only if they are within reach along the surface, not merely in
// space. Fails only with out_of_memory.
[[nodiscard]] Status triangulate_points(uint32_t count, const float* positions,
                                        const float* normals, double area, const MeshView* surface,
                                        const uint32_t* host_triangle, PointTriangulation* out);

}  // namespace stipple
