#include "bake/token_relaxation.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>

namespace stipple::bake {

namespace {

constexpr uint32_t kNone = 0xFFFFFFFFu;

uint64_t next_random(uint64_t* state) {
    uint64_t z = (*state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

struct Patch {
    int level = 0;
    uint32_t parent = kNone;
    std::vector<uint32_t> children;
    std::vector<uint32_t> neighbours;  // patches of the same level sharing a border
    double area = 0;
    Vec3d lo, hi;
    uint32_t leaf = 0;  // the base patch whose centre is this patch's centre (§5.4)
};

double box_span(const Vec3d& lo, const Vec3d& hi) {
    return (hi - lo).norm();
}

// Thesis Alg. 5.1 with the neighbours of Alg. 5.2 (polygons around the polygon, here its
// edge neighbours and theirs): each centre is pushed away from the centres closer than
// the repulsion radius and moved on the surface (projected back onto the input triangles
// around its host, so it can "jump" to a neighbouring polygon).
void primary_relaxation(const InputSurface& surface, std::vector<BasePatch>* base, double area,
                        int iterations) {
    std::vector<BasePatch>& b = *base;
    const double radius = std::sqrt(area / double(b.size()));
    std::vector<Vec3d> step(b.size());
    std::vector<uint32_t> around;
    for (int it = 0; it < iterations; ++it) {
        for (size_t f = 0; f < b.size(); ++f) {
            around.clear();
            for (int i = 0; i < b[f].neighbour_count; ++i) {
                const uint32_t n = b[f].neighbours[i];
                around.push_back(n);
                for (int j = 0; j < b[n].neighbour_count; ++j) around.push_back(b[n].neighbours[j]);
            }
            std::sort(around.begin(), around.end());
            around.erase(std::unique(around.begin(), around.end()), around.end());
            Vec3d force(0, 0, 0);
            int count = 0;
            for (uint32_t n : around) {
                if (n == f) continue;
                const Vec3d d = b[f].centre.position - b[n].centre.position;
                const double len = d.norm();
                if (len >= radius || len <= 0) continue;
                force += d * ((radius - len) / len);
                ++count;
            }
            step[f] = count ? force * (0.5 / count) : Vec3d(0, 0, 0);
        }
        for (size_t f = 0; f < b.size(); ++f) {
            if (step[f].sqrnorm() == 0) continue;
            const uint32_t host = b[f].centre.host;
            b[f].centre =
                surface.project(b[f].centre.position + step[f], surface.normal(host), &host, 1);
        }
    }
}

// §5.4: repeatedly fuse the smallest unfused patch with up to four unfused neighbours that
// keep the bounding box smallest, level after level, until fewer than 10 patches remain.
std::vector<std::vector<uint32_t>> fuse_patches(const std::vector<BasePatch>& base,
                                                std::vector<Patch>* patches, uint64_t* rng) {
    std::vector<Patch>& p = *patches;
    std::vector<std::vector<uint32_t>> levels(1);
    p.resize(base.size());
    for (uint32_t i = 0; i < base.size(); ++i) {
        p[i].area = base[i].area;
        p[i].lo = base[i].lo;
        p[i].hi = base[i].hi;
        p[i].leaf = i;
        p[i].neighbours.assign(base[i].neighbours, base[i].neighbours + base[i].neighbour_count);
        levels[0].push_back(i);
    }
    while (levels.back().size() >= 10) {
        std::vector<uint32_t> order = levels.back();
        std::stable_sort(order.begin(), order.end(),
                         [&](uint32_t a, uint32_t b) { return p[a].area < p[b].area; });
        std::vector<uint32_t> next;
        const int level = int(levels.size());
        for (uint32_t id : order) {
            if (p[id].parent != kNone) continue;
            Patch fused;
            fused.level = level;
            fused.children = {id};
            fused.lo = p[id].lo;
            fused.hi = p[id].hi;
            const uint32_t fused_id = uint32_t(p.size());
            p[id].parent = fused_id;
            while (fused.children.size() < 5) {
                uint32_t best = kNone;
                double best_span = 1e300;
                for (uint32_t c : fused.children)
                    for (uint32_t n : p[c].neighbours) {
                        if (p[n].parent != kNone) continue;
                        Vec3d lo = fused.lo, hi = fused.hi;
                        lo.minimize(p[n].lo);
                        hi.maximize(p[n].hi);
                        const double span = box_span(lo, hi);
                        if (span < best_span || (span == best_span && n < best)) {
                            best_span = span;
                            best = n;
                        }
                    }
                if (best == kNone) break;
                p[best].parent = fused_id;
                fused.children.push_back(best);
                fused.lo.minimize(p[best].lo);
                fused.hi.maximize(p[best].hi);
            }
            for (uint32_t c : fused.children) fused.area += p[c].area;
            fused.leaf = p[fused.children[next_random(rng) % fused.children.size()]].leaf;
            p.push_back(fused);
            next.push_back(fused_id);
        }
        for (uint32_t id : next) {
            std::vector<uint32_t> n;
            for (uint32_t c : p[id].children)
                for (uint32_t cn : p[c].neighbours)
                    if (p[cn].parent != id) n.push_back(p[cn].parent);
            std::sort(n.begin(), n.end());
            n.erase(std::unique(n.begin(), n.end()), n.end());
            p[id].neighbours = std::move(n);
        }
        if (next.size() == levels.back().size()) break;  // nothing fused: stop
        levels.push_back(std::move(next));
    }
    return levels;
}

uint32_t ancestor(const std::vector<Patch>& p, uint32_t id, int level) {
    while (p[id].level < level && p[id].parent != kNone) id = p[id].parent;
    return id;
}

// Tokens on the nodes around `node` (graph search over patches of the node's level whose
// centres lie within `reach`), nearest first, at most `limit`.
void tokens_around(const std::vector<Patch>& p, const std::vector<BasePatch>& base,
                   const std::vector<uint32_t>& occupant, uint32_t node, double reach,
                   std::vector<uint32_t>* visited, std::vector<uint32_t>* mark, uint32_t stamp,
                   std::vector<std::pair<double, uint32_t>>* found) {
    found->clear();
    visited->clear();
    visited->push_back(node);
    (*mark)[node] = stamp;
    const Vec3d origin = base[p[node].leaf].centre.position;
    for (size_t i = 0; i < visited->size() && visited->size() < 600; ++i) {
        const uint32_t at = (*visited)[i];
        if (at != node && occupant[at] != kNone)
            found->push_back({(base[p[at].leaf].centre.position - origin).norm(), occupant[at]});
        for (uint32_t n : p[at].neighbours) {
            if ((*mark)[n] == stamp) continue;
            (*mark)[n] = stamp;
            if ((base[p[n].leaf].centre.position - origin).norm() <= reach) visited->push_back(n);
        }
    }
    std::sort(found->begin(), found->end());
}

}  // namespace

void relax_hierarchy(const InputSurface& surface, std::vector<BasePatch> base, uint64_t seed,
                     int primary_iterations, PointHierarchy* out, RelaxationStats* stats) {
    uint64_t rng = seed;
    double area = 0;
    for (const BasePatch& b : base) area += b.area;
    primary_relaxation(surface, &base, area, primary_iterations);
    std::vector<Patch> p;
    const std::vector<std::vector<uint32_t>> levels = fuse_patches(base, &p, &rng);
    if (stats) stats->levels = int(levels.size());

    // Points in creation order (coarse levels first): the leaf whose centre they sit on,
    // their radius and neighbours.
    std::vector<uint32_t> point_leaf;
    std::vector<double> point_radius;
    std::vector<std::vector<uint32_t>> point_neighbours;
    std::vector<uint32_t> occupant(p.size(), kNone), mark(p.size(), 0), visited;
    std::vector<std::pair<double, uint32_t>> found;
    uint32_t stamp = 0;
    std::vector<uint32_t> level_end;  // points created up to each level, coarse to fine

    // Thesis Alg. 5.4: from the top level down, add a token for every patch that holds none,
    // relax the new tokens on the graph three levels finer (Alg. 5.3), then fix them.
    for (int level = int(levels.size()) - 1; level >= 0; --level) {
        const int node_level = std::max(level - 3, 0);
        const std::vector<uint32_t>& nodes = levels[size_t(node_level)];
        for (uint32_t n : nodes) occupant[n] = kNone;
        std::vector<uint32_t> has_point(p.size(), 0);
        for (uint32_t i = 0; i < point_leaf.size(); ++i) {
            occupant[ancestor(p, point_leaf[i], node_level)] = i;
            has_point[ancestor(p, point_leaf[i], level)] = 1;
        }
        // §5.5.1: each new token starts on a random descendant of its patch.
        std::vector<uint32_t> token_node;
        for (uint32_t patch : levels[size_t(level)]) {
            if (has_point[patch]) continue;
            uint32_t node = patch;
            for (int tries = 0; tries < 8; ++tries) {
                node = patch;
                while (p[node].level > node_level)
                    node = p[node].children[next_random(&rng) % p[node].children.size()];
                if (occupant[node] == kNone) break;
            }
            if (occupant[node] != kNone) continue;
            occupant[node] = uint32_t(point_leaf.size() + token_node.size());
            token_node.push_back(node);
        }
        const uint32_t first_new = uint32_t(point_leaf.size());
        const double count = double(point_leaf.size() + token_node.size());
        const double repulsion = std::sqrt(area / count);  // §5.5.3, k = 1
        const double reach = 2.0 * repulsion;
        if (node_level < level) {
            size_t previous = SIZE_MAX;
            for (int it = 0; it < 30; ++it) {
                std::vector<std::pair<uint32_t, uint32_t>> moves;  // token, target node
                for (uint32_t t = 0; t < token_node.size(); ++t) {
                    const uint32_t at = token_node[t];
                    tokens_around(p, base, occupant, at, reach, &visited, &mark, ++stamp, &found);
                    const Vec3d here = base[p[at].leaf].centre.position;
                    Vec3d force(0, 0, 0);
                    int forces = 0;
                    for (const auto& [d, other] : found) {
                        if (d >= repulsion) break;
                        const uint32_t other_node = other < first_new
                                                        ? ancestor(p, point_leaf[other], node_level)
                                                        : token_node[other - first_new];
                        const Vec3d away = here - base[p[other_node].leaf].centre.position;
                        if (d > 0) force += away * ((repulsion - d) / d);
                        ++forces;
                    }
                    if (forces == 0 || force.sqrnorm() == 0) continue;
                    // §5.5.4: pass the token to the empty neighbour most along the force.
                    uint32_t best = kNone;
                    double best_dot = 0;
                    for (uint32_t n : p[at].neighbours) {
                        if (occupant[n] != kNone) continue;
                        const double dot = force | (base[p[n].leaf].centre.position - here);
                        if (dot > best_dot) {
                            best_dot = dot;
                            best = n;
                        }
                    }
                    if (best != kNone) moves.push_back({t, best});
                }
                size_t moved = 0;
                for (const auto& [t, target] : moves) {
                    if (occupant[target] != kNone) continue;
                    occupant[token_node[t]] = kNone;
                    occupant[target] = first_new + t;
                    token_node[t] = target;
                    ++moved;
                }
                if (stats) {
                    ++stats->iterations;
                    stats->displacements += moved;
                }
                // Stop when nothing moves or the displacement count stops decreasing.
                if (moved == 0 || moved >= previous) break;
                previous = moved;
            }
        }
        // Fix the tokens: neighbours are the nearest tokens around (§5.3: "the average of
        // the distances to its neighbors"), radius their mean distance.
        for (uint32_t t = 0; t < token_node.size(); ++t) {
            point_leaf.push_back(p[token_node[t]].leaf);
        }
        for (uint32_t t = 0; t < token_node.size(); ++t) {
            tokens_around(p, base, occupant, token_node[t], reach, &visited, &mark, ++stamp,
                          &found);
            std::vector<uint32_t> neighbours;
            double sum = 0;
            for (const auto& [d, other] : found) {
                if (neighbours.size() == 4) break;  // enough for Alg. 6.4, and 2 bytes each
                neighbours.push_back(other);
                sum += d;
            }
            const double r = neighbours.empty() ? repulsion : sum / double(neighbours.size());
            point_neighbours.push_back(std::move(neighbours));
            point_radius.push_back(r);
        }
        level_end.push_back(uint32_t(point_leaf.size()));
    }

    // Radius per level (§5.3): levels are 4-5x apart in size, so a level's points get radii
    // spread between its own spacing and the coarser level's: ordered level by level, inside
    // a level by their neighbours' mean distance (the locally sparser first), and the point
    // of rank i gets sqrt(area / (i + 1)), the spacing of an even i + 1 point prefix
    // (region = r^2, runtime/stipple_size.h). Without this, tone would step with the levels.
    std::vector<uint32_t> order(point_leaf.size());
    std::iota(order.begin(), order.end(), 0u);
    uint32_t begin = 0;
    for (uint32_t end : level_end) {
        std::stable_sort(order.begin() + begin, order.begin() + end,
                         [&](uint32_t a, uint32_t b) { return point_radius[a] > point_radius[b]; });
        begin = end;
    }
    std::vector<uint32_t> rank(order.size());
    for (uint32_t i = 0; i < order.size(); ++i) {
        rank[order[i]] = i;
        point_radius[order[i]] = std::sqrt(area / double(i + 1));
    }
    *out = PointHierarchy();
    out->neighbour_offsets.push_back(0);
    for (uint32_t id : order) {
        const SurfacePoint& s = base[point_leaf[id]].centre;
        out->host_triangle.push_back(s.host);
        out->bary_u.push_back(float(s.u));
        out->bary_v.push_back(float(s.v));
        out->radius.push_back(float(point_radius[id]));
        for (uint32_t n : point_neighbours[id]) out->neighbours.push_back(rank[n]);
        out->neighbour_offsets.push_back(uint32_t(out->neighbours.size()));
    }
}

}  // namespace stipple::bake
