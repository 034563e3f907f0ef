// Explicit paintstrokes from JSON (bake/stroke_json.h, docs/strokes.md): the shipped water
// example parses and bakes into an asset the runtime loads; joint names resolve against the
// skin; every bad input is one malformed_input line naming the stroke and the field.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "bake/asset_writer.h"
#include "bake/stroke_json.h"
#include "runtime/asset.h"

namespace {

using namespace stipple;

// A quad (2 triangles) and a three-point hierarchy; skinned with joints "root" and "arm".
void make_scene(bake::RawScene* s, bake::PointHierarchy* p, bool skinned) {
    *s = bake::RawScene();
    *p = bake::PointHierarchy();
    s->positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    s->normals = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    s->indices = {0, 1, 2, 0, 2, 3};
    if (skinned) {
        s->joints = {0, 0, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0};
        s->weights = {1, 0, 0, 0, 0.5f, 0.5f, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
        s->nodes.resize(3);
        s->nodes[0].name = "scene";
        s->nodes[1].parent = 0;
        s->nodes[1].name = "root";
        s->nodes[2].parent = 1;
        s->nodes[2].name = "arm";
        s->joint_nodes = {1, 2};
        s->inverse_bind.assign(32, 0.0f);
        for (int j = 0; j < 2; ++j)
            for (int k = 0; k < 4; ++k) s->inverse_bind[size_t(j) * 16 + size_t(k) * 5] = 1.0f;
    }
    p->host_triangle = {0, 1, 1};
    p->bary_u = {0.25f, 0.5f, 0.0f};
    p->bary_v = {0.25f, 0.5f, 1.0f};
    p->radius = {0.8f, 0.5f, 0.3f};
    p->neighbour_offsets = {0, 2, 3, 5};
    p->neighbours = {1, 2, 0, 0, 1};
}

bake::BakeError parse(const std::string& text, bake::BakedStrokes* out, bool skinned = true) {
    bake::RawScene s;
    bake::PointHierarchy p;
    make_scene(&s, &p, skinned);
    return bake::parse_strokes_json(text, s, out);
}

TEST(StrokeJson, WaterExampleParsesAndLoads) {
    bake::RawScene s;
    bake::PointHierarchy p;
    make_scene(&s, &p, false);
    bake::BakedStrokes water;
    const bake::BakeError e = bake::load_strokes_json(
        std::string(STIPPLE_SOURCE_DIR) + "/assets/strokes/water.json", s, &water);
    ASSERT_TRUE(e.ok()) << e.message;
    ASSERT_EQ(water.strokes.size(), 4u);  // three for the tap, one for the stream
    const format::StrokeRecord& stream = water.strokes[3];
    EXPECT_LT(stream.op_centre, stream.op_edge);  // Fresnel: clear centre, opaque edges
    for (const format::StrokeRecord& r : water.strokes) {
        EXPECT_EQ(r.anchor, format::kAnchorObject);
        EXPECT_EQ(r.root_point, format::kNoRootPoint);
    }
    const std::vector<uint8_t> bytes = bake::encode_asset(s, p, water);
    Asset a;
    const Status st = load_asset_memory(bytes.data(), bytes.size(), &a);
    ASSERT_TRUE(st.ok()) << st.message;
    EXPECT_EQ(a.strokes.stroke_count, 4u);
    EXPECT_EQ(a.strokes.point_count, uint32_t(water.points.size()));
}

TEST(StrokeJson, FieldsAreQuantizedAsDocumented) {
    bake::BakedStrokes b;
    const bake::BakeError e = parse(R"({"strokes": [
        {"anchor": "joint", "joint": "arm", "points": [[0, 0, 0, 0.1], [0, 1, 0, 0.2]],
         "colour": [[1, 0, 0], [0, 0.5, 1]], "reflectance": [0, 1],
         "opacity": {"min": 0.5, "max": 1, "centre": 0.2, "edge": 0.8},
         "global_normal": [0, 2, 0], "global_depth": [0, 1]},
        {"anchor": "surface", "triangle": 1, "barycentric": [0.25, 0.5],
         "points": [[0, 0, 0, 0.01], [0, 0, 0.1, 0.01]]},
        {"points": [[0, 0, 0, 1], [1, 1, 1, 1]]}]})",
                                    &b);
    ASSERT_TRUE(e.ok()) << e.message;
    ASSERT_EQ(b.strokes.size(), 3u);
    EXPECT_EQ(b.strokes[0].anchor, format::kAnchorJoint);
    EXPECT_EQ(b.strokes[0].host, 1u);  // "arm" is joint 1
    EXPECT_EQ(b.strokes[0].op_centre, 51);
    EXPECT_EQ(b.strokes[0].op_edge, 204);
    EXPECT_EQ(b.points[1].colour[1], 128);
    EXPECT_EQ(b.points[1].colour[2], 255);
    EXPECT_EQ(b.points[0].reflectance, 0);
    EXPECT_EQ(b.points[1].reflectance, 255);
    EXPECT_EQ(b.points[0].op_min, 128);
    EXPECT_EQ(b.points[0].global_normal[1], 127);  // normalised, then snorm8
    EXPECT_EQ(b.points[1].global_depth, 255);
    EXPECT_FLOAT_EQ(b.points[1].radius, 0.2f);
    EXPECT_EQ(b.strokes[1].anchor, format::kAnchorSurface);
    EXPECT_EQ(b.strokes[1].host, 1u);
    EXPECT_FLOAT_EQ(b.strokes[1].bary_v, 0.5f);
    EXPECT_EQ(b.strokes[2].anchor, format::kAnchorObject);  // the default
    EXPECT_EQ(b.strokes[2].first_point, 4u);
    EXPECT_EQ(b.points[4].global_normal[0], 0);  // no global shading by default
}

TEST(StrokeJson, BadInputIsOneLineNamingTheField) {
    struct Case {
        const char* json;
        const char* words;
    };
    const Case cases[] = {
        {"not json", "not valid JSON"},
        {"[]", "top level: must be an object"},
        {R"({"strokes": 3})", "strokes: must be an array"},
        {R"({"strokez": []})", "unknown key 'strokez'"},
        {R"({"strokes": [{"points": [[0,0,0,1]]}]})", "strokes[0].points: has 1 points"},
        {R"({"strokes": [{}]})", "strokes[0].points: missing"},
        {R"({"strokes": [{"points": [[0,0,0,1],[0,0,0,0]]}]})", "strokes[0].points[1]: radius"},
        {R"({"strokes": [{"points": [[0,0,0,1],[0,0,"x",1]]}]})",
         "strokes[0].points[1][2]: must be a number"},
        {R"({"strokes": [{"points": [[0,0,0,1],[0,0,1]]}]})",
         "strokes[0].points[1]: must be an array of 4"},
        {R"({"strokes": [{"points": [[0,0,0,1],[0,0,1e9,1]]}]})", "strokes[0].points[1][2]: value"},
        {R"({"strokes": [{"points": [[0,0,0,1],[0,0,1,1]], "colr": [1,1,1]}]})",
         "strokes[0]: unknown key 'colr'"},
        {R"({"strokes": [{"points": [[0,0,0,1],[0,0,1,1]], "colour": [1,1]}]})",
         "strokes[0].colour: must be an array of 3"},
        {R"({"strokes": [{"points": [[0,0,0,1],[0,0,1,1]], "colour": [[1,1,1]]}]})",
         "strokes[0].colour: has 1 entries for 2 points"},
        {R"({"strokes": [{"points": [[0,0,0,1],[0,0,1,1]], "colour": [2,0,0]}]})",
         "strokes[0].colour[0]: value 2 not in [0, 1]"},
        {R"({"strokes": [{"points": [[0,0,0,1],[0,0,1,1]], "reflectance": "shiny"}]})",
         "strokes[0].reflectance: must be a number"},
        {R"({"strokes": [{"points": [[0,0,0,1],[0,0,1,1]], "opacity": {"middle": 1}}]})",
         "strokes[0].opacity: unknown key 'middle'"},
        {R"({"strokes": [{"points": [[0,0,0,1],[0,0,1,1]], "global_normal": [0,0,1e-9]}]})",
         "strokes[0].global_normal: point 0 has no direction"},
        {R"({"strokes": [{"points": [[0,0,0,1],[0,0,1,1]], "anchor": "bone"}]})",
         "strokes[0].anchor: must be"},
        {R"({"strokes": [{"points": [[0,0,0,1],[0,0,1,1]], "anchor": "joint"}]})",
         "strokes[0]: joint anchor without"},
        {R"({"strokes": [{"points": [[0,0,0,1],[0,0,1,1]], "anchor": "joint", "joint": "leg"}]})",
         "strokes[0].joint: no joint named 'leg'"},
        {R"({"strokes": [{"points": [[0,0,0,1],[0,0,1,1]], "anchor": "joint", "joint": 2}]})",
         "strokes[0].joint: value 2 not in [0, 1]"},
        {R"({"strokes": [{"points": [[0,0,0,1],[0,0,1,1]], "anchor": "joint", "joint": [1]}]})",
         "strokes[0].joint: must be a joint name (a string) or index"},
        {R"({"strokes": [{"points": [[0,0,0,1],[0,0,1,1]], "joint": "arm"}]})",
         "strokes[0].joint: only for joint anchors"},
        {R"({"strokes": [{"points": [[0,0,0,1],[0,0,1,1]], "anchor": "surface", "triangle": 2,
             "barycentric": [0, 0]}]})",
         "strokes[0].triangle: value 2 not in [0, 1]"},
        {R"({"strokes": [{"points": [[0,0,0,1],[0,0,1,1]], "anchor": "surface", "triangle": 0.5,
             "barycentric": [0, 0]}]})",
         "strokes[0].triangle: must be an integer"},
        {R"({"strokes": [{"points": [[0,0,0,1],[0,0,1,1]], "anchor": "surface", "triangle": 0,
             "barycentric": [0.7, 0.7]}]})",
         "strokes[0].barycentric: u + v above 1"},
        {R"({"strokes": [{"points": [[0,0,0,1],[0,0,1,1]]}, {"points": []}]})",
         "strokes[1].points: has 0 points"},
    };
    for (const Case& c : cases) {
        bake::BakedStrokes b;
        const bake::BakeError e = parse(c.json, &b);
        EXPECT_EQ(e.code, bake::BakeErrorCode::malformed_input) << c.json;
        EXPECT_NE(e.message.find(c.words), std::string::npos) << e.message;
        EXPECT_EQ(e.message.find('\n'), std::string::npos) << e.message;
        EXPECT_TRUE(b.empty()) << c.json;
    }
}

TEST(StrokeJson, JointsResolveByIndexToo) {
    bake::BakedStrokes b;
    const bake::BakeError e = parse(
        R"({"strokes": [{"anchor": "joint", "joint": 1, "points": [[0,0,0,1],[0,0,1,1]]},
                        {"anchor": "joint", "joint": "root", "points": [[0,0,0,1],[0,0,1,1]]}]})",
        &b);
    ASSERT_TRUE(e.ok()) << e.message;
    EXPECT_EQ(b.strokes[0].host, 1u);
    EXPECT_EQ(b.strokes[1].host, 0u);
}

TEST(StrokeJson, JointAnchorsNeedASkin) {
    bake::BakedStrokes b;
    const bake::BakeError e = parse(
        R"({"strokes": [{"anchor": "joint", "joint": "arm", "points": [[0,0,0,1],[0,0,1,1]]}]})",
        &b, /*skinned=*/false);
    EXPECT_EQ(e.code, bake::BakeErrorCode::malformed_input);
    EXPECT_NE(e.message.find("strokes[0].joint: joint 'arm': the scene has no skin"),
              std::string::npos)
        << e.message;
}

TEST(StrokeJson, MissingFileIsAnIoErrorNamingIt) {
    bake::RawScene s;
    bake::PointHierarchy p;
    make_scene(&s, &p, false);
    bake::BakedStrokes b;
    const bake::BakeError e = bake::load_strokes_json("/nonexistent/strokes.json", s, &b);
    EXPECT_EQ(e.code, bake::BakeErrorCode::io);
    EXPECT_NE(e.message.find("/nonexistent/strokes.json"), std::string::npos);
}

}  // namespace
