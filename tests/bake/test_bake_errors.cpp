// The bake's error type (bake/bake_error.h): every public bake function that can fail says
// what kind of failure it is. Missing files are io, broken files malformed_input, valid
// input the bake cannot handle unsupported, bad options invalid_option; messages stay one
// line naming the file.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "bake/asset_writer.h"
#include "bake/gltf_file_access.h"
#include "bake/point_hierarchy.h"
#include "bake/scene_import.h"
#include "tests/common/fixtures.h"
#include "tests/common/gltf_writer.h"

namespace stipple::bake {
namespace {

// One triangle whose index buffer holds `last` as its third index.
void write_triangle_gltf(const std::string& path, uint16_t last,
                         const std::string& extensions = "") {
    test::GltfBin bin;
    bin.put<float>({0, 0, 0, 1, 0, 0, 0, 1, 0});
    bin.put<uint16_t>({0, 1, last}).pad4();
    test::write_gltf(path,
                     R"({
      "asset": {"version": "2.0"},)" +
                         extensions + R"(
      "scene": 0, "scenes": [{"nodes": [0]}],
      "nodes": [{"mesh": 0}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
      "buffers": [@BUFFER@],
      "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                      {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
      "accessors": [
        {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
         "min": [0, 0, 0], "max": [1, 1, 0]},
        {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}]
    })",
                     bin);
}

TEST(BakeErrors, DefaultIsSuccess) {
    const BakeError ok;
    EXPECT_TRUE(ok.ok());
    EXPECT_EQ(ok.code, BakeErrorCode::none);
    EXPECT_FALSE(malformed_input("x").ok());
    EXPECT_STREQ(bake_error_code_name(BakeErrorCode::out_of_memory), "out_of_memory");
    EXPECT_STREQ(bake_error_code_name(BakeErrorCode::malformed_input), "malformed_input");
    EXPECT_EQ(prefixed("a: ", malformed_input("b")).message, "a: b");
    EXPECT_TRUE(prefixed("a: ", BakeError()).message.empty());
}

TEST(BakeErrors, ImportersSayWhatFailed) {
    test::ScratchDir dir;
    RawScene s;
    BakeError e = import_scene(dir.file("missing.glb"), &s);
    EXPECT_EQ(e.code, BakeErrorCode::io) << e.message;
    EXPECT_EQ(e.message, dir.file("missing.glb") + ": cannot open file: No such file or directory");
    e = import_scene(dir.file("missing.stl"), &s);
    EXPECT_EQ(e.code, BakeErrorCode::io) << e.message;
    e = import_scene(dir.file("mesh.fbx"), &s);
    EXPECT_EQ(e.code, BakeErrorCode::unsupported) << e.message;

    const std::string bad = dir.file("bad_index.gltf");
    write_triangle_gltf(bad, 5);
    e = import_gltf(bad, &s);
    EXPECT_EQ(e.code, BakeErrorCode::malformed_input) << e.message;
    EXPECT_EQ(e.message, bad + ": mesh 0 primitive 0: index 5 out of range (vertex count 3)");
    EXPECT_EQ(s.vertex_count(), 0u);  // nothing half-imported

    const std::string draco = dir.file("draco.gltf");
    write_triangle_gltf(draco, 2,
                        R"("extensionsUsed": ["KHR_draco_mesh_compression"],
                           "extensionsRequired": ["KHR_draco_mesh_compression"],)");
    e = import_gltf(draco, &s);
    EXPECT_EQ(e.code, BakeErrorCode::unsupported) << e.message;
    EXPECT_NE(e.message.find("KHR_draco_mesh_compression is unsupported"), std::string::npos)
        << e.message;

    const std::string good = dir.file("good.gltf");
    write_triangle_gltf(good, 2);
    e = import_scene(good, &s);
    ASSERT_TRUE(e.ok()) << e.message;
    EXPECT_EQ(s.triangle_count(), 1u);
}

TEST(BakeErrors, HierarchyAndWriterSayWhatFailed) {
    RawScene s;
    s.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    s.normals = {0, 0, 1, 0, 0, 1, 0, 0, 1};
    s.indices = {0, 1, 2};
    HierarchyConfig config;
    config.point_count = 0;
    PointHierarchy p;
    BakeError e = build_point_hierarchy(s, config, &p, nullptr);
    EXPECT_EQ(e.code, BakeErrorCode::invalid_option);
    EXPECT_EQ(e.message, "point count must be positive");
    config.point_count = 10;
    s.indices = {0, 1, 7};
    e = build_point_hierarchy(s, config, &p, nullptr);
    EXPECT_EQ(e.code, BakeErrorCode::malformed_input);
    s.indices = {0, 1, 2};
    e = build_point_hierarchy(s, config, &p, nullptr);
    ASSERT_TRUE(e.ok()) << e.message;
    EXPECT_EQ(p.size(), 10u);

    test::ScratchDir dir;
    e = write_asset(dir.file("no_such_dir/out.stip"), std::vector<uint8_t>(4, 0));
    EXPECT_EQ(e.code, BakeErrorCode::io);
    EXPECT_NE(e.message.find("cannot open"), std::string::npos) << e.message;
}

// A data URI over the cap is refused from its length in the JSON text, before decoding.
TEST(BakeErrors, DataUrisOverTheCapAreRefused) {
    const std::string json = R"({"buffers": [{"uri": "data:application/octet-stream;base64,)" +
                             std::string(64, 'A') + R"(", "byteLength": 48}]})";
    const auto* text = reinterpret_cast<const unsigned char*>(json.data());
    EXPECT_TRUE(gltf::check_data_uris(text, json.size(), 200).ok());
    const BakeError e = gltf::check_data_uris(text, json.size(), 64);
    EXPECT_EQ(e.code, BakeErrorCode::unsupported);
    EXPECT_EQ(e.message.find("a data URI of 101 bytes is over the 64 bytes cap"), 0u) << e.message;
    // An unterminated one counts to the end of the text.
    const std::string cut = json.substr(0, json.find("AAAA") + 10);
    EXPECT_FALSE(
        gltf::check_data_uris(reinterpret_cast<const unsigned char*>(cut.data()), cut.size(), 40)
            .ok());
}

}  // namespace
}  // namespace stipple::bake
