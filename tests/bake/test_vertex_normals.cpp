// Shading styles of thesis §7.1: flat, smooth and auto (split at sharp edges).
#include <gtest/gtest.h>

#include <cmath>

#include "bake/vertex_normals.h"

namespace {

using namespace stipple::bake;

// Unit cube, 8 shared vertices, 12 outward triangles.
RawScene cube() {
    RawScene s;
    for (int i = 0; i < 8; ++i) {
        s.positions.insert(s.positions.end(), {float(i & 1), float((i >> 1) & 1), float(i >> 2)});
        s.normals.insert(s.normals.end(), {0, 0, 1});
    }
    s.indices = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
                 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
    return s;
}

// A shallow "roof": two triangles folded by 10 degrees along the x axis.
RawScene roof(float degrees) {
    float a = degrees * float(M_PI) / 180.0f;
    RawScene s;
    s.positions = {0,
                   0,
                   0,
                   1,
                   0,
                   0,
                   0,
                   std::cos(a),
                   std::sin(a),
                   1,
                   std::cos(a),
                   std::sin(a),
                   0,
                   -std::cos(a),
                   std::sin(a),
                   1,
                   -std::cos(a),
                   std::sin(a)};
    s.normals.assign(18, 0.0f);
    s.indices = {0, 1, 2, 1, 3, 2, 0, 4, 1, 1, 4, 5};
    return s;
}

TEST(VertexNormals, FlatGivesEveryCornerItsFaceNormal) {
    RawScene s = cube();
    assign_normals({NormalMode::flat, 40}, &s);
    EXPECT_EQ(s.vertex_count(), 36u);  // every triangle corner its own vertex
    EXPECT_EQ(s.triangle_count(), 12u);
    for (size_t c = 0; c < s.indices.size(); ++c) {
        const float* n = &s.normals[size_t(s.indices[c]) * 3];
        EXPECT_FLOAT_EQ(std::fabs(n[0]) + std::fabs(n[1]) + std::fabs(n[2]), 1.0f);
    }
}

TEST(VertexNormals, SmoothSharesOneNormalPerPosition) {
    RawScene s = cube();
    assign_normals({NormalMode::smooth, 40}, &s);
    EXPECT_EQ(s.vertex_count(), 8u);
    // Corner (1,1,1) points along the diagonal.
    for (size_t v = 0; v < 8; ++v) {
        if (s.positions[v * 3] == 1 && s.positions[v * 3 + 1] == 1 && s.positions[v * 3 + 2] == 1) {
            EXPECT_NEAR(s.normals[v * 3], 1.0 / std::sqrt(3.0), 1e-6);
        }
    }
}

TEST(VertexNormals, AutoSplitsSharpEdgesOnlyAndKeepsSkinData) {
    RawScene s = cube();
    s.joints.assign(32, 0);
    s.weights.assign(32, 0.25f);
    EXPECT_EQ(assign_normals({NormalMode::automatic, 40}, &s), 16u);  // 90 degree edges split
    EXPECT_EQ(s.weights.size(), s.vertex_count() * 4);

    RawScene r = roof(10);  // 20 degree dihedral: below the crease angle, stays smooth
    assign_normals({NormalMode::automatic, 40}, &r);
    EXPECT_EQ(r.vertex_count(), 6u);
    RawScene sharp = roof(35);  // 70 degrees: split along the ridge
    assign_normals({NormalMode::automatic, 40}, &sharp);
    EXPECT_EQ(sharp.vertex_count(), 8u);
}

TEST(VertexNormals, ParsesModes) {
    NormalMode m;
    EXPECT_TRUE(parse_normal_mode("auto", &m));
    EXPECT_EQ(m, NormalMode::automatic);
    EXPECT_TRUE(parse_normal_mode("flat", &m));
    EXPECT_FALSE(parse_normal_mode("phong", &m));
}

}  // namespace

namespace {

TEST(VertexNormals, InsideOutClosedMeshesAreFlippedOpenOnesLeftAlone) {
    stipple::bake::RawScene s = cube();
    for (size_t t = 0; t < s.triangle_count(); ++t)
        std::swap(s.indices[t * 3 + 1], s.indices[t * 3 + 2]);
    const std::vector<uint32_t> inside_out = s.indices;
    EXPECT_TRUE(stipple::bake::orient_outward(&s));
    EXPECT_NE(s.indices, inside_out);
    EXPECT_EQ(s.indices, cube().indices);             // back to the outward winding
    EXPECT_FALSE(stipple::bake::orient_outward(&s));  // already outward
    stipple::bake::RawScene r = roof(20);             // open surface: no volume to judge by
    const std::vector<uint32_t> before = r.indices;
    EXPECT_FALSE(stipple::bake::orient_outward(&r));
    EXPECT_EQ(r.indices, before);
}

}  // namespace
