// The particle tree from simplification's own merge record (bake/particle_parents.h,
// docs/particles.md "Parents"): the record mapped through the coarse-to-fine order is a
// forest whose parents precede their children; on simplify bakes a simplified point's record
// parent is the vertex its shortest edge collapsed onto (its nearest relevant neighbour) and a
// subdivision point's is an endpoint of its split edge (it sits at the midpoint of that
// endpoint and another neighbour); the tree fitted to the runtime's levels has every child
// one level below its parent, mostly the record's own parent; the loader accepts it.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <glm/glm.hpp>
#include <vector>

#include "bake/asset_writer.h"
#include "bake/particle_parents.h"
#include "bake/point_hierarchy.h"
#include "bake/scene_import.h"
#include "runtime/asset.h"
#include "runtime/particle_tree.h"
#include "tests/common/bake_result.h"
#include "tests/common/fixtures.h"

namespace {

using namespace stipple;
using namespace stipple::bake;

struct Baked {
    RawScene scene;
    PointHierarchy points;
    HierarchyStats stats;
    std::vector<float> xyz;  // bind-pose positions, 3 per point
    glm::vec3 at(uint32_t i) const { return glm::vec3(xyz[i * 3], xyz[i * 3 + 1], xyz[i * 3 + 2]); }
};

Baked simplify_bake(const char* asset, uint32_t count, float jitter) {
    Baked b;
    std::string error;
    EXPECT_TRUE(test::bake_ok(import_scene(test::source(asset), &b.scene), &error)) << error;
    HierarchyConfig c;
    c.method = HierarchyMethod::simplify;
    c.point_count = count;
    c.jitter = jitter;
    EXPECT_TRUE(test::bake_ok(build_point_hierarchy(b.scene, c, &b.points, &b.stats), &error))
        << error;
    const PointHierarchy& p = b.points;
    for (size_t i = 0; i < p.size(); ++i) {
        const uint32_t* t = &b.scene.indices[size_t(p.host_triangle[i]) * 3];
        const float w[3] = {p.bary_u[i], p.bary_v[i], 1.0f - p.bary_u[i] - p.bary_v[i]};
        for (int k = 0; k < 3; ++k) {
            float x = 0.0f;
            for (int c3 = 0; c3 < 3; ++c3) x += w[c3] * b.scene.positions[size_t(t[c3]) * 3 + k];
            b.xyz.push_back(x);
        }
    }
    return b;
}

std::vector<uint32_t> neighbours_of(const PointHierarchy& p, uint32_t i) {
    return std::vector<uint32_t>(p.neighbours.begin() + p.neighbour_offsets[i],
                                 p.neighbours.begin() + p.neighbour_offsets[i + 1]);
}

uint32_t level_of(uint32_t i) {
    uint32_t level = 0;
    for (uint64_t end = 1; end <= i; end *= 4) ++level;
    return level;
}

TEST(ParticleParents, TheRecordFollowsTheFinalOrder) {
    // Ids 0..6. 6 split from 1; 1 merged into 4, 4 into 2, 5 into 3, 3 into 2; 2 and 0 are the
    // base mesh. Placed (coarse to fine): 2, 0, 3, 6, 1, 5; 4 is dropped.
    const std::vector<uint32_t> merged = {kNoMerge, 4, kNoMerge, 2, 2, 3, 1};
    const std::vector<uint32_t> order = {2, 0, 3, 6, 1, 5};
    std::vector<uint32_t> rank(7, UINT32_MAX);
    for (uint32_t i = 0; i < order.size(); ++i) rank[order[i]] = i;
    const std::vector<uint32_t> got = record_parents(merged, order, rank);
    // 2, 0: roots. 3 -> 2 (place 0). 6 -> 1 is placed after it: 1's chain skips the dropped 4
    // to 2 (place 0). 1 -> 4 (dropped) -> 2. 5 -> 3 (place 2).
    const std::vector<uint32_t> expected = {kNoMerge, kNoMerge, 0, 0, 0, 2};
    EXPECT_EQ(got, expected);
}

TEST(ParticleParents, TheTreeKeepsEveryChildOneLevelBelowItsParent) {
    // 21 points on a line; the record sends every point to point 0 (the base mesh's one
    // vertex), except 5 -> 1 (one level up) and 17 -> 6 (one level up).
    const uint32_t n = 21;
    std::vector<uint32_t> record(n, 0);
    record[0] = kNoMerge;
    record[5] = 1;
    record[17] = 6;
    std::vector<float> xyz;
    for (uint32_t i = 0; i < n; ++i) xyz.insert(xyz.end(), {float(i), 0.0f, 0.0f});
    MergeTreeStats st;
    const std::vector<uint32_t> parent = merge_tree_parents(record, xyz, &st);
    ASSERT_EQ(parent.size(), n);
    EXPECT_EQ(parent[0], kNoMerge);
    for (uint32_t i = 1; i < n; ++i) EXPECT_EQ(level_of(parent[i]) + 1, level_of(i)) << i;
    EXPECT_EQ(parent[5], 1u);
    EXPECT_EQ(parent[17], 6u);
    // 16 -> 0 skips level 2: the nearest of level 2 (points 4..15) under 0 within twice 16's
    // distance to 0: 15.
    EXPECT_EQ(parent[16], 15u);
    EXPECT_EQ(st.record, 3u + 2u);  // 1, 2, 3 -> 0; 5 -> 1; 17 -> 6
    EXPECT_EQ(st.record + st.subtree + st.nearest, n - 1);
    EXPECT_TRUE(particle_parents_valid(n, parent.data()));
}

// Particles shown when every node above level k is unfolded and every node of level k and
// below folded (the cut a uniform density target makes, GI'01 §2 stage 1): the roots and
// every point whose parent lies above level k, per point of levels 0..k (4^k). 1 when every
// child is one level below its parent.
double shown_per_level_point(const std::vector<uint32_t>& parent, uint32_t k) {
    uint64_t shown = 0;
    for (uint32_t i = 0; i < parent.size(); ++i)
        shown += parent[i] == kNoMerge || level_of(parent[i]) < k;
    return double(shown) / double(uint64_t(1) << (2 * k));
}

// Prints shown_per_level_point for the record forest and the tree at every full level;
// returns the record forest's largest.
double report_cuts(const Baked& b, const std::vector<uint32_t>& tree, const char* what) {
    double worst = 0;
    for (uint32_t k = 2; (uint64_t(1) << (2 * k)) <= b.points.size(); ++k) {
        const double record = shown_per_level_point(b.points.record_parent, k);
        worst = std::max(worst, record);
        std::printf(
            "%s: cut above level %u: %.2f shown per point of the levels with the record "
            "forest, %.2f with the tree\n",
            what, k, record, shown_per_level_point(tree, k));
        EXPECT_EQ(shown_per_level_point(tree, k), 1.0) << what << " level " << k;
    }
    return worst;
}

// The tree's parents by kind, and how far each child lies from its parent against the
// nearest point of the level above.
void report_tree(const Baked& b, const char* what, MergeTreeStats* st, double* far_fraction) {
    const auto t0 = std::chrono::steady_clock::now();
    const std::vector<uint32_t> parent = merge_tree_parents(b.points.record_parent, b.xyz, st);
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    const uint32_t n = uint32_t(b.points.size());
    ASSERT_EQ(parent.size(), n);
    EXPECT_TRUE(particle_parents_valid(n, parent.data())) << what;
    EXPECT_EQ(parent[0], kNoParent);
    uint32_t far = 0;
    for (uint32_t i = 1; i < n; ++i) {
        ASSERT_LT(parent[i], i) << what;
        EXPECT_EQ(level_of(parent[i]) + 1, level_of(i)) << what << " point " << i;
        float nearest = INFINITY;  // of the level above: [4^(L-2), 4^(L-1)) for level L
        const uint32_t level = level_of(i);
        const uint32_t lo = level <= 1 ? 0 : 1u << (2 * (level - 2)), hi = 1u << (2 * (level - 1));
        for (uint32_t j = lo; j < hi; ++j)
            nearest = std::min(nearest, glm::length(b.at(j) - b.at(i)));
        far += glm::length(b.at(parent[i]) - b.at(i)) > 2.0f * nearest;
    }
    *far_fraction = double(far) / double(n - 1);
    // Used as it stands, the record would unfold several levels' worth of particles at once
    // where the density target asks for one (a base-mesh vertex gathers merges of every scale).
    EXPECT_GT(report_cuts(b, parent, what), 1.5) << what;
    std::printf(
        "%s: %u points, record %u, subtree %u, nearest %u; %.1f%% farther than twice "
        "the nearest of the level above; %.1f ms\n",
        what, n, st->record, st->subtree, st->nearest, 100.0 * *far_fraction, ms);
}

// Bunny: 35,947 input vertices, 20,000 points: every point is a simplified vertex.
TEST(ParticleParents, SimplifiedPointsMergedIntoTheirNearestNeighbour) {
    const Baked b = simplify_bake("assets/StanfordBunny/stanford-bunny.obj", 20000, 0.35f);
    const PointHierarchy& p = b.points;
    ASSERT_EQ(p.record_parent.size(), p.size());
    ASSERT_EQ(b.stats.subdivided_points, 0u);
    uint32_t roots = 0, nearest_neighbour = 0, checked = 0;
    for (uint32_t i = 0; i < p.size(); ++i) {
        const uint32_t r = p.record_parent[i];
        if (r == kNoMerge) {
            ++roots;
            continue;
        }
        ASSERT_LT(r, i);
        // The shortest edge collapses first (thesis §4.5), so the survivor is no farther than
        // any of the removed vertex's one-ring, its relevant neighbours.
        const std::vector<uint32_t> ring = neighbours_of(p, i);
        if (std::find(ring.begin(), ring.end(), r) == ring.end()) continue;
        ++checked;
        const float d = glm::length(b.at(r) - b.at(i));
        bool nearest = true;
        for (uint32_t q : ring) nearest = nearest && d <= glm::length(b.at(q) - b.at(i)) * 1.0001f;
        nearest_neighbour += nearest;
    }
    std::printf(
        "bunny: %u roots, %u of %zu record parents in the one-ring, %u of them the "
        "nearest\n",
        roots, checked, p.size(), nearest_neighbour);
    EXPECT_LT(roots, p.size() / 100);  // the base mesh's vertices
    EXPECT_GT(checked, uint32_t(0.9 * double(p.size())));
    EXPECT_GT(nearest_neighbour, uint32_t(0.97 * double(checked)));
    MergeTreeStats st;
    double far = 0;
    report_tree(b, "bunny", &st, &far);
    EXPECT_GT(st.record, p.size() / 2);
}

// Torus (2,304 vertices) at 10,000 points without randomization: most points are
// subdivision points, at the (projected) midpoint of their split edge.
TEST(ParticleParents, SubdivisionPointsParentToAnEndpointOfTheirEdge) {
    const Baked b = simplify_bake("assets/torus.obj", 10000, 0.0f);
    const PointHierarchy& p = b.points;
    ASSERT_EQ(p.record_parent.size(), p.size());
    ASSERT_GT(b.stats.subdivided_points, 5000u);
    uint32_t split = 0, endpoint = 0;
    for (uint32_t i = 0; i < p.size(); ++i) {
        const float u = p.bary_u[i], v = p.bary_v[i];
        const bool corner = (u == 1 && v == 0) || (u == 0 && v == 1) || (u == 0 && v == 0);
        if (corner) continue;  // an input vertex (not moved: no randomization)
        ++split;
        const uint32_t r = p.record_parent[i];
        if (r == kNoMerge) continue;
        ASSERT_LT(r, i);
        // The other endpoint is a relevant neighbour too, and i lies at their midpoint.
        const float to_r = glm::length(b.at(r) - b.at(i));
        bool found = false;
        for (uint32_t q : neighbours_of(p, i)) {
            const float edge = glm::length(b.at(q) - b.at(r));
            found = found ||
                    (q != r && glm::length(0.5f * (b.at(q) + b.at(r)) - b.at(i)) < 0.05f * edge &&
                     to_r <= glm::length(b.at(q) - b.at(i)) * 1.0001f);
        }
        endpoint += found;
    }
    std::printf(
        "torus: %u subdivision points, %u parented to the nearer endpoint of their "
        "split edge\n",
        split, endpoint);
    EXPECT_GT(split, 5000u);
    EXPECT_GT(endpoint, uint32_t(0.9 * double(split)));
    MergeTreeStats st;
    double far = 0;
    report_tree(b, "torus", &st, &far);
    EXPECT_GT(st.record, p.size() / 2);
}

TEST(ParticleParents, TheLoaderAcceptsTheMergeTree) {
    const Baked b = simplify_bake("assets/torus.obj", 4000, 0.35f);
    const std::vector<uint32_t> parent = merge_tree_parents(b.points.record_parent, b.xyz);
    const std::vector<uint8_t> bytes =
        encode_asset(b.scene, b.points, BakedStrokes(), BakedLooks(), parent);
    Asset a;
    const Status st = load_asset_memory(bytes.data(), bytes.size(), &a);
    ASSERT_TRUE(st.ok()) << st.message;
    ASSERT_NE(a.particle_parent, nullptr);
    EXPECT_TRUE(std::equal(parent.begin(), parent.end(), a.particle_parent));
    ParticleTree t;
    EXPECT_TRUE(particle_tree_build(&t, uint32_t(parent.size()), a.particle_parent).ok());
    EXPECT_EQ(t.root_count, 1u);
}

// Other methods keep no record: their tree is the runtime's rule (runtime/particle_tree.h).
TEST(ParticleParents, OnlySimplifyKeepsARecord) {
    RawScene s;
    std::string error;
    ASSERT_TRUE(test::bake_ok(import_scene(test::source("assets/torus.obj"), &s), &error));
    for (HierarchyMethod m :
         {HierarchyMethod::eliminate, HierarchyMethod::relax, HierarchyMethod::random}) {
        HierarchyConfig c;
        c.method = m;
        c.point_count = 2000;
        PointHierarchy p;
        ASSERT_TRUE(test::bake_ok(build_point_hierarchy(s, c, &p, nullptr), &error)) << error;
        EXPECT_TRUE(p.record_parent.empty());
    }
}

}  // namespace
