// Point hierarchy on a mesh surface: each point stored as a host triangle of the input mesh +
// barycentric coordinates, a relevance radius and its list of relevant neighbours, ordered
// coarse to fine. Built by progressive sample elimination (the default, even on any
// triangulation: bake/sample_elimination.h), thesis ch. 4 (longest-edge subdivision below
// the input resolution and edge-collapse simplification above it) or ch. 5 (token
// relaxation); docs/hierarchy.md compares them.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "bake/bake_error.h"
#include "bake/raw_scene.h"

namespace stipple::bake {

struct PointHierarchy {
    std::vector<uint32_t> host_triangle;      // triangle of the input mesh holding the point
    std::vector<float> bary_u, bary_v;        // weights of the host's 1st and 2nd vertex
    std::vector<float> radius;                // relevance radius, object space (§4.5)
    std::vector<uint32_t> neighbour_offsets;  // size() + 1 entries
    std::vector<uint32_t> neighbours;         // relevant neighbours, as point indices
    std::vector<uint32_t> record_parent;  // simplify: the merge record (bake/particle_parents.h)
    size_t size() const { return host_triangle.size(); }
};

enum class HierarchyMethod {
    simplify,   // thesis ch. 4: randomize + project, simplification and legal subdivision
    random,     // naive baseline: one random point per polygon, in random order (Fig. 5.1)
    relax,      // thesis ch. 5: primary relaxation, patch hierarchy, graph token relaxation
    eliminate,  // progressive weighted sample elimination over area-uniform surface samples
                // (Yuksel 2015; bake/sample_elimination.h): even on any triangulation
};

// Token relaxation parameters (thesis ch. 5); the defaults are the thesis's.
struct RelaxConfig {
    int primary_iterations = 6;  // §5.6.2: "a constant number of six primary relaxations"
    double primary_step = 0.5;   // fraction of the mean repulsive force moved per iteration
    int fusion_neighbours = 4;   // §5.4: the smallest patch is fused with four neighbours
    int token_depth = 3;         // §5.5.1: tokens start on descendants three levels below
    int max_iterations = 50;     // §5.6.2: at most 50 iterations per level...
    int patience = 15;           // ...or 15 without a decrease of the total tension
    double repulsion_k = 1.0;    // §5.5.3: repulsionRadius = k sqrt(a / n), k in [1, 2]
    // §5.1 asks for at least one polygon per point. With exactly one, the finest level is a
    // point in every polygon and copies the input's tessellation density (the dark seams of
    // a scan at zoom 4); with more, the finest level is the part of that level taken
    // farthest first (bake/level_order.h), even wherever the input is finely tessellated.
    double polygons_per_point = 1.5;
};

// Progress of a bake phase ("simplify", "subdivide", "relax", ...) in [0, 1].
using ProgressFn = void (*)(const char* phase, float fraction, void* user);

struct HierarchyConfig {
    // The default was chosen by measurement over the corpus (docs/hierarchy.md).
    HierarchyMethod method = HierarchyMethod::eliminate;
    uint32_t point_count = 20000;  // total points wanted
    uint64_t seed = 1;             // randomization, and which end of a collapsed edge goes
    // Randomize operator range (§4.4.1, Fig. 4.11 shows 15%, 35% and 75%): a vertex moves
    // up to this fraction of the way towards the other corners of a random incident face.
    float jitter = 0.35f;
    float weld_epsilon = 1e-6f;  // relative to the bounding-box diagonal
    RelaxConfig relax;
    // Called now and then with the current phase and its progress; may be null.
    ProgressFn progress = nullptr;
    void* progress_user = nullptr;

    void report(const char* phase, float fraction) const {
        if (progress) progress(phase, fraction, progress_user);
    }
};

struct HierarchyStats {
    uint32_t welded_vertices = 0;
    uint32_t skipped_faces = 0;               // degenerate after welding
    uint32_t split_vertices = 0;              // vertices duplicated to keep the mesh manifold
    uint32_t simplified_points = 0;           // points from input vertices (Alg. 4.1)
    uint32_t subdivided_points = 0;           // points from edge splits (Alg. 4.2)
    uint32_t discarded_randomizations = 0;    // moves undone: they folded a face or made a sliver
    uint32_t legal_splits = 0;                // extra splits made by refineLocal (Alg. 4.3)
    uint32_t slivers_before_subdivision = 0;  // faces with an angle < 10 deg, randomized input
    uint32_t slivers_after_subdivision = 0;   // the same after subdivision
    uint32_t levels = 0;            // relax: levels of the patch hierarchy; eliminate: halvings
    uint32_t relax_iterations = 0;  // relax: token relaxation iterations, all levels
    // simplify, relax: input triangles examined by the projections (bake/surface_projection.h;
    // a work counter: it grows linearly with the mesh whatever its connectivity).
    uint64_t projection_candidates = 0;
    // eliminate, relax: samples examined by the neighbour searches of the eliminations, points
    // by the level order's and relevant-neighbour searches (a work counter, linear whatever
    // the connectivity: crowded places take the k nearest, bake/point_hierarchy_nearest.h).
    uint64_t neighbour_candidates = 0;
};

// Errors: malformed_input (no triangles, a non-finite position, an index out of range, no
// surface area), invalid_option (a point count of 0), out_of_memory. `stats` may be null.
[[nodiscard]] BakeError build_point_hierarchy(const RawScene& scene, const HierarchyConfig& config,
                                              PointHierarchy* out, HierarchyStats* stats);

}  // namespace stipple::bake
