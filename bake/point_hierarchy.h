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

enum class HierarchyMethod {
    simplify,  // thesis ch. 4: randomize + project, simplification and legal subdivision
    random,    // naive baseline: uniformly random surface points in random order
    relax,     // thesis ch. 5: patch hierarchy + graph token relaxation
};

struct HierarchyConfig {
    HierarchyMethod method = HierarchyMethod::simplify;
    uint32_t point_count = 20000;  // total points wanted
    uint64_t seed = 1;             // randomization, and which end of a collapsed edge goes
    // Randomize operator range (§4.4.1, Fig. 4.11 shows 15%, 35% and 75%): a vertex moves
    // up to this fraction of the way towards the other corners of a random incident face.
    float jitter = 0.35f;
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
    uint32_t discarded_randomizations = 0;  // moves undone because they folded the mesh
    uint32_t legal_splits = 0;       // extra splits made by refineLocal (Alg. 4.3)
};

bool build_point_hierarchy(const RawScene& scene, const HierarchyConfig& config,
                           PointHierarchy* out, HierarchyStats* stats, std::string* error);

}  // namespace stipple::bake
