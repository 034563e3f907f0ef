// Point hierarchies by patch-based token relaxation (thesis ch. 5): primary relaxation of
// one point per polygon (Alg. 5.1/5.2), a patch hierarchy by fusion of the smallest patch
// with up to four neighbours (§5.4), then top-down graph token relaxation (Alg. 5.3/5.4):
// at each level, tokens move between the patch centres of a finer level, pushed apart by
// their neighbours, and are fixed before the next level adds more.
#pragma once
#include <string>
#include <vector>

#include "bake/point_hierarchy.h"
#include "bake/surface_projection.h"

namespace stipple::bake {

// One polygon of the (refined) input: the lowest level of the patch hierarchy.
struct BasePatch {
    SurfacePoint centre;  // a random point of the polygon ("the polygon centre", §5.1)
    double area = 0;
    Vec3d lo, hi;            // bounding box
    uint32_t neighbours[3];  // polygons sharing an edge (§5.4)
    int neighbour_count = 0;
};

struct RelaxationStats {
    int levels = 0;
    int iterations = 0;  // relaxation iterations over all levels
    uint64_t displacements = 0;
};

// Builds the hierarchy: one point per base patch, ordered coarse to fine. `surface` is used
// to move points on the input surface during primary relaxation.
void relax_hierarchy(const InputSurface& surface, std::vector<BasePatch> base, uint64_t seed,
                     int primary_iterations, PointHierarchy* out, RelaxationStats* stats);

}  // namespace stipple::bake
