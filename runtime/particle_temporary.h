// Temporary particles on triangles (GI'01 §5: "we would like to add temporary particles on
// triangles ... so that strokes don't tear open up close"): the particle tree continued past
// the finest baked level with the run-time refinement's extra points (runtime/
// point_refinement.h, docs/tone.md), so a close-up of an ordinary bake keeps its stroke density.
//
//   - Which points: the refinement's own sequence on the render mesh: the k-th extra point of
//     triangle t lies at refinement_barycentric(t, k) with region 1 / (rho_t + (k + phase_t) /
//     a_t), the hierarchy's A / i law continued per triangle (rho_t the baked density there).
//   - Their place in the tree: the extra points are ranked by the index their region stands for
//     (A / region), so they continue the hierarchy's coarse-to-fine order after the baked
//     points: they first complete the partly baked finest level, then fill whole levels beyond
//     it. The tree's rule (runtime/particle_tree.h) gives each its parent: the nearest point of
//     the level above, a baked point of the finest levels or an extra point of the level before.
//   - Ids: temporary particle N + j is the refinement's point (triangle[j], rank[j]), the same
//     every frame and every run for an asset and a budget (a stable id for the strokes CSV).
//   - Memory: the budget (the tree's total size) is fixed at init; the extended points cost 24
//     bytes each here, and the particle stage's per-particle buffers grow with them. A frame
//     only visits the particles unfolded, so dormant temporary ones cost nothing per frame.
#pragma once
#include <cstdint>

#include "runtime/asset.h"
#include "runtime/memory.h"
#include "runtime/status.h"

namespace stipple {

// Default size of the particle tree, baked and temporary together: four levels past the
// default bake's finest complete one (4^9: a 20,000-point bake holds its density to zoom 8).
constexpr uint32_t kDefaultParticleTreePoints = 262144;

struct TemporaryParticles {
    uint32_t baked = 0;  // the asset's points: particles [0, baked)
    uint32_t count = 0;  // baked + temporary
    // The extended points (count entries: the baked ones copied, then the temporary ones).
    Buffer<uint32_t> host_triangle;
    Buffer<float> bary_u, bary_v, radius;
    // Per temporary particle (count - baked): its refinement id (mesh triangle, rank k).
    Buffer<uint32_t> triangle, rank;
    // Radius scale: the baked radii of the finest levels over the A / i law (fitted at init, so
    // the temporary particles continue the baked ones' unfolding thresholds).
    float radius_scale = 1.0f;
    PointsView view;  // over the arrays above (no neighbours)
};

// Continues the asset's points with temporary particles up to `total` points (nothing to add
// when total <= the baked count: the view is then the asset's own points). Fails with
// out_of_memory.
[[nodiscard]] Status temporary_particles_build(TemporaryParticles* t, const Asset& asset,
                                               uint32_t total);

// Points of `view` placed on the mesh's bind pose (Thesis Alg. 6.3 unposed): 3 floats each.
void particle_bind_positions(const MeshView& mesh, const PointsView& view, float* out);

}  // namespace stipple
