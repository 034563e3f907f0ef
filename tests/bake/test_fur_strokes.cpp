// Fur (bake/fur.h) and explicit strokes from JSON (bake/stroke_json.h): hairs rooted on the
// hierarchy's first points, in the runtime's own tangent frame (runtime/stroke_anchor.h) so
// bake and runtime agree on the rest pose to the bit; JSON strokes parsed, resolved and
// refused with one-line errors naming the stroke and the field.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "bake/asset_writer.h"
#include "bake/fur.h"
#include "bake/point_hierarchy.h"
#include "bake/scene_import.h"
#include "bake/scene_orientation.h"
#include "bake/stroke_json.h"
#include "bake/vertex_normals.h"
#include "runtime/asset.h"
#include "runtime/asset_limits.h"
#include "runtime/point_placement.h"
#include "runtime/stroke_anchor.h"
#include "tests/common/bake_fixtures.h"

namespace {

using namespace stipple;

const stipple::test::Torus& torus() {
    return stipple::test::prepared_torus(400);
}

SurfaceFrame runtime_frame(const Asset& a, uint32_t triangle, float u, float v) {
    auto at = [&](const float* data, int corner) {
        const size_t i = a.mesh.indices[size_t(triangle) * 3 + size_t(corner)];
        return glm::vec3(data[i * 3], data[i * 3 + 1], data[i * 3 + 2]);
    };
    return surface_frame(at(a.mesh.positions, 0), at(a.mesh.positions, 1), at(a.mesh.positions, 2),
                         at(a.mesh.normals, 0), at(a.mesh.normals, 1), at(a.mesh.normals, 2), u, v);
}

SurfaceFrame bake_frame(const bake::RawScene& s, uint32_t triangle, float u, float v) {
    auto at = [&](const std::vector<float>& data, int corner) {
        const size_t i = s.indices[size_t(triangle) * 3 + size_t(corner)];
        return glm::vec3(data[i * 3], data[i * 3 + 1], data[i * 3 + 2]);
    };
    return surface_frame(at(s.positions, 0), at(s.positions, 1), at(s.positions, 2),
                         at(s.normals, 0), at(s.normals, 1), at(s.normals, 2), u, v);
}

glm::vec3 point_position(const format::StrokePointRecord& p) {
    return glm::vec3(p.position[0], p.position[1], p.position[2]);
}

TEST(FurStrokes, RootsSitOnTheirHierarchyPointsInTheRuntimeFrame) {
    const stipple::test::Torus& t = torus();
    bake::FurConfig config;
    config.count = 250;
    bake::BakedStrokes fur;
    ASSERT_TRUE(bake::bake_fur(t.scene, t.points, config, &fur).ok());
    ASSERT_EQ(fur.strokes.size(), 250u);
    EXPECT_EQ(fur.points.size(), 250u * bake::kFurControlPoints);
    const std::vector<uint8_t> bytes = bake::encode_asset(t.scene, t.points, fur);
    Asset a;
    const Status st = load_asset_memory(bytes.data(), bytes.size(), &a);
    ASSERT_TRUE(st.ok()) << st.message;
    ASSERT_EQ(a.strokes.stroke_count, 250u);
    const PointsView& p = a.points;
    std::vector<float> pos(size_t(p.point_count) * 3), nrm(pos.size());
    place_points(p, a.mesh.indices, a.mesh.positions, a.mesh.normals, pos.data(), nrm.data());
    const float radius = bake::default_fur_length(t.scene) / 25.0f;
    for (uint32_t i = 0; i < a.strokes.stroke_count; ++i) {
        const format::StrokeRecord& s = a.strokes.strokes[i];
        ASSERT_EQ(s.root_point, i);  // ascending: the hierarchy's coarse-to-fine prefix
        EXPECT_EQ(s.anchor, format::kAnchorSurface);
        EXPECT_EQ(s.host, p.host_triangle[i]);
        EXPECT_EQ(s.bary_u, p.bary_u[i]);  // the decoded barycentrics, to the bit
        EXPECT_EQ(s.bary_v, p.bary_v[i]);
        const SurfaceFrame rt = runtime_frame(a, s.host, s.bary_u, s.bary_v);
        const SurfaceFrame bk = bake_frame(t.scene, s.host, s.bary_u, s.bary_v);
        EXPECT_EQ(rt.origin, bk.origin);  // the MESH section is the scene's floats
        EXPECT_EQ(rt.x, bk.x);
        EXPECT_EQ(rt.z, bk.z);
        // The frame's origin is the stipple point the runtime places.
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(rt.origin[k], pos[size_t(i) * 3 + k], 1e-5f);
        // The root control point: just below the surface, on the normal.
        const format::StrokePointRecord& root = a.strokes.points[s.first_point];
        EXPECT_EQ(root.position[0], 0.0f);
        EXPECT_EQ(root.position[1], 0.0f);
        EXPECT_FLOAT_EQ(root.position[2], -0.1f * radius);
        EXPECT_FLOAT_EQ(root.radius, radius);
        const glm::vec3 world = frame_point(rt, glm::vec3(root.position[0], root.position[1], 0));
        EXPECT_EQ(world, rt.origin);
        // Global normal = the surface normal, depth 0 at the root and 1 at the tip.
        EXPECT_EQ(root.global_normal[2], 127);
        EXPECT_EQ(root.global_depth, 0);
        EXPECT_EQ(a.strokes.points[s.first_point + s.point_count - 1].global_depth, 255);
        EXPECT_NEAR(a.strokes.points[s.first_point + s.point_count - 1].radius, 0.2f * radius,
                    1e-6f);
    }
}

TEST(FurStrokes, MoreHairsThanPointsGivesOnePerPoint) {
    const stipple::test::Torus& t = torus();
    bake::FurConfig config;
    config.count = 100000;
    bake::BakedStrokes fur;
    ASSERT_TRUE(bake::bake_fur(t.scene, t.points, config, &fur).ok());
    EXPECT_EQ(fur.strokes.size(), t.points.size());
    for (size_t i = 0; i < fur.strokes.size(); ++i) {
        EXPECT_EQ(fur.strokes[i].root_point, i);
        EXPECT_EQ(fur.strokes[i].first_point, i * bake::kFurControlPoints);
    }
}

TEST(FurStrokes, HairsHangUnderGravityAndStandWithoutAComb) {
    const stipple::test::Torus& t = torus();
    bake::FurConfig config;
    config.count = 400;
    bake::BakedStrokes hang, straight;
    ASSERT_TRUE(bake::bake_fur(t.scene, t.points, config, &hang).ok());
    config.comb[1] = 0.0f;
    ASSERT_TRUE(bake::bake_fur(t.scene, t.points, config, &straight).ok());
    int side = 0, down = 0;
    for (size_t i = 0; i < hang.strokes.size(); ++i) {
        const format::StrokeRecord& s = hang.strokes[i];
        const SurfaceFrame f = bake_frame(t.scene, s.host, s.bary_u, s.bary_v);
        const glm::vec3 root = frame_point(f, point_position(hang.points[s.first_point]));
        const glm::vec3 tip =
            frame_point(f, point_position(hang.points[s.first_point + s.point_count - 1]));
        if (std::fabs(f.z.y) < 0.3f) {
            ++side;
            down += tip.y < root.y - 1e-4f;
        }
        const format::StrokePointRecord& stip = straight.points[s.first_point + s.point_count - 1];
        EXPECT_NEAR(stip.position[0], 0.0f, 1e-6f);  // no comb: straight along the normal
        EXPECT_NEAR(stip.position[1], 0.0f, 1e-6f);
        EXPECT_GT(stip.position[2], 0.0f);
    }
    ASSERT_GT(side, 20);
    EXPECT_EQ(down, side);
}

TEST(FurStrokes, CurlTwistsTheBendAndColoursVaryDeterministically) {
    const stipple::test::Torus& t = torus();
    bake::FurConfig config;
    config.count = 50;
    config.comb[0] = 1.0f;
    bake::BakedStrokes plain, curled, again;
    ASSERT_TRUE(bake::bake_fur(t.scene, t.points, config, &plain).ok());
    config.curl = 40.0f;
    ASSERT_TRUE(bake::bake_fur(t.scene, t.points, config, &curled).ok());
    ASSERT_TRUE(bake::bake_fur(t.scene, t.points, config, &again).ok());
    ASSERT_EQ(curled.points.size(), again.points.size());
    EXPECT_EQ(std::memcmp(curled.points.data(), again.points.data(),
                          curled.points.size() * sizeof(format::StrokePointRecord)),
              0);
    int moved = 0, greys = 0;
    for (size_t i = 0; i < plain.points.size(); ++i) {
        moved += point_position(plain.points[i]) != point_position(curled.points[i]);
        const uint8_t* c = plain.points[i].colour;
        EXPECT_TRUE(c[0] == c[1] && c[1] == c[2]);
        EXPECT_LT(c[0], 100);  // dark grey
        greys += c[0] != plain.points[0].colour[0];
    }
    EXPECT_GT(moved, 0);
    EXPECT_GT(greys, 0);  // per-hair variation
}

TEST(FurStrokes, BadConfigurationsAreRefused) {
    const stipple::test::Torus& t = torus();
    const float nan = std::nanf("");
    struct Case {
        float length, radius, comb_x, curl;
        uint32_t count;
    };
    const Case cases[] = {{-1, 0, 0, 0, 10},       {nan, 0, 0, 0, 10},
                          {1e6f, 0, 0, 0, 10},     {0, -2, 0, 0, 10},
                          {0, INFINITY, 0, 0, 10}, {0, 0, nan, 0, 10},
                          {0, 0, 0, nan, 10},      {0, 0, 0, 0, limits::kMaxStrokes + 1}};
    for (const Case& c : cases) {
        bake::FurConfig config;
        config.length = c.length;
        config.radius = c.radius;
        config.comb[0] = c.comb_x;
        config.curl = c.curl;
        config.count = c.count;
        bake::BakedStrokes fur;
        const bake::BakeError e = bake::bake_fur(t.scene, t.points, config, &fur);
        EXPECT_EQ(e.code, bake::BakeErrorCode::invalid_option) << e.message;
        EXPECT_TRUE(fur.empty());
        EXPECT_EQ(e.message.find('\n'), std::string::npos);
    }
}

}  // namespace
