#include "runtime/particle_adjust.h"

#include <algorithm>

namespace stipple {

namespace {

// Joined this frame, waiting for its decision in a later round (not asked in the first).
constexpr uint8_t kParticleQueued = 8;
// Rounds of decisions per frame after the first: how many levels one frame may unfold.
constexpr int kMaxRounds = 64;

bool parent_shows(const ParticleSet& s, const ParticleTree& t, uint32_t p) {
    const uint32_t q = t.parent[p];
    constexpr uint8_t kShows = kParticleActive | kParticleUnfolded;
    return q == kNoParent || (s.state[q] & kShows) == kShows;
}

// New members this frame (born: not listed before) and the next round's questions.
struct Joins {
    uint32_t born = 0, queued = 0;
};

// Unfolds p: its children join the active set and are asked about in the next round. Within
// the list's capacity only: a node whose children would overflow it stays folded (asked again
// next frame), so the list holds the coarse-to-fine rounds' first list_capacity particles.
void unfold(ParticleSet* s, const ParticleTree& t, uint32_t p, Joins* j) {
    const uint32_t children = t.child_begin[p + 1] - t.child_begin[p];
    if (s->list_capacity < s->capacity &&
        uint64_t(s->count) + j->born + children > s->list_capacity)
        return;
    s->state[p] |= kParticleUnfolded;
    for (uint32_t k = t.child_begin[p]; k < t.child_begin[p + 1]; ++k) {
        const uint32_t c = t.children[k];
        uint8_t& st = s->state[c];
        if (st & kParticleActive) continue;
        if (!(st & kParticleListed)) {
            s->born[j->born++] = c;
            s->alpha[c] = 0.0f;
        }
        st |= kParticleActive | kParticleListed | kParticleQueued;
        s->queue[j->queued++] = c;
        ++s->joined;
    }
}

// Asks `decide` about ids[0 .. n) and keeps the answers in want[id].
void ask_about(ParticleSet* s, const uint32_t* ids, uint32_t n, ParticleDecideFn decide,
               void* user) {
    if (n == 0) return;
    uint8_t* answer = s->want.get() + s->capacity;  // past the ids: answers in ids' order
    std::fill(answer, answer + n, uint8_t(0));
    decide(ids, n, answer, user);
    for (uint32_t k = 0; k < n; ++k) s->want[ids[k]] = answer[k] != 0;
    s->asked += n;
}

// The first pass, over the listed particles in ascending order, so that a parent is settled
// before its children: members whose parent no longer shows them leave (and fold, so their
// own children leave later in the same pass); the others fold or unfold as decided.
void settle(ParticleSet* s, const ParticleTree& t, Joins* j) {
    for (uint32_t i = 0; i < s->count; ++i) {
        const uint32_t p = s->list[i];
        if (p >= t.count) break;  // extra members (ascending, after the tree's): the caller's
        uint8_t& st = s->state[p];
        if (!(st & kParticleActive) || (st & kParticleQueued)) continue;
        if (!parent_shows(*s, t, p)) {
            st &= uint8_t(~(kParticleActive | kParticleUnfolded));
            ++s->left;
        } else if (s->want[p] && !(st & kParticleUnfolded)) {
            unfold(s, t, p, j);
        } else if (!s->want[p] && (st & kParticleUnfolded)) {
            st &= uint8_t(~kParticleUnfolded);
        }
    }
}

// Further rounds: the particles that just joined are asked, and those that unfold bring
// their children into the next round.
void unfold_rounds(ParticleSet* s, const ParticleTree& t, ParticleDecideFn decide, void* user,
                   Joins* j) {
    for (int round = 0; round < kMaxRounds && j->queued > 0; ++round) {
        const uint32_t n = j->queued;
        std::copy(s->queue.get(), s->queue.get() + n, s->ask.get());
        std::sort(s->ask.get(), s->ask.get() + n);
        j->queued = 0;
        ask_about(s, s->ask.get(), n, decide, user);
        for (uint32_t k = 0; k < n; ++k) {
            const uint32_t p = s->ask[k];
            s->state[p] &= uint8_t(~kParticleQueued);
            if (s->want[p]) unfold(s, t, p, j);
        }
    }
    for (uint32_t k = 0; k < j->queued; ++k)  // past the round limit: asked next frame
        s->state[s->queue[k]] &= uint8_t(~kParticleQueued);
}

// Advances p's fade; false when it has faded out (it leaves the list). The first frame has
// nothing to fade from: what it shows shows at once.
bool fade(ParticleSet* s, uint32_t p) {
    float& a = s->alpha[p];
    if (!s->settled && (s->state[p] & kParticleActive)) {
        a = 1.0f;
        return true;
    }
    if (s->state[p] & kParticleActive) {
        a = std::min(a + s->fade_step, 1.0f);
        return true;
    }
    a -= s->fade_step;
    if (a > 0.0f) return true;
    a = 0.0f;
    s->state[p] &= uint8_t(~kParticleListed);
    return false;
}

// The new list: the old members still listed merged with the born ones, ascending.
void merge_list(ParticleSet* s, uint32_t born) {
    std::sort(s->born.get(), s->born.get() + born);
    uint32_t i = 0, b = 0, n = 0, active = 0;
    while (i < s->count || b < born) {
        uint32_t p;
        if (b >= born || (i < s->count && s->list[i] < s->born[b]))
            p = s->list[i++];
        else
            p = s->born[b++];
        if (!fade(s, p)) continue;
        s->next[n++] = p;
        active += (s->state[p] & kParticleActive) != 0;
    }
    s->list.swap(s->next);
    s->count = n;
    s->active_count = active;
    s->settled = true;
}

}  // namespace

Status particle_set_init(ParticleSet* set, const ParticleTree& tree, int fade_frames,
                         uint32_t list_capacity, uint32_t extra_ids) {
    *set = ParticleSet();
    if (fade_frames < 1 || fade_frames > 255)
        return make_status(StatusCode::invalid_argument, "fade frames %d is outside [1, 255]",
                           fade_frames);
    const size_t n = size_t(tree.count) + extra_ids;
    const size_t m =
        list_capacity == 0 ? n : std::min<size_t>(n, std::max(list_capacity, tree.root_count));
    set->state = make_buffer<uint8_t>(n);
    set->want = make_buffer<uint8_t>(n + m);
    set->alpha = make_buffer<float>(n);
    set->list = make_buffer<uint32_t>(m);
    set->next = make_buffer<uint32_t>(m);
    set->ask = make_buffer<uint32_t>(m);
    set->born = make_buffer<uint32_t>(m);
    set->queue = make_buffer<uint32_t>(m);
    if (!set->state || !set->want || !set->alpha || !set->list || !set->next || !set->ask ||
        !set->born || !set->queue)
        return make_status(StatusCode::out_of_memory, "out of memory for %zu particles", n);
    std::fill(set->state.get(), set->state.get() + n, uint8_t(0));
    std::fill(set->want.get(), set->want.get() + n + m, uint8_t(0));
    std::fill(set->alpha.get(), set->alpha.get() + n, 0.0f);
    set->capacity = uint32_t(n);
    set->tree_count = tree.count;
    set->list_capacity = uint32_t(m);
    set->fade_step = 1.0f / float(fade_frames);
    for (uint32_t r = 0; r < tree.root_count; ++r) {
        const uint32_t p = tree.roots[r];
        set->state[p] = kParticleActive | kParticleListed;
        set->alpha[p] = 1.0f;
        set->list[set->count++] = p;
    }
    set->active_count = set->count;
    return {};
}

void particles_adjust_tree(ParticleSet* set, const ParticleTree& tree, ParticleDecideFn decide,
                           void* user) {
    set->joined = set->left = set->asked = 0;
    uint32_t n = 0;
    for (uint32_t i = 0; i < set->count && set->list[i] < tree.count; ++i)
        if (set->state[set->list[i]] & kParticleActive) set->ask[n++] = set->list[i];
    ask_about(set, set->ask.get(), n, decide, user);
    Joins joins;
    settle(set, tree, &joins);
    unfold_rounds(set, tree, decide, user, &joins);
    set->born_count = joins.born;
}

void particles_adjust_finish(ParticleSet* set) {
    merge_list(set, set->born_count);
    set->born_count = 0;
}

void particles_adjust(ParticleSet* set, const ParticleTree& tree, ParticleDecideFn decide,
                      void* user) {
    particles_adjust_tree(set, tree, decide, user);
    particles_adjust_finish(set);
}

uint32_t particle_set_room(const ParticleSet& set) {
    const uint64_t used = uint64_t(set.count) + set.born_count;
    return used >= set.list_capacity ? 0u : uint32_t(set.list_capacity - used);
}

bool particle_set_join(ParticleSet* set, uint32_t id) {
    uint8_t& st = set->state[id];
    if (st & kParticleActive) return true;
    if (!(st & kParticleListed)) {
        if (particle_set_room(*set) == 0) return false;
        set->born[set->born_count++] = id;
        set->alpha[id] = 0.0f;
    }
    st |= kParticleActive | kParticleListed;
    ++set->joined;
    return true;
}

void particle_set_leave(ParticleSet* set, uint32_t id) {
    uint8_t& st = set->state[id];
    if (!(st & kParticleActive)) return;
    st &= uint8_t(~(kParticleActive | kParticleUnfolded));
    ++set->left;
}

}  // namespace stipple
