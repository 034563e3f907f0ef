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

// The k nearest of a set of points (a static kd-tree, Friedman, Bentley and Finkel, ACM TOMS
// 3(3), 1977): O(n log n) to build, about O(k log n) a query near the points' manifold.
class NearestTree {
  public:
    // `xyz`: 3 doubles per point; `ids`: what nearest() reports for each.
    void build(std::vector<double> xyz, std::vector<uint32_t> ids);
    // Appends the ids of the k nearest to q (ties: lower index first) to `out`, unordered.
    void nearest(const Vec3d& q, int k, std::vector<uint32_t>* out) const;

  private:
    void build_range(uint32_t lo, uint32_t hi);
    std::vector<double> xyz_;
    std::vector<uint32_t> ids_;
    std::vector<uint32_t> order_;  // an implicit tree: the median of [lo, hi) splits it
    std::vector<uint8_t> axis_;    // split axis of the node at order_[mid]
};

class InputSurface {
  public:
    // A welded vertex with more triangles than this is a hub (the centre of a fan, a
    // non-manifold star, many duplicates of one position): a projection near it searches
    // the kHubNearest of the hub's triangles whose directions from the hub are nearest the
    // point's, instead of all of them.
    static constexpr uint32_t kHubValence = 64;
    static constexpr int kHubNearest = 32;

    // `welded[v]` maps each input vertex to its position class (so triangles meeting at a
    // seam are neighbours).
    InputSurface(const RawScene& scene, const std::vector<uint32_t>& welded);

    Vec3d corner(uint32_t triangle, int k) const;
    const Vec3d& normal(uint32_t triangle) const { return normals_[triangle]; }
    // Total area of the input triangles.
    double area() const { return area_; }
    // Candidate triangles examined by project() so far (a work counter for the tests).
    uint64_t candidates_examined() const { return examined_; }

    // Barycentrics of a point of triangle t (clamped into the triangle).
    SurfacePoint locate(uint32_t triangle, const Vec3d& p) const;

    // Projects p along the line p + s * direction onto the input triangles near the seed
    // triangles (those sharing a vertex with a seed; around a hub, the kHubNearest in p's
    // direction):
    // the intersection closest to p; if the line misses them all, the closest point on them.
    // Always returns a point on the input surface.
    SurfacePoint project(const Vec3d& p, const Vec3d& direction, const uint32_t* seeds,
                         int seed_count) const;

  private:
    void build_hubs(uint32_t classes);
    uint32_t edge_partner(uint32_t c) const;
    void gather(const Vec3d& p, const uint32_t* seeds, int seed_count) const;

    const RawScene& scene_;
    std::vector<Vec3d> normals_;  // unit normal per triangle (0 if degenerate)
    double area_ = 0;
    std::vector<uint32_t> corner_class_;    // welded class of each triangle corner
    std::vector<uint32_t> around_offsets_;  // CSR: triangles around each welded vertex
    std::vector<uint32_t> around_;
    std::vector<uint32_t> hub_of_class_;  // index into hubs_, or UINT32_MAX (empty: no hub)
    struct Hub {
        Vec3d centre;
        Vec3d axis{0, 0, 0};     // a star's hub: unit direction of its shared edge
        NearestTree directions;  // key() of the directions to its triangles' centroids
        Vec3d key(Vec3d d) const;
    };
    std::vector<Hub> hubs_;
    mutable std::vector<uint32_t> candidates_;
    mutable uint64_t examined_ = 0;
};

}  // namespace stipple::bake
