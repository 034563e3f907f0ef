#include "bake/token_relaxation.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "bake/level_order.h"
#include "bake/patch_hierarchy.h"
#include "bake/point_grid.h"

namespace stipple::bake {

namespace {

// Points on the base mesh: the face each lies in and its position.
struct Centres {
    std::vector<uint32_t> face;
    std::vector<Vec3d> position;
};

double surface_area(const BaseMesh& base) {
    double area = 0;
    for (uint32_t f = 0; f < base.face_count(); ++f) area += base.area(f);
    return area;
}

// §5.1: "each polygon is assigned a random point on its surface".
Centres random_centres(const BaseMesh& base, Rng* rng) {
    Centres c;
    const uint32_t n = base.face_count();
    c.face.resize(n);
    c.position.resize(n);
    for (uint32_t f = 0; f < n; ++f) {
        const double r1 = std::sqrt(rng->uniform()), r2 = rng->uniform();  // uniform in area
        c.face[f] = f;
        c.position[f] = base.corner(f, 0) * (1 - r1) + base.corner(f, 1) * (r1 * (1 - r2)) +
                        base.corner(f, 2) * (r1 * r2);
    }
    return c;
}

// A vertex of more polygons than this is a hub (a fan's centre, a non-manifold star):
// scanning its polygons for every point in one of them is quadratic in its valence.
constexpr uint32_t kHubValence = 64;

bool touches_hub(const BaseMesh& base, uint32_t f) {
    for (int k = 0; k < 3; ++k) {
        const uint32_t v = base.faces[size_t(f) * 3 + size_t(k)];
        if (base.vf_offsets[v + 1] - base.vf_offsets[v] > kHubValence) return true;
    }
    return false;
}

bool share_vertex(const BaseMesh& base, uint32_t f, uint32_t g) {
    for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b)
            if (base.faces[size_t(f) * 3 + size_t(a)] == base.faces[size_t(g) * 3 + size_t(b)])
                return true;
    return false;
}

// Alg. 5.2's neighbours of point i (the points in polygons sharing a vertex with its host),
// in the order they are summed: by polygon, then by point. Around a hub they are found by a
// grid of cell `radius` (only those closer than the radius push), so a point costs O(1)
// there too; the set and its order are the same, so the sums are the same to the bit.
struct NeighbourSearch {
    const BaseMesh& base;
    std::vector<uint32_t> offsets, in_face, around, near;
    std::vector<double> xyz;
    PointGrid grid;
    bool hubs = false;

    void index(const Centres& c, double radius) {
        const uint32_t n = uint32_t(c.face.size());
        // Points by host polygon (counting sort, so the order is the points' order).
        offsets.assign(size_t(base.face_count()) + 1, 0);
        for (uint32_t f : c.face) ++offsets[f + 1];
        for (uint32_t f = 0; f < base.face_count(); ++f) offsets[f + 1] += offsets[f];
        in_face.resize(n);
        std::vector<uint32_t> fill(offsets.begin(), offsets.end() - 1);
        for (uint32_t i = 0; i < n; ++i) in_face[fill[c.face[i]]++] = i;
        if (!hubs) return;
        xyz.resize(size_t(n) * 3);
        for (uint32_t i = 0; i < n; ++i)
            for (int k = 0; k < 3; ++k) xyz[size_t(i) * 3 + size_t(k)] = c.position[i][k];
        grid.build(xyz.data(), n, radius);
    }

    const std::vector<uint32_t>& of(const Centres& c, uint32_t i) {
        near.clear();
        const uint32_t f = c.face[i];
        if (hubs && touches_hub(base, f)) {
            grid.visit(&xyz[size_t(i) * 3], 1, [&](uint32_t j) {
                if (share_vertex(base, f, c.face[j])) near.push_back(j);
            });
            std::sort(near.begin(), near.end(), [&](uint32_t a, uint32_t b) {
                return c.face[a] != c.face[b] ? c.face[a] < c.face[b] : a < b;
            });
            return near;
        }
        base.faces_around(f, &around);
        for (uint32_t g : around)
            near.insert(near.end(), in_face.begin() + offsets[g], in_face.begin() + offsets[g + 1]);
        return near;
    }
};

// Thesis Alg. 5.1 with the neighbours of Alg. 5.2: each point is pushed by the points
// closer than the repulsion radius among those in its host polygon and the polygons sharing
// a vertex with it (hosts are updated as points move: "the relevant neighbors is the set of
// all the points in the neighboring polygons and all the other points which share the same
// host face"); forces are computed for all points first, then all points move on the
// surface, jumping to neighbouring polygons (walk_on_surface).
void primary_relaxation(const BaseMesh& base, double area, const RelaxConfig& config,
                        const HierarchyConfig& progress, Centres* c) {
    const uint32_t n = uint32_t(c->face.size());
    const double radius = config.repulsion_k * std::sqrt(area / double(n));
    std::vector<Vec3d> step(n);
    NeighbourSearch search{base};
    for (uint32_t f = 0; f < base.face_count() && !search.hubs; ++f)
        search.hubs = touches_hub(base, f);
    for (int it = 0; it < config.primary_iterations; ++it) {
        search.index(*c, radius);
        for (uint32_t i = 0; i < n; ++i) {
            Vec3d force(0, 0, 0);
            int count = 0;
            for (uint32_t j : search.of(*c, i)) {
                const Vec3d d = c->position[i] - c->position[j];
                const double len = d.norm();
                if (j == i || len >= radius || len <= 0) continue;
                force += d * ((radius - len) / len);
                ++count;
            }
            step[i] = count ? force * (config.primary_step / count) : Vec3d(0, 0, 0);
        }
        for (uint32_t i = 0; i < n; ++i)
            if (step[i].sqrnorm() > 0) walk_on_surface(base, &c->face[i], &c->position[i], step[i]);
        progress.report("relax: primary", float(it + 1) / float(config.primary_iterations));
    }
}

// Graph token relaxation of one level (thesis Alg. 5.3). Tokens sit on nodes, the patches of
// `node_level`; `fixed` tokens (coarser levels) repel but do not move.
struct TokenLevel {
    const PatchHierarchy& h;
    const Centres& centres;
    const RelaxConfig& config;
    int level, node_level;
    double repulsion;
    std::vector<uint32_t> node;                    // per token: its node; fixed tokens first
    uint32_t fixed = 0;                            // tokens [0, fixed) do not move
    std::vector<uint32_t> occupant;                // per node: token or kNoPatch
    std::vector<uint32_t> bucket_offsets, bucket;  // tokens by patch of `level`

    const PatchLevel& nodes() const { return h.levels[size_t(node_level)]; }
    const Vec3d& at(uint32_t n) const { return centres.position[nodes().leaf[n]]; }

    void fill_buckets() {
        const PatchLevel& l = h.levels[size_t(level)];
        bucket_offsets.assign(size_t(l.size()) + 1, 0);
        std::vector<uint32_t> patch(node.size());
        for (uint32_t t = 0; t < node.size(); ++t) {
            patch[t] = h.ancestor(node_level, node[t], level);
            ++bucket_offsets[patch[t] + 1];
        }
        for (uint32_t p = 0; p < l.size(); ++p) bucket_offsets[p + 1] += bucket_offsets[p];
        bucket.resize(node.size());
        std::vector<uint32_t> fill(bucket_offsets.begin(), bucket_offsets.end() - 1);
        for (uint32_t t = 0; t < node.size(); ++t) bucket[fill[patch[t]]++] = t;
    }

    // §5.5.2: the neighbouring tokens of t are those in its patch at this level and in the
    // patches next to it; calls f(other token, its position).
    template <class F>
    void for_each_neighbour(uint32_t t, F&& f) const {
        const PatchLevel& l = h.levels[size_t(level)];
        const uint32_t p = h.ancestor(node_level, node[t], level);
        auto visit = [&](uint32_t patch) {
            for (uint32_t k = bucket_offsets[patch]; k < bucket_offsets[patch + 1]; ++k)
                if (bucket[k] != t) f(at(node[bucket[k]]));
        };
        visit(p);
        for (uint32_t k = l.neighbour_offsets[p]; k < l.neighbour_offsets[p + 1]; ++k)
            visit(l.neighbours[k]);
    }

    // §5.5.3: the mean of (R - |d|) d/|d| over the neighbouring tokens closer than the
    // repulsion radius R.
    Vec3d force_on(uint32_t t) const {
        const Vec3d here = at(node[t]);
        Vec3d force(0, 0, 0);
        int count = 0;
        for_each_neighbour(t, [&](const Vec3d& other) {
            const Vec3d d = here - other;
            const double len = d.norm();
            if (len >= repulsion) return;
            if (len > 0) force += d * ((repulsion - len) / len);
            ++count;
        });
        return count ? force / double(count) : force;
    }

    // The tension t would have at `here`: the sum of (R - |d|)^2 over the same neighbours.
    double tension_at(uint32_t t, const Vec3d& here) const {
        double e = 0;
        for_each_neighbour(t, [&](const Vec3d& other) {
            const double len = (here - other).norm();
            if (len < repulsion) e += (repulsion - len) * (repulsion - len);
        });
        return e;
    }

    // §5.5.4: the empty neighbour node most along the force, or kNoPatch.
    uint32_t target(uint32_t t, const Vec3d& force) const {
        const PatchLevel& l = nodes();
        const uint32_t from = node[t];
        uint32_t best = kNoPatch;
        double best_dot = 0;
        for (uint32_t k = l.neighbour_offsets[from]; k < l.neighbour_offsets[from + 1]; ++k) {
            const uint32_t n = l.neighbours[k];
            if (occupant[n] != kNoPatch) continue;
            const double dot = force | (at(n) - at(from));
            if (dot > best_dot) {
                best_dot = dot;
                best = n;
            }
        }
        // "Determine whether the token needs to be displaced" (Alg. 5.3): only if the move
        // lowers its own tension. Without this test a token near balance still jumps a
        // whole node along a small force, and on the crowded graphs of the finest levels
        // most tokens swap back and forth every iteration (measured: the tension stops
        // falling after 1-2 iterations; with it, nn CV 0.134 instead of 0.178 at 16k points
        // of the bunny).
        if (best != kNoPatch && tension_at(t, at(best)) >= tension_at(t, at(from))) return kNoPatch;
        return best;
    }

    // One iteration: forces and targets for every moving token, then the moves (a node
    // taken earlier in the same pass stays taken). Returns the total tension.
    double iterate(uint32_t* moved) {
        fill_buckets();
        std::vector<std::pair<uint32_t, uint32_t>> moves;
        double tension = 0;
        for (uint32_t t = fixed; t < node.size(); ++t) {
            const Vec3d f = force_on(t);
            tension += f.norm();
            if (f.sqrnorm() == 0) continue;
            const uint32_t to = target(t, f);
            if (to != kNoPatch) moves.push_back({t, to});
        }
        *moved = 0;
        for (const auto& [t, to] : moves) {
            if (occupant[to] != kNoPatch) continue;
            occupant[node[t]] = kNoPatch;
            occupant[to] = t;
            node[t] = to;
            ++*moved;
        }
        return tension;
    }

    // Alg. 5.3's loop with the limits of §5.6.2: until nothing moves, at most
    // max_iterations, or `patience` iterations without a lower total tension; the tokens
    // end where the tension was lowest.
    int relax() {
        std::vector<uint32_t> best_node = node;
        double best = 1e300;
        int since_best = 0, it = 0;
        while (it < config.max_iterations && since_best < config.patience) {
            uint32_t moved = 0;
            const double tension = iterate(&moved);
            ++it;
            if (tension < best) {
                best = tension;
                best_node = node;
                since_best = 0;
            } else {
                ++since_best;
            }
            if (moved == 0) break;
        }
        // The last tension measured belongs to the tokens before the last moves.
        fill_buckets();
        double final_tension = 0;
        for (uint32_t t = fixed; t < node.size(); ++t) final_tension += force_on(t).norm();
        if (final_tension > best) {
            for (uint32_t t = fixed; t < node.size(); ++t) occupant[node[t]] = kNoPatch;
            node = best_node;
            for (uint32_t t = fixed; t < node.size(); ++t) occupant[node[t]] = t;
        }
        return it;
    }
};

// Thesis Alg. 5.4: from the top level down, every patch of the level that holds no point yet
// gets a token on a random descendant `token_depth` levels finer (§5.5.1); the new tokens are
// relaxed on that finer graph and fixed. Returns the leaves of the points, coarse levels
// first, and each level's end.
std::vector<uint32_t> place_tokens(const PatchHierarchy& h, const Centres& centres, double area,
                                   const HierarchyConfig& config, Rng* rng,
                                   std::vector<uint32_t>* level_end, HierarchyStats* stats) {
    std::vector<uint32_t> leaves;
    const int top = int(h.levels.size()) - 1;
    for (int level = top; level >= 0; --level) {
        TokenLevel tl{
            h, centres, config.relax, level, std::max(level - config.relax.token_depth, 0), 0, {},
            0, {},      {},           {}};
        const PatchLevel& nodes = tl.nodes();
        tl.occupant.assign(nodes.size(), kNoPatch);
        const PatchLevel& patches = h.levels[size_t(level)];
        std::vector<uint32_t> has_point(patches.size(), 0);
        for (uint32_t leaf : leaves) {
            const uint32_t n = h.ancestor(0, leaf, tl.node_level);
            tl.occupant[n] = uint32_t(tl.node.size());
            tl.node.push_back(n);
            ++has_point[h.ancestor(0, leaf, level)];
        }
        tl.fixed = uint32_t(tl.node.size());
        // §5.5.1: a new token starts on a random free descendant `token_depth` levels finer.
        auto place_new_token = [&](uint32_t patch) {
            uint32_t n = patch;
            for (int tries = 0; tries < 8; ++tries) {
                n = patch;
                for (int l = level; l > tl.node_level; --l) {
                    const PatchLevel& pl = h.levels[size_t(l)];
                    const uint32_t count = pl.child_offsets[n + 1] - pl.child_offsets[n];
                    n = pl.children[pl.child_offsets[n] + rng->below(count)];
                }
                if (tl.occupant[n] == kNoPatch) break;
            }
            if (tl.occupant[n] != kNoPatch) return;
            tl.occupant[n] = uint32_t(tl.node.size());
            tl.node.push_back(n);
        };
        // "Select a number of tokens for each patch" (Alg. 5.4): as many as its share of the
        // surface, so that a level has as many tokens as patches, but small patches (where
        // the input is finely tessellated) get fewer than one and large ones more; the
        // fractions carry from patch to patch. One token per patch makes finely tessellated
        // regions denser at every level (bunny, 100k points: density CV 0.206 instead of
        // 0.164 at 1k points). Level 0 has one node per polygon: every polygon gets a point.
        double share = 0;
        uint32_t given = 0;
        for (uint32_t patch = 0; patch < patches.size(); ++patch) {
            uint32_t quota = 1;
            if (level > 0) {
                share += double(patches.size()) * patches.area[patch] / area;
                const uint32_t upto = uint32_t(std::llround(share));
                quota = upto - given;
                given = upto;
            }
            for (uint32_t q = has_point[patch]; q < quota; ++q) place_new_token(patch);
        }
        tl.repulsion = config.relax.repulsion_k * std::sqrt(area / double(tl.node.size()));
        if (tl.node_level < level && stats) stats->relax_iterations += uint32_t(tl.relax());
        for (uint32_t t = tl.fixed; t < tl.node.size(); ++t)
            leaves.push_back(nodes.leaf[tl.node[t]]);
        level_end->push_back(uint32_t(leaves.size()));
        config.report("relax: tokens", float(top - level + 1) / float(top + 1));
        if (leaves.size() >= config.point_count) break;  // finer levels are not wanted
    }
    return leaves;
}

// Writes the points in the order `order` (point ids), with their radii.
void emit(const InputSurface& surface, const BaseMesh& base, const Centres& centres,
          const std::vector<uint32_t>& leaves, const std::vector<uint32_t>& order,
          const std::vector<float>& radius, const LevelOrder& lo, PointHierarchy* out) {
    std::vector<uint32_t> rank(leaves.size());
    for (uint32_t i = 0; i < order.size(); ++i) rank[order[i]] = i;
    *out = PointHierarchy();
    out->neighbour_offsets.push_back(0);
    for (uint32_t i = 0; i < order.size(); ++i) {
        const uint32_t id = order[i], leaf = leaves[id];
        const SurfacePoint s =
            surface.locate(base.host[centres.face[leaf]], centres.position[leaf]);
        out->host_triangle.push_back(s.host);
        out->bary_u.push_back(float(s.u));
        out->bary_v.push_back(float(s.v));
        out->radius.push_back(radius[id]);
        if (lo.neighbour_offsets.empty()) continue;
        for (uint32_t k = lo.neighbour_offsets[id]; k < lo.neighbour_offsets[id + 1]; ++k)
            out->neighbours.push_back(rank[lo.neighbours[k]]);
        out->neighbour_offsets.push_back(uint32_t(out->neighbours.size()));
    }
    if (lo.neighbour_offsets.empty()) out->neighbour_offsets.assign(order.size() + 1, 0);
}

}  // namespace

void relax_hierarchy(const InputSurface& surface, const BaseMesh& base,
                     const HierarchyConfig& config, PointHierarchy* out, HierarchyStats* stats) {
    Rng rng{config.seed};
    const double area = surface_area(base);
    Centres centres = random_centres(base, &rng);

    primary_relaxation(base, area, config.relax, config, &centres);
    config.report("relax: patches", 0);
    const PatchHierarchy h = fuse_patches(base, config.relax.fusion_neighbours, &rng);
    if (stats) stats->levels = uint32_t(h.levels.size());
    std::vector<uint32_t> level_end;
    const std::vector<uint32_t> leaves =
        place_tokens(h, centres, area, config, &rng, &level_end, stats);
    config.report("relax: order", 0);
    LevelPoints lp;
    lp.level_end = level_end;
    lp.xyz.reserve(leaves.size() * 3);
    lp.normal.reserve(leaves.size() * 3);
    for (uint32_t leaf : leaves) {
        const Vec3d& p = centres.position[leaf];
        const Vec3d n = base.unit_normal(centres.face[leaf]);
        lp.xyz.insert(lp.xyz.end(), {p[0], p[1], p[2]});
        lp.normal.insert(lp.normal.end(), {n[0], n[1], n[2]});
    }
    const LevelOrder lo = order_levels(lp, area);
    if (stats) stats->neighbour_candidates += lo.candidates;
    // Radius per level (§5.3), spread inside the level by rank: the point of rank i gets
    // the region area / (i + 1) of an even prefix (runtime/stipple_size.h). Radii from the
    // neighbours' distances would step with the levels (4-5x apart in size), and tone with
    // them as the view zooms.
    std::vector<float> radius(leaves.size());
    for (uint32_t i = 0; i < lo.order.size(); ++i)
        radius[lo.order[i]] = float(std::sqrt(area / double(i + 1)));
    emit(surface, base, centres, leaves, lo.order, radius, lo, out);
    config.report("relax: order", 1);
}

void random_hierarchy(const InputSurface& surface, const BaseMesh& base,
                      const HierarchyConfig& config, PointHierarchy* out) {
    Rng rng{config.seed};
    const double area = surface_area(base);
    const Centres centres = random_centres(base, &rng);
    std::vector<uint32_t> leaves(base.face_count());
    std::iota(leaves.begin(), leaves.end(), 0u);
    std::vector<uint32_t> order = leaves;
    for (uint32_t i = uint32_t(order.size()); i > 1; --i)  // Fisher-Yates
        std::swap(order[i - 1], order[rng.below(i)]);
    // Radius of rank i: the region area / (i + 1) of an even prefix (runtime/stipple_size.h).
    std::vector<float> radius(leaves.size());
    for (uint32_t i = 0; i < order.size(); ++i)
        radius[order[i]] = float(std::sqrt(area / double(i + 1)));
    emit(surface, base, centres, leaves, order, radius, LevelOrder(), out);
}

}  // namespace stipple::bake
