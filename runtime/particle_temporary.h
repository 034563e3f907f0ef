// Temporary particles on triangles (GI'01 §5: "we would like to add temporary particles on
// triangles ... so that strokes don't tear open up close"), generated per view: the particle
// tree continued past the finest baked level with the run-time refinement's extra points
// (runtime/point_refinement.h, docs/tone.md), only where the view needs them.
//
//   - Which points: the refinement's own sequence on the render mesh: the k-th extra point of
//     triangle t lies at refinement_barycentric(t, k) with region 1 / (rho_t + (k + phase_t) /
//     a_t), the hierarchy's A / i law continued per triangle (rho_t the baked density there).
//   - When: rank k of triangle t shows while its relevance radius, projected at the triangle's
//     nearest corner, is larger than the style's spacing (the tree's own criterion, GI'01 §2:
//     a node's children show while half its projected radius, about their own radius, exceeds
//     the target), with the tree's 15% hysteresis. Since the region shrinks with k, a
//     triangle shows a prefix of ranks [0, n_t), so the need is one count per triangle. Only
//     triangles in the view (with a stroke's margin) and facing the eye or near the silhouette
//     count; the others need none.
//   - Slots: a fixed pool taken at init (particle_stage_init's tree size minus the bake). A
//     slot holds one (triangle, rank) while that rank is shown or fading out; its particle id
//     is baked + slot, distinct from the baked ids and the same every frame while it lives
//     (stroke coherence, fades: they join and leave the particle set like the tree's
//     particles, runtime/particle_adjust.h). A slot is freed once its particle has faded out
//     (its triangle left the view, or the rank is no longer needed: a fold), and reused by the
//     next rank that needs one. Everything runs in ascending order from a LIFO free list, so
//     the ids are deterministic.
//   - Budget: when the ranks wanted (and those still fading out) exceed the slots, or the
//     list's room, the spacing is raised for every triangle by the same factor, found by
//     bisection, until they fit: the coarsest ranks on screen keep their slots (priority by
//     screen-space need), and the density falls evenly where the view is finest.
// Memory is taken at init; a frame allocates nothing.
#pragma once
#include <cstdint>
#include <glm/glm.hpp>

#include "runtime/asset.h"
#include "runtime/memory.h"
#include "runtime/particle_adjust.h"
#include "runtime/point_refinement.h"
#include "runtime/status.h"

namespace stipple {

struct ParticleFrame;
struct ParticleStyle;

// Default size of the particle ids, baked and temporary slots together (4^9). Per view, a
// 20,000-point bake at 640x480 needs about 10% of the slots at zoom 8 (docs/particles.md).
constexpr uint32_t kDefaultParticleTreePoints = 262144;

// A slot holding no (triangle, rank).
constexpr uint32_t kFreeSlot = 0xFFFFFFFFu;

struct TemporaryStats {
    uint32_t live = 0;          // slots holding a (triangle, rank)
    uint32_t shown = 0;         // ranks shown (active) this frame
    uint32_t triangles = 0;     // triangles in view that were asked
    uint64_t wanted = 0;        // ranks the view asked for before the budget
    float budget_scale = 1.0f;  // spacing factor the budget imposed (1: it did not bind)
};

struct TemporaryParticles {
    uint32_t baked = 0;  // the asset's points: particles [0, baked)
    uint32_t slots = 0;  // temporary particles: ids [baked, baked + slots)
    uint32_t count = 0;  // baked + slots
    // Per id: the baked points copied, then each slot's (written when it is taken).
    Buffer<uint32_t> host_triangle;
    Buffer<float> bary_u, bary_v, radius;
    // Per slot: its refinement id (mesh triangle, rank k; triangle kFreeSlot when free) and
    // the slot of rank k - 1 of the same triangle (a triangle's slots, linked from its tail).
    Buffer<uint32_t> triangle, rank, prev;
    Buffer<uint32_t> free_slots;  // LIFO
    uint32_t free_count = 0;
    // Per triangle: ranks held in slots ([0, linked)), the slot of the last, ranks shown
    // ([0, shown)), and this frame's need (density threshold at unit spacing, 0 when culled).
    Buffer<uint32_t> linked, tail, shown;
    Buffer<float> need;
    Buffer<uint32_t> touched;  // this frame's triangles in view or holding slots, ascending
    uint32_t touched_count = 0;
    // Per vertex scratch of a frame: clip position, frustum outcode, N.V.
    Buffer<glm::vec4> clip;
    Buffer<uint8_t> outside;
    Buffer<float> facing;
    uint32_t vertex_count = 0;
    RefinementMesh mesh;  // the refinement's bind tables (areas, densities, phases, cells)
    // Radius scale: the baked radii of the finest levels over the A / i law (fitted at init, so
    // the temporary particles continue the baked ones' unfolding thresholds).
    float radius_scale = 1.0f;
    PointsView view;  // over the arrays above (no neighbours)
    TemporaryStats stats;
};

// Takes `total` - baked slots (none when total <= the baked count: the view is then the
// asset's own points) and the per-triangle tables. Fails with out_of_memory.
[[nodiscard]] Status temporary_particles_build(TemporaryParticles* t, const Asset& asset,
                                               uint32_t total);

// One frame, between particles_adjust_tree and particles_adjust_finish: the ranks this view
// needs join `set` (taking free slots), the others leave it (they fade out).
void temporary_particles_update(TemporaryParticles* t, ParticleSet* set, const ParticleFrame& f,
                                const ParticleStyle& style);

// After particles_adjust_finish: slots whose particle has faded out of the list are freed.
void temporary_particles_release(TemporaryParticles* t, ParticleSet* set);

// Points of `view` placed on the mesh's bind pose (Thesis Alg. 6.3 unposed): 3 floats each.
void particle_bind_positions(const MeshView& mesh, const PointsView& view, float* out);

}  // namespace stipple
