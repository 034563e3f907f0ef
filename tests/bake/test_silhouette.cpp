// Silhouette edges: adjacency from the bake (welded across seams) and the per-frame test
// front-facing vs back-facing (thesis §3.2).
#include <gtest/gtest.h>

#include "bake/silhouette_edges.h"
#include "runtime/silhouette.h"

namespace {

// A tetrahedron whose vertex 0 is duplicated (a UV seam): welding must still find 6 edges.
stipple::bake::RawScene tetrahedron() {
    stipple::bake::RawScene s;
    s.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
    s.normals.assign(15, 0.0f);
    // Outward (counter-clockwise seen from outside) faces; face 3 uses the seam copy (4).
    s.indices = {0, 2, 1, 0, 1, 3, 4, 3, 2, 1, 2, 3};
    return s;
}

TEST(Silhouette, BakeWeldsSeamsAndPairsEveryEdge) {
    std::vector<uint32_t> edges = stipple::bake::silhouette_edges(tetrahedron());
    ASSERT_EQ(edges.size(), 6u * 4u);
    for (size_t i = 0; i < edges.size(); i += 4) {
        EXPECT_NE(edges[i + 2], edges[i + 3]);
        EXPECT_NE(edges[i + 3], stipple::format::kNoFace);  // closed: no boundary
    }
}

TEST(Silhouette, LinesSeparateFrontFromBackFaces) {
    stipple::bake::RawScene s = tetrahedron();
    std::vector<uint32_t> e = stipple::bake::silhouette_edges(s);
    stipple::EdgesView view;
    view.edge_count = uint32_t(e.size() / 4);
    view.edges = e.data();
    // Seen from high on +z the bottom face (z = 0) faces away and the slanted face faces
    // the eye; the lines must be exactly the edges between faces of different facing.
    uint8_t front[4];
    const glm::vec3 eye(0.2f, 0.2f, 10.0f);
    stipple::triangle_facing(4, s.indices.data(), s.positions.data(), eye, front);
    EXPECT_EQ(front[0], 0);  // z = 0 face, normal -z
    EXPECT_EQ(front[3], 1);  // slanted face, normal (1,1,1)
    float lines[6 * 6];
    uint32_t n = stipple::silhouette_lines(view, front, s.positions.data(), lines);
    uint32_t expected = 0;
    for (uint32_t i = 0; i < view.edge_count; ++i)
        expected += front[e[i * 4 + 2]] != front[e[i * 4 + 3]];
    EXPECT_EQ(n, expected);
    EXPECT_GE(n, 3u);  // a closed convex object always shows a closed outline
    // Every endpoint is a tetrahedron vertex (coordinates sum to 0 or 1).
    for (uint32_t i = 0; i < n * 2; ++i) {
        float sum = lines[i * 3] + lines[i * 3 + 1] + lines[i * 3 + 2];
        EXPECT_TRUE(sum == 0.0f || sum == 1.0f);
    }
}

TEST(Silhouette, OpenBoundaryOfAFrontFaceIsDrawn) {
    stipple::bake::RawScene s;
    s.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    s.normals.assign(9, 0.0f);
    s.indices = {0, 1, 2};
    std::vector<uint32_t> e = stipple::bake::silhouette_edges(s);
    ASSERT_EQ(e.size(), 12u);
    stipple::EdgesView view{3, e.data()};
    uint8_t front[1];
    float lines[18];
    stipple::triangle_facing(1, s.indices.data(), s.positions.data(), glm::vec3(0, 0, 5), front);
    EXPECT_EQ(stipple::silhouette_lines(view, front, s.positions.data(), lines), 3u);
    stipple::triangle_facing(1, s.indices.data(), s.positions.data(), glm::vec3(0, 0, -5), front);
    EXPECT_EQ(stipple::silhouette_lines(view, front, s.positions.data(), lines), 0u);
}

}  // namespace
