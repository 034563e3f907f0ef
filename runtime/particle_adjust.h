// Stage 1 of view-dependent particles, "adjust particles" (GI'01 §2): the active set of the
// particle tree (runtime/particle_tree.h) persists from frame to frame, and each frame a
// style's callback decides, for the particles it is asked about, whether each should be
// unfolded (its children join the active set) or folded (its descendants leave it). Only the
// active set and what changes are visited, so the cost follows the particles drawn, not the
// tree. Particles fade in when they join and fade out when they leave, by a fixed step per
// frame (GI'01 §5: "fading in over several frames the strokes associated with newly created
// particles ... by adding an age field to each particle"), so nothing pops.
// All memory is taken at init; adjusting allocates nothing.
#pragma once
#include <cstdint>

#include "runtime/memory.h"
#include "runtime/particle_tree.h"
#include "runtime/status.h"

namespace stipple {

// Per-particle state bits.
enum : uint8_t {
    kParticleActive = 1,    // in the active set (its parent is active and unfolded, or a root)
    kParticleUnfolded = 2,  // its children are active
    kParticleListed = 4,    // in ParticleSet::list: active, or fading out with alpha > 0
};

// The style's adjust criterion: for each of `count` particles (`ids`, ascending), write 1 to
// unfold[k] if particle ids[k] should show its children this frame, 0 if it should not.
// Called a few times per frame: first for the whole active set, then for the particles that
// joined it, so a zoom unfolds as deep as it needs within one frame.
using ParticleDecideFn = void (*)(const uint32_t* ids, uint32_t count, uint8_t* unfold, void* user);

struct ParticleSet {
    uint32_t capacity = 0;  // ids: the tree's particles, then the caller's extra ids
    // Ids below tree_count are the tree's; ids from tree_count on are members the caller adds
    // and removes itself each frame (particle_set_join / particle_set_leave: the temporary
    // particles of runtime/particle_temporary.h), which fade like the tree's.
    uint32_t tree_count = 0;
    // The most particles listed at once (the per-frame budget): the list and stage 1's scratch
    // are this long, and a node whose children would overflow it stays folded this frame.
    uint32_t list_capacity = 0;
    float fade_step = 0.25f;  // opacity gained or lost per frame (1 / fade frames)
    Buffer<uint8_t> state;    // kParticle* bits, per particle
    Buffer<uint8_t> want;     // last decision, per particle
    Buffer<float> alpha;      // opacity in [0, 1], per particle
    // The listed particles (active or fading out), ascending; `next` is the merge target.
    Buffer<uint32_t> list, next;
    uint32_t count = 0;
    bool settled = false;  // false until the first adjust: its joins show at once (no fade)
    Buffer<uint32_t> ask, born, queue;  // scratch: decisions asked, new members, next round
    uint32_t born_count = 0;            // new members waiting for particles_adjust_finish
    // Of the last adjust:
    uint32_t active_count = 0;      // particles in the active set
    uint32_t joined = 0, left = 0;  // particles that joined or left the active set
    uint32_t asked = 0;             // decisions asked
};

// Takes the set's memory for `tree` and activates its roots. The first adjust shows what it
// unfolds at full opacity (there is nothing to fade from); later ones fade. fade_frames in [1,
// 255]: frames a fade takes. list_capacity: the most particles listed at once (0: the whole
// tree; at least the roots are listed). extra_ids: ids past the tree, [tree.count, tree.count +
// extra_ids), that the caller adds and removes (particle_set_join).
[[nodiscard]] Status particle_set_init(ParticleSet* set, const ParticleTree& tree, int fade_frames,
                                       uint32_t list_capacity = 0, uint32_t extra_ids = 0);

// One frame of stage 1: asks `decide` about the active set, folds and unfolds, advances the
// fades. Afterwards set->list[0 .. count) are the particles to draw, each at alpha[id].
// Equivalent to particles_adjust_tree then particles_adjust_finish.
void particles_adjust(ParticleSet* set, const ParticleTree& tree, ParticleDecideFn decide,
                      void* user);

// The same frame in two halves, so that extra members can join or leave in between: the
// tree's half (asks, folds, unfolds; its new members wait in born) ...
void particles_adjust_tree(ParticleSet* set, const ParticleTree& tree, ParticleDecideFn decide,
                           void* user);
// ... and the merge of the new members into the list with every member's fade.
void particles_adjust_finish(ParticleSet* set);

// Between the halves: extra id `id` (>= tree_count) is active this frame. A member fading out
// fades back in from where it is; a new one starts at opacity 0 (or at once on the first
// frame). False, and nothing changes, when the list has no room for a new member.
bool particle_set_join(ParticleSet* set, uint32_t id);
// Extra id `id` is no longer active: it fades out, and leaves the list when it has (its
// kParticleListed bit clears in particles_adjust_finish).
void particle_set_leave(ParticleSet* set, uint32_t id);
// New members the list still has room for this frame.
uint32_t particle_set_room(const ParticleSet& set);

}  // namespace stipple
