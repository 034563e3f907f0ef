// The input surface as the point hierarchy's ground truth (thesis §4.4): every point lives
// on an input triangle. Randomized and subdivided vertices are projected back onto it along
// the summed normals of their neighbourhood (§4.4.2, "the projection operator"), searching
// the input triangles around the neighbours' host triangles.
#pragma once
#include <OpenMesh/Core/Geometry/VectorT.hh>
#include <cstdint>
#include <vector>

#include "bake/raw_scene.h"

namespace stipple::bake {

using Vec3d = OpenMesh::Vec3d;

struct SurfacePoint {
    uint32_t host = 0;    // input triangle
    double u = 0, v = 0;  // barycentric weights of its 1st and 2nd vertex
    Vec3d position;
};

class InputSurface {
  public:
    // `welded[v]` maps each input vertex to its position class (so triangles meeting at a
    // seam are neighbours).
    InputSurface(const RawScene& scene, const std::vector<uint32_t>& welded);

    Vec3d corner(uint32_t triangle, int k) const;
    const Vec3d& normal(uint32_t triangle) const { return normals_[triangle]; }
    // Total area of the input triangles.
    double area() const { return area_; }

    // Barycentrics of a point of triangle t (clamped into the triangle).
    SurfacePoint locate(uint32_t triangle, const Vec3d& p) const;

    // Projects p along the line p + s * direction onto the input triangles near the seed
    // triangles: the intersection closest to p; if the line misses them all, the closest
    // point on them. Always returns a point on the input surface.
    SurfacePoint project(const Vec3d& p, const Vec3d& direction, const uint32_t* seeds,
                         int seed_count) const;

  private:
    const RawScene& scene_;
    std::vector<Vec3d> normals_;  // unit normal per triangle (0 if degenerate)
    double area_ = 0;
    std::vector<uint32_t> near_offsets_;  // CSR: triangles sharing a vertex with t
    std::vector<uint32_t> near_;
    mutable std::vector<uint32_t> candidates_;
};

}  // namespace stipple::bake
