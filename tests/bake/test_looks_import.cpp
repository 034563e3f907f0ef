// The bake's looks (issue 9): glTF materials into parts (one per material, or per primitive
// without one), base colours sampled from the texture at each point (thesis §8.6), parts
// made transparent by alphaMode BLEND or --transparent (§7.4), and crease edges (§7.1).
#include <gtest/gtest.h>
#include <stb/stb_image_write.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "bake/point_hierarchy.h"
#include "bake/scene_import.h"
#include "bake/surface_looks.h"
#include "runtime/asset_format.h"
#include "tests/common/gltf_writer.h"
#include "tests/common/scratch.h"

namespace {

using namespace stipple;

std::string temp_path(const std::string& name) {
    return stipple::test::scratch_path("looks_" + name);
}

// A 64 x 64 texture of 8 x 8 squares, 8 texels each: black where (column + row) is even.
std::vector<uint8_t> checker_png() {
    std::vector<uint8_t> rgba(64 * 64 * 4);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            const uint8_t c = ((x / 8 + y / 8) % 2 == 0) ? 0 : 255;
            uint8_t* p = &rgba[size_t(y * 64 + x) * 4];
            p[0] = p[1] = p[2] = c;
            p[3] = 255;
        }
    std::vector<uint8_t> png;
    stbi_write_png_to_func(
        [](void* context, void* data, int size) {
            auto* out = static_cast<std::vector<uint8_t>*>(context);
            const uint8_t* d = static_cast<const uint8_t*>(data);
            out->insert(out->end(), d, d + size);
        },
        &png, 64, 64, 4, rgba.data(), 64 * 4);
    return png;
}

// The unit square in the z = 0 plane with texture coordinates (x, y), textured by the
// checker (material factor white, sampler `wrap`).
std::string write_checker_quad(int wrap = 10497, const std::vector<uint8_t>& png = checker_png()) {
    test::GltfBin bin;
    bin.put<float>({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0});
    bin.put<float>({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1});
    bin.put<float>({0, 0, 1, 0, 1, 1, 0, 1});
    bin.put<uint16_t>({0, 1, 2, 0, 2, 3});
    bin.bytes.insert(bin.bytes.end(), png.begin(), png.end());
    const std::string path = temp_path("checker.gltf");
    test::write_gltf(path,
                     R"({
      "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
      "nodes": [{"mesh": 0}],
      "meshes": [{"name": "quad", "primitives": [{"attributes":
        {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3, "material": 0}]}],
      "materials": [{"name": "checker", "pbrMetallicRoughness":
        {"baseColorTexture": {"index": 0, "texCoord": 0}}}],
      "textures": [{"source": 0, "sampler": 0}],
      "samplers": [{"wrapS": )" +
                         std::to_string(wrap) + R"(, "wrapT": )" + std::to_string(wrap) + R"(}],
      "images": [{"bufferView": 4, "mimeType": "image/png"}],
      "buffers": [@BUFFER@],
      "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                      {"buffer": 0, "byteOffset": 48, "byteLength": 48},
                      {"buffer": 0, "byteOffset": 96, "byteLength": 32},
                      {"buffer": 0, "byteOffset": 128, "byteLength": 12},
                      {"buffer": 0, "byteOffset": 140, "byteLength": )" +
                         std::to_string(png.size()) + R"(}],
      "accessors": [
        {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
         "min": [0, 0, 0], "max": [1, 1, 0]},
        {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
        {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
        {"bufferView": 3, "componentType": 5123, "count": 6, "type": "SCALAR"}]
    })",
                     bin);
    return path;
}

bake::PointHierarchy points_on(const bake::RawScene& scene, uint32_t count) {
    bake::HierarchyConfig config;
    config.point_count = count;
    bake::PointHierarchy points;
    bake::HierarchyStats stats;
    EXPECT_TRUE(bake::build_point_hierarchy(scene, config, &points, &stats).ok());
    return points;
}

bake::RawScene imported(const std::string& path, const bake::ImportOptions& options) {
    bake::RawScene scene;
    const bake::BakeError error = bake::import_scene(path, &scene, options);
    EXPECT_TRUE(error.ok()) << error.message;
    return scene;
}

TEST(LooksImport, PointColoursFollowTheCheckerTexture) {
    bake::ImportOptions options;
    options.looks = true;
    const bake::RawScene scene = imported(write_checker_quad(), options);
    ASSERT_EQ(scene.parts.size(), 1u);
    ASSERT_EQ(scene.textures.size(), 1u);
    ASSERT_EQ(scene.uvs.size(), scene.vertex_count() * 2);
    const bake::PointHierarchy points = points_on(scene, 3000);
    const bake::BakedLooks looks = bake::bake_looks(scene, points, bake::LooksConfig{false, 40});
    ASSERT_EQ(looks.point_colour.size(), points.size() * 4);
    EXPECT_TRUE(looks.part_flags.size() == 1 && looks.part_flags[0] == 0);
    size_t black = 0, white = 0;
    for (size_t i = 0; i < points.size(); ++i) {
        // The point's position (x, y) is its texture coordinate.
        const uint32_t* t = &scene.indices[size_t(points.host_triangle[i]) * 3];
        const float w[3] = {points.bary_u[i], points.bary_v[i],
                            1 - points.bary_u[i] - points.bary_v[i]};
        float x = 0, y = 0;
        for (int k = 0; k < 3; ++k) {
            x += w[k] * scene.positions[size_t(t[k]) * 3];
            y += w[k] * scene.positions[size_t(t[k]) * 3 + 1];
        }
        // Away from a square's border by more than a texel, bilinear sampling is pure.
        const float fx = x * 8 - std::floor(x * 8), fy = y * 8 - std::floor(y * 8);
        if (fx < 0.2f || fx > 0.8f || fy < 0.2f || fy > 0.8f) continue;
        const bool dark = (int(x * 8) + int(y * 8)) % 2 == 0;
        const uint8_t* c = &looks.point_colour[i * 4];
        const uint8_t want = dark ? 0 : 255;
        EXPECT_TRUE(c[0] == want && c[1] == want && c[2] == want && c[3] == 255)
            << "point " << i << " at (" << x << ", " << y << ") has " << int(c[0]);
        (dark ? black : white)++;
    }
    EXPECT_GT(black, points.size() / 8);
    EXPECT_GT(white, points.size() / 8);
}

TEST(LooksImport, SamplerWrapModesRepeatMirrorAndClamp) {
    bake::ImportOptions options;
    options.looks = true;
    for (int wrap : {10497, 33648, 33071}) {
        const bake::RawScene scene = imported(write_checker_quad(wrap), options);
        ASSERT_EQ(scene.textures.size(), 1u);
        float inside[4], outside[4];
        // Square (0, 0) is black, square (7, 0) white.
        bake::base_colour_at(scene, scene.parts[0], 1.0f / 16, 1.0f / 16, inside);
        EXPECT_EQ(inside[0], 0.0f);
        bake::base_colour_at(scene, scene.parts[0], 1.0f + 1.0f / 16, 1.0f / 16, outside);
        // REPEAT lands on square 0 (black); MIRRORED_REPEAT and CLAMP on square 7 (white).
        EXPECT_EQ(outside[0], wrap == 10497 ? 0.0f : 1.0f) << "wrap " << wrap;
    }
}

TEST(LooksImport, HugeOrBrokenImagesAreSkippedWithAWarning) {
    bake::ImportOptions options;
    options.looks = true;
    std::vector<uint8_t> huge = checker_png();
    // IHDR width and height (big-endian, bytes 16-23): 40000 x 40000 would decode to 6.4 GB.
    for (int k : {16, 20}) {
        huge[size_t(k) + 2] = 0x9C;
        huge[size_t(k) + 3] = 0x40;
    }
    std::vector<uint8_t> broken(200, 0x5A);
    for (const auto& image : {huge, broken}) {
        const bake::RawScene scene = imported(write_checker_quad(10497, image), options);
        ASSERT_EQ(scene.parts.size(), 1u);
        EXPECT_EQ(scene.parts[0].texture, -1);
        EXPECT_TRUE(scene.textures.empty());
        bool warned = false;
        for (const std::string& w : scene.warnings) warned = warned || w.find("image 0: ") == 0;
        EXPECT_TRUE(warned);
    }
}

TEST(LooksImport, DanglingTextureReferencesLeaveThePartUntextured) {
    // Texture 7 of none, sampled with TEXCOORD_3 the primitive lacks; image source -1.
    for (const char* material :
         {R"({"pbrMetallicRoughness": {"baseColorTexture": {"index": 7, "texCoord": 3}}})",
          R"({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0, "texCoord": 3}}})"}) {
        test::GltfBin bin;
        bin.put<float>({0, 0, 0, 1, 0, 0, 0, 1, 0});
        const std::string path = temp_path("dangling.gltf");
        test::write_gltf(path,
                         std::string(R"({
          "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
          "nodes": [{"mesh": 0}],
          "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "material": 0}]}],
          "materials": [)") + material +
                             R"(],
          "textures": [{"source": -1}],
          "buffers": [@BUFFER@],
          "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}],
          "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                         "min": [0, 0, 0], "max": [1, 1, 0]}]
        })",
                         bin);
        bake::ImportOptions options;
        options.looks = true;
        bake::RawScene scene;
        const bake::BakeError error = bake::import_scene(path, &scene, options);
        if (!error.ok()) {  // tinygltf may refuse the dangling index itself: one line
            EXPECT_EQ(error.message.find('\n'), std::string::npos);
            continue;
        }
        ASSERT_EQ(scene.parts.size(), 1u);
        EXPECT_EQ(scene.parts[0].texture, -1);
        EXPECT_TRUE(scene.uvs.empty());
        const bake::PointHierarchy points = points_on(scene, 50);
        EXPECT_TRUE(bake::bake_looks(scene, points, bake::LooksConfig{true, 40}).empty());
    }
}

TEST(LooksImport, WithoutLooksNoImageIsDecoded) {
    const bake::RawScene scene = imported(write_checker_quad(), bake::ImportOptions());
    ASSERT_EQ(scene.parts.size(), 1u);
    EXPECT_EQ(scene.parts[0].texture, -1);
    EXPECT_TRUE(scene.textures.empty());
    EXPECT_TRUE(scene.uvs.empty());
}

// Four nodes, one triangle each: "glassmesh" (material "glass", BLEND), "woodmesh" and
// "woodmesh2" (both material "wood", a blue-violet factor) and "plainmesh" (no material).
std::string write_parts_scene() {
    test::GltfBin bin;
    bin.put<float>({0, 0, 0, 1, 0, 0, 0, 1, 0});
    bin.put<uint16_t>({0, 1, 2});
    const std::string path = temp_path("parts.gltf");
    test::write_gltf(path, R"({
      "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 1, 2, 3]}],
      "nodes": [{"mesh": 0}, {"mesh": 1, "translation": [2, 0, 0]},
                {"mesh": 2, "translation": [4, 0, 0]}, {"mesh": 3, "translation": [6, 0, 0]}],
      "meshes": [
        {"name": "glassmesh", "primitives": [{"attributes": {"POSITION": 0}, "indices": 1,
          "material": 0}]},
        {"name": "woodmesh", "primitives": [{"attributes": {"POSITION": 0}, "indices": 1,
          "material": 1}]},
        {"name": "woodmesh2", "primitives": [{"attributes": {"POSITION": 0}, "indices": 1,
          "material": 1}]},
        {"name": "plainmesh", "primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
      "materials": [
        {"name": "glass", "alphaMode": "BLEND",
         "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 0.3]}},
        {"name": "wood", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.25, 1, 1]}}],
      "buffers": [@BUFFER@],
      "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                      {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
      "accessors": [
        {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
         "min": [0, 0, 0], "max": [1, 1, 0]},
        {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}]
    })",
                     bin);
    return path;
}

TEST(LooksImport, OnePartPerMaterialAndPerPrimitiveWithoutOne) {
    const bake::RawScene scene = imported(write_parts_scene(), bake::ImportOptions());
    ASSERT_EQ(scene.parts.size(), 3u);
    EXPECT_EQ(scene.triangle_part, (std::vector<uint16_t>{0, 1, 1, 2}));
    EXPECT_EQ(scene.parts[0].material_name, "glass");
    EXPECT_TRUE(scene.parts[0].blend && scene.parts[0].transparent);
    EXPECT_EQ(scene.parts[1].material_name, "wood");
    EXPECT_FALSE(scene.parts[1].transparent);
    EXPECT_EQ(scene.parts[1].mesh_names, (std::vector<std::string>{"woodmesh", "woodmesh2"}));
    EXPECT_EQ(scene.parts[1].colour[1], 0.25f);
    EXPECT_EQ(scene.parts[2].material_name, "");
    EXPECT_EQ(scene.parts[2].colour[0], 1.0f);
    bake::PointHierarchy points = points_on(scene, 200);
    const bake::BakedLooks looks = bake::bake_looks(scene, points, bake::LooksConfig{false, 40});
    EXPECT_EQ(looks.part_flags, (std::vector<uint8_t>{format::kLookPartTransparent, 0, 0}));
    EXPECT_EQ(looks.part_colour,
              (std::vector<uint8_t>{255, 255, 255, 77, 128, 64, 255, 255, 255, 255, 255, 255}));
    // Each point takes its host triangle's part colour.
    ASSERT_EQ(looks.point_colour.size(), points.size() * 4);
    for (size_t i = 0; i < points.size(); ++i) {
        const uint16_t part = scene.triangle_part[points.host_triangle[i]];
        for (int c = 0; c < 4; ++c)
            ASSERT_EQ(looks.point_colour[i * 4 + size_t(c)], looks.part_colour[part * 4u + c]);
    }
}

TEST(LooksImport, TransparentNamesMarkMaterialsAndMeshes) {
    bake::ImportOptions options;
    options.transparent = {"wood"};
    bake::RawScene scene = imported(write_parts_scene(), options);
    ASSERT_EQ(scene.parts.size(), 3u);
    EXPECT_TRUE(scene.parts[1].transparent);
    EXPECT_FALSE(scene.parts[1].blend);
    // A mesh name splits its part off the shared material.
    options.transparent = {"woodmesh2"};
    scene = imported(write_parts_scene(), options);
    ASSERT_EQ(scene.parts.size(), 4u);
    EXPECT_EQ(scene.triangle_part, (std::vector<uint16_t>{0, 1, 2, 3}));
    EXPECT_FALSE(scene.parts[1].transparent);
    EXPECT_TRUE(scene.parts[2].transparent);
    EXPECT_EQ(scene.parts[2].material_name, "wood");
}

TEST(LooksImport, UnknownTransparentNamesAreAnErrorNamingThem) {
    bake::ImportOptions options;
    options.transparent = {"glass", "nope", "also-not"};
    bake::RawScene scene;
    const bake::BakeError error = bake::import_scene(write_parts_scene(), &scene, options);
    ASSERT_FALSE(error.ok());
    EXPECT_EQ(error.code, bake::BakeErrorCode::invalid_option);
    EXPECT_NE(error.message.find("'nope', 'also-not'"), std::string::npos) << error.message;
    // Only the unknown names are named as unknown; the input's names follow.
    const size_t names = error.message.find("(names: ");
    ASSERT_NE(names, std::string::npos) << error.message;
    EXPECT_GT(error.message.find("'glass'"), names) << error.message;
    EXPECT_NE(error.message.find("'woodmesh2'"), std::string::npos) << error.message;
    EXPECT_EQ(scene.triangle_count(), 0u);
}

// OBJ text of a closed mesh.
std::string write_obj(const std::string& name, const std::string& text) {
    const std::string path = temp_path(name);
    FILE* f = std::fopen(path.c_str(), "w");
    std::fputs(text.c_str(), f);
    std::fclose(f);
    return path;
}

std::string cube_obj() {
    return "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
           "f 1 4 3\nf 1 3 2\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\n"
           "f 4 8 7\nf 4 7 3\nf 1 5 8\nf 1 8 4\nf 2 3 7\nf 2 7 6\n";
}

// A UV sphere of `slices` x `stacks` quads (two triangles each, fans at the poles).
std::string sphere_obj(int slices, int stacks) {
    std::string s = "v 0 1 0\n";
    for (int i = 1; i < stacks; ++i)
        for (int j = 0; j < slices; ++j) {
            const double th = M_PI * i / stacks, ph = 2 * M_PI * j / slices;
            s += "v " + std::to_string(std::sin(th) * std::cos(ph)) + " " +
                 std::to_string(std::cos(th)) + " " + std::to_string(std::sin(th) * std::sin(ph)) +
                 "\n";
        }
    s += "v 0 -1 0\n";
    const int bottom = 2 + (stacks - 1) * slices;
    auto at = [&](int i, int j) { return 2 + (i - 1) * slices + (j % slices); };
    for (int j = 0; j < slices; ++j) {
        s += "f 1 " + std::to_string(at(1, j + 1)) + " " + std::to_string(at(1, j)) + "\n";
        s += "f " + std::to_string(bottom) + " " + std::to_string(at(stacks - 1, j)) + " " +
             std::to_string(at(stacks - 1, j + 1)) + "\n";
    }
    for (int i = 1; i + 1 < stacks; ++i)
        for (int j = 0; j < slices; ++j) {
            const std::string a = std::to_string(at(i, j)), b = std::to_string(at(i, j + 1)),
                              c = std::to_string(at(i + 1, j + 1)),
                              d = std::to_string(at(i + 1, j));
            s += "f " + a + " " + b + " " + c + "\nf " + a + " " + c + " " + d + "\n";
        }
    return s;
}

TEST(LooksImport, PlyVertexColoursAreInterpolatedAtEachPoint) {
    // A square whose left vertices are red and right vertices blue (8-bit sRGB 255 and 0,
    // which decode to linear 1 and 0 exactly).
    const std::string ply = write_obj("colours.ply",
                                      "ply\nformat ascii 1.0\nelement vertex 4\n"
                                      "property float x\nproperty float y\nproperty float z\n"
                                      "property uchar red\nproperty uchar green\n"
                                      "property uchar blue\nelement face 2\n"
                                      "property list uchar int vertex_indices\nend_header\n"
                                      "0 0 0 255 0 0\n1 0 0 0 0 255\n1 1 0 0 0 255\n"
                                      "0 1 0 255 0 0\n3 0 1 2\n3 0 2 3\n");
    const bake::RawScene scene = imported(ply, {});
    ASSERT_EQ(scene.colours.size(), scene.vertex_count() * 4);
    EXPECT_TRUE(scene.parts.empty());
    const bake::PointHierarchy points = points_on(scene, 500);
    const bake::BakedLooks looks = bake::bake_looks(scene, points, bake::LooksConfig{false, 40});
    ASSERT_EQ(looks.point_colour.size(), points.size() * 4);
    EXPECT_TRUE(looks.part_flags.empty());  // one part: no part table
    for (size_t i = 0; i < points.size(); ++i) {
        const uint32_t* t = &scene.indices[size_t(points.host_triangle[i]) * 3];
        const float w[3] = {points.bary_u[i], points.bary_v[i],
                            1 - points.bary_u[i] - points.bary_v[i]};
        float x = 0;
        for (int k = 0; k < 3; ++k) x += w[k] * scene.positions[size_t(t[k]) * 3];
        // Red falls linearly from 1 at x = 0 to 0 at x = 1, blue rises; green stays 0.
        const uint8_t* c = &looks.point_colour[i * 4];
        EXPECT_NEAR(c[0], (1 - x) * 255, 1.01) << "point " << i;
        EXPECT_NEAR(c[2], x * 255, 1.01) << "point " << i;
        EXPECT_EQ(c[1], 0);
        EXPECT_EQ(c[3], 255);
    }
}

TEST(LooksImport, GltfColour0MultipliesTheBaseColourFactor) {
    // One triangle, COLOR_0 red, green, blue at its corners; factor (0.5, 1, 1, 1).
    test::GltfBin bin;
    bin.put<float>({0, 0, 0, 1, 0, 0, 0, 1, 0});
    bin.put<float>({1, 0, 0, 0, 1, 0, 0, 0, 1});
    const std::string path = temp_path("colour0.gltf");
    test::write_gltf(path, R"({
      "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
      "nodes": [{"mesh": 0}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "COLOR_0": 1},
                                  "material": 0}]}],
      "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.5, 1, 1, 1]}}],
      "buffers": [@BUFFER@],
      "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                      {"buffer": 0, "byteOffset": 36, "byteLength": 36}],
      "accessors": [
        {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
         "min": [0, 0, 0], "max": [1, 1, 0]},
        {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"}]
    })",
                     bin);
    bake::ImportOptions options;
    options.looks = true;
    const bake::RawScene scene = imported(path, options);
    ASSERT_EQ(scene.colours, (std::vector<float>{1, 0, 0, 1, 0, 1, 0, 1, 0, 0, 1, 1}));
    const bake::PointHierarchy points = points_on(scene, 300);
    const bake::BakedLooks looks = bake::bake_looks(scene, points, bake::LooksConfig{false, 40});
    ASSERT_EQ(looks.point_colour.size(), points.size() * 4);
    for (size_t i = 0; i < points.size(); ++i) {
        const uint32_t* t = &scene.indices[size_t(points.host_triangle[i]) * 3];
        const float w[3] = {points.bary_u[i], points.bary_v[i],
                            1 - points.bary_u[i] - points.bary_v[i]};
        float rgb[3] = {0, 0, 0};  // the corners' colours at the point
        for (int k = 0; k < 3; ++k)
            for (int c = 0; c < 3; ++c) rgb[c] += w[k] * scene.colours[size_t(t[k]) * 4 + c];
        const uint8_t* got = &looks.point_colour[i * 4];
        EXPECT_NEAR(got[0], 0.5f * rgb[0] * 255, 0.51f);
        EXPECT_NEAR(got[1], rgb[1] * 255, 0.51f);
        EXPECT_NEAR(got[2], rgb[2] * 255, 0.51f);
    }
    // Without looks the colours are not read.
    EXPECT_TRUE(imported(path, bake::ImportOptions()).colours.empty());
}

TEST(LooksImport, CubeHasTwelveCreasesAndASphereNone) {
    const bake::RawScene cube = imported(write_obj("cube.obj", cube_obj()), {});
    ASSERT_EQ(cube.triangle_count(), 12u);
    const std::vector<uint32_t> creases = bake::crease_edges(cube, 40);
    EXPECT_EQ(creases.size(), 12u * 4);
    for (size_t e = 0; e < creases.size(); e += 4) {
        EXPECT_NE(creases[e + 3], format::kNoFace);
        EXPECT_NE(creases[e + 2], creases[e + 3]);
    }
    EXPECT_EQ(bake::crease_edges(cube, 100).size(), 0u);  // the cube's edges are 90 degrees
    const bake::RawScene sphere = imported(write_obj("sphere.obj", sphere_obj(32, 16)), {});
    EXPECT_EQ(bake::crease_edges(sphere, 40).size(), 0u);
    EXPECT_GT(bake::crease_edges(sphere, 5).size(), 0u);
    // A static mesh is one white opaque part: only its creases are looks.
    const bake::PointHierarchy points = points_on(cube, 100);
    const bake::BakedLooks looks = bake::bake_looks(cube, points, bake::LooksConfig{true, 40});
    EXPECT_EQ(looks.creases, creases);
    EXPECT_TRUE(looks.point_colour.empty() && looks.part_flags.empty());
    EXPECT_TRUE(bake::bake_looks(cube, points, bake::LooksConfig{false, 40}).empty());
}

TEST(LooksImport, OpenSheetBoundariesAreNotCreases) {
    // Two triangles folded at 90 degrees: one crease, four boundary edges that are not.
    const bake::RawScene fold = imported(
        write_obj("fold.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 1 0 1\nf 1 2 3\nf 1 4 2\n"), {});
    const std::vector<uint32_t> creases = bake::crease_edges(fold, 40);
    ASSERT_EQ(creases.size(), 4u);
    EXPECT_EQ(std::min(creases[0], creases[1]), 0u);
    EXPECT_EQ(std::max(creases[0], creases[1]), 1u);
}

}  // namespace
