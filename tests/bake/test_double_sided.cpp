// Double-sided surfaces (issue 7, item 5): the stage that turns normals toward the viewer,
// silhouette rims of open double-sided sheets, and the glTF material import. The frame checks:
// tests/frames/test_double_sided_frames.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "bake/asset_writer.h"
#include "bake/scene_import.h"
#include "runtime/asset.h"
#include "runtime/double_sided.h"
#include "runtime/silhouette.h"
#include "tests/common/bake_result.h"
#include "tests/common/fixtures.h"
#include "tests/common/gltf_writer.h"

namespace {

using namespace stipple;

TEST(DoubleSided, PointFlagsFollowTheirHostTriangles) {
    const uint32_t host[] = {0, 1, 1, 2, 2};
    const uint8_t triangle_double_sided[] = {0, 1, 0};
    uint8_t flags[5];
    EXPECT_EQ(double_sided_point_flags(5, host, triangle_double_sided, flags), 2u);
    const uint8_t want[] = {0, 1, 1, 0, 0};
    for (int i = 0; i < 5; ++i) EXPECT_EQ(flags[i], want[i]) << i;
}

// Structure of arrays as the pipeline holds it: 3 floats per point for positions and
// normals, one flag byte per point.
TEST(DoubleSided, OnlyFlaggedBackFacingNormalsTurnTowardTheEye) {
    const glm::vec3 eye(0, 0, 10);
    const float positions[] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 2, 0, 0, 0, 20};
    float normals[] = {0,    0, -1,     // 0: flagged, faces away -> turned
                       0,    0, -1,     // 1: single-sided, faces away -> kept (not drawn)
                       0,    0, 1,      // 2: flagged, faces the eye -> kept
                       0.6f, 0, -0.8f,  // 3: flagged, oblique, faces away -> turned
                       0,    0, 1};     // 4: flagged, behind the eye: +z faces away -> turned
    const uint8_t flags[] = {1, 0, 1, 1, 1};
    float before[15];
    std::copy(normals, normals + 15, before);
    EXPECT_EQ(face_double_sided_points(5, flags, positions, normals, eye), 3u);
    const float want[] = {0, 0, 1, 0, 0, -1, 0, 0, 1, -0.6f, 0, 0.8f, 0, 0, -1};
    for (int i = 0; i < 15; ++i) EXPECT_FLOAT_EQ(normals[i], want[i]) << i;
    // The slope factor the size stage sees (N.V, §3.1.2) is |N.V| of the original normal.
    for (int i : {0, 3}) {
        const glm::vec3 p(positions[i * 3], positions[i * 3 + 1], positions[i * 3 + 2]);
        const glm::vec3 v = glm::normalize(eye - p);
        const glm::vec3 n(normals[i * 3], normals[i * 3 + 1], normals[i * 3 + 2]);
        const glm::vec3 n0(before[i * 3], before[i * 3 + 1], before[i * 3 + 2]);
        EXPECT_GT(glm::dot(n, v), 0.0f);
        EXPECT_FLOAT_EQ(glm::dot(n, v), std::fabs(glm::dot(n0, v)));
    }
    // Without double-sided triangles the stage is a no-op.
    EXPECT_EQ(face_double_sided_points(5, nullptr, positions, normals, eye), 0u);
    for (int i = 0; i < 15; ++i) EXPECT_FLOAT_EQ(normals[i], want[i]) << i;
}

// A unit quad in z = 0 facing +z, baked with one double-sided and one single-sided triangle.
void quad_scene(bake::RawScene* s, bake::PointHierarchy* p, std::vector<uint8_t> sides) {
    *s = bake::RawScene();
    *p = bake::PointHierarchy();
    s->positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    s->normals = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    s->indices = {0, 1, 2, 0, 2, 3};
    s->double_sided = std::move(sides);
    p->host_triangle = {0, 1};
    p->bary_u = {0.3f, 0.3f};
    p->bary_v = {0.3f, 0.3f};
    p->radius = {0.5f, 0.4f};
    p->neighbour_offsets = {0, 1, 2};
    p->neighbours = {1, 0};
}

// Seen from behind, a single-sided open sheet has no outline (its rim's only face is a back
// face); a double-sided one keeps the rim of its double-sided triangle. Folds of a
// double-sided sheet (front next to back) stay silhouettes as before.
TEST(DoubleSided, RimOfAnOpenDoubleSidedSheetIsDrawnFromBehind) {
    bake::RawScene s;
    bake::PointHierarchy p;
    for (int double_sided = 0; double_sided < 2; ++double_sided) {
        quad_scene(&s, &p, double_sided ? std::vector<uint8_t>{1, 0} : std::vector<uint8_t>{});
        std::vector<uint8_t> bytes = bake::encode_asset(s, p);
        Asset a;
        Status st = load_asset_memory(bytes.data(), bytes.size(), &a);
        ASSERT_TRUE(st.ok()) << st.message;
        ASSERT_EQ(a.edges.edge_count, 5u);  // 4 rim edges (2 per triangle) and the diagonal
        uint8_t front[2];
        float lines[5 * 6];
        triangle_facing(2, a.mesh.indices, a.mesh.positions, glm::vec3(0.5f, 0.5f, -3), front);
        EXPECT_EQ(front[0] + front[1], 0);
        const uint32_t n = silhouette_lines(a.edges, front, a.mesh.positions, lines);
        EXPECT_EQ(n, double_sided ? 2u : 0u);  // triangle 0's two rim edges
        triangle_facing(2, a.mesh.indices, a.mesh.positions, glm::vec3(0.5f, 0.5f, 3), front);
        EXPECT_EQ(silhouette_lines(a.edges, front, a.mesh.positions, lines), 4u);
    }
}

TEST(DoubleSided, GltfMaterialDoubleSidedIsImportedPerTriangle) {
    // Two primitives of one mesh: the first with a doubleSided material, the second with a
    // single-sided one, then a third without material (glTF's default: single-sided).
    test::GltfBin bin;
    bin.put<float>({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0});
    bin.put<uint16_t>({0, 1, 2, 1, 3, 2});
    const std::string path = test::scratch_path("double_sided.gltf");
    test::write_gltf(path, R"({
      "asset": {"version": "2.0"},
      "scene": 0, "scenes": [{"nodes": [0]}],
      "nodes": [{"mesh": 0}],
      "materials": [{"doubleSided": true}, {"doubleSided": false}],
      "meshes": [{"primitives": [
        {"attributes": {"POSITION": 0}, "indices": 1, "material": 0},
        {"attributes": {"POSITION": 0}, "indices": 1, "material": 1},
        {"attributes": {"POSITION": 0}, "indices": 1}]}],
      "buffers": [@BUFFER@],
      "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                      {"buffer": 0, "byteOffset": 48, "byteLength": 12}],
      "accessors": [
        {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
         "min": [0, 0, 0], "max": [1, 1, 0]},
        {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"}]
    })",
                     bin);
    bake::RawScene scene;
    std::string error;
    ASSERT_TRUE(stipple::test::bake_ok(bake::import_scene(path, &scene), &error)) << error;
    ASSERT_EQ(scene.triangle_count(), 6u);
    EXPECT_EQ(scene.double_sided, (std::vector<uint8_t>{1, 1, 0, 0, 0, 0}));
    // Stored as one run: (first triangle 0, 2 triangles).
    bake::PointHierarchy p;
    p.host_triangle = {0, 3};
    p.bary_u = {0.3f, 0.3f};
    p.bary_v = {0.3f, 0.3f};
    p.radius = {0.5f, 0.4f};
    p.neighbour_offsets = {0, 1, 2};
    p.neighbours = {1, 0};
    std::vector<uint8_t> bytes = bake::encode_asset(scene, p);
    Asset a;
    Status st = load_asset_memory(bytes.data(), bytes.size(), &a);
    ASSERT_TRUE(st.ok()) << st.message;
    ASSERT_EQ(a.sides.run_count, 1u);
    EXPECT_EQ(a.sides.runs[0], 0u);
    EXPECT_EQ(a.sides.runs[1], 2u);
    EXPECT_EQ(a.sides.triangle_count, 2u);
    ASSERT_NE(a.sides.triangle_double_sided, nullptr);
    for (uint32_t t = 0; t < 6; ++t) EXPECT_EQ(a.sides.triangle_double_sided[t], t < 2) << t;
}

}  // namespace
