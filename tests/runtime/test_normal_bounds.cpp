// The normal bounds of a part (runtime/normal_bounds.h) that the level of detail's clusters take
// from their vertex pairs: part_bounds and part_facing bound what they say they bound.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "runtime/normal_bounds.h"
#include "runtime/point_simd.h"

namespace {

struct Part {
    std::vector<float> positions, normals;
    std::vector<float> pairs;        // 8 per vertex (pair_vertices)
    std::vector<uint32_t> vertices;  // the part's list: every vertex, some twice, shuffled
};

// `count` vertices in the unit box around the origin, normals within ~31 degrees of `facing`.
Part make_part(std::mt19937* rng, uint32_t count, const glm::vec3& facing) {
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    Part p;
    for (uint32_t v = 0; v < count; ++v) {
        const glm::vec3 n = facing + 0.3f * glm::vec3(u(*rng), u(*rng), u(*rng));
        p.positions.insert(p.positions.end(), {u(*rng), u(*rng), u(*rng)});
        p.normals.insert(p.normals.end(), {n.x, n.y, n.z});
    }
    p.pairs.resize(size_t(count) * 8);
    std::uniform_int_distribution<uint32_t> pick(0, count - 1);
    for (uint32_t j = 0; j < count + count / 3; ++j)
        p.vertices.push_back(j < count ? j : pick(*rng));
    std::shuffle(p.vertices.begin(), p.vertices.end(), *rng);
    return p;
}

void pair(Part* p) {
    stipple::pair_vertices(uint32_t(p->positions.size() / 3), p->positions.data(),
                           p->normals.data(), p->pairs.data());
}

stipple::SizeParams lights(std::mt19937* rng, int count) {
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    stipple::SizeParams s;
    s.light_count = count;
    for (int l = 0; l < count; ++l)
        s.light_direction[l] = glm::normalize(glm::vec3(u(*rng), u(*rng), u(*rng)) + 0.1f);
    return s;
}

TEST(NormalBounds, BoundsHoldForTheirVertices) {
    std::mt19937 rng(11);
    for (int trial = 0; trial < 20; ++trial) {
        const glm::vec3 facing = trial % 2 ? glm::vec3(0, 0, 1) : glm::vec3(0, 0, -1);
        Part p = make_part(&rng, 40, facing);
        pair(&p);
        const stipple::SizeParams s = lights(&rng, 1 + trial % 4);
        const uint32_t n = uint32_t(p.vertices.size());
        stipple::PartBounds b;
        stipple::part_bounds(p.pairs.data(), p.vertices.data(), n, s, &b);
        EXPECT_TRUE(b.cone);
        for (uint32_t v = 0; v < 40; ++v) {
            const glm::vec3 pos(p.positions[v * 3], p.positions[v * 3 + 1], p.positions[v * 3 + 2]);
            const glm::vec3 normal = glm::normalize(
                glm::vec3(p.normals[v * 3], p.normals[v * 3 + 1], p.normals[v * 3 + 2]));
            EXPECT_TRUE(glm::all(glm::lessThanEqual(b.lo, pos)) &&
                        glm::all(glm::lessThanEqual(pos, b.hi)));
            for (int l = 0; l < s.light_count; ++l)
                EXPECT_LE(b.least[l], glm::dot(normal, s.light_direction[l]) + 1e-6f);
        }
        const stipple::PartFacing f = stipple::part_facing(p.pairs.data(), p.vertices.data(), n, b,
                                                           glm::vec3(0, 0, 20), true);
        EXPECT_EQ(f.away, facing.z < 0) << "trial " << trial;
        EXPECT_LE(f.slope, 1.0f);
        if (f.away) {
            EXPECT_LT(f.slope, 1.0f);  // seen from behind: the cone bounds N.V
        }
    }
}

// A vertex whose normal has no length: no cone, and no light it is sure to get.
TEST(NormalBounds, ANormalWithoutLengthGivesNoCone) {
    std::mt19937 rng(3);
    Part p = make_part(&rng, 12, glm::vec3(0, 1, 0));
    for (int k = 0; k < 3; ++k) p.normals[5 * 3 + k] = 0.0f;
    pair(&p);
    const stipple::SizeParams s = lights(&rng, 2);
    stipple::PartBounds b;
    stipple::part_bounds(p.pairs.data(), p.vertices.data(), uint32_t(p.vertices.size()), s, &b);
    EXPECT_FALSE(b.cone);
    for (int l = 0; l < 2; ++l) EXPECT_LE(b.least[l], 0.0f);
    const stipple::PartFacing f =
        stipple::part_facing(p.pairs.data(), p.vertices.data(), uint32_t(p.vertices.size()), b,
                             glm::vec3(0, 20, 0), true);
    EXPECT_FALSE(f.away);
    EXPECT_EQ(f.slope, 1.0f);
}

}  // namespace
