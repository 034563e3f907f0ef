// Point hierarchy on a mesh surface, thesis ch. 4: longest-edge subdivision below the input
// resolution and edge-collapse simplification above it, each point stored as a host
// triangle of the input mesh + barycentric coordinates, a relevance radius and its list of
// relevant neighbours, ordered coarse to fine.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "bake/raw_scene.h"

namespace stipple::bake {

struct PointHierarchy {
    std::vector<uint32_t> host_triangle;     // triangle of the input mesh holding the point
    std::vector<float> bary_u, bary_v;       // weights of the host's 1st and 2nd vertex
    std::vector<float> radius;               // relevance radius, object space (§4.5)
    std::vector<uint32_t> neighbour_offsets; // size() + 1 entries
    std::vector<uint32_t> neighbours;        // relevant neighbours, as point indices
    size_t size() const { return host_triangle.size(); }
};

struct HierarchyConfig {
    uint32_t point_count = 20000;  // total points wanted (at least the welded vertex count)
    uint64_t seed = 1;             // picks which end of a collapsed edge is removed
    float weld_epsilon = 1e-6f;    // relative to the bounding-box diagonal
    // Called now and then with progress in [0, 1]; may be null.
    void (*progress)(float fraction, void* user) = nullptr;
    void* progress_user = nullptr;
};

struct HierarchyStats {
    uint32_t welded_vertices = 0;
    uint32_t skipped_faces = 0;      // degenerate after welding
    uint32_t split_vertices = 0;     // vertices duplicated to keep the mesh manifold
    uint32_t simplified_points = 0;  // points from input vertices (Alg. 4.1)
    uint32_t subdivided_points = 0;  // points from edge splits (Alg. 4.2)
};

bool build_point_hierarchy(const RawScene& scene, const HierarchyConfig& config,
                           PointHierarchy* out, HierarchyStats* stats, std::string* error);

}  // namespace stipple::bake
