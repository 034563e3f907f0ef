// Principal curvature directions (bake/principal_curvature.h) and the CURV section
// (runtime/asset_curvature.cpp): on assets/torus.obj the stored direction runs around the
// tube, the direction of the larger curvature (1 / 0.4 against at most 1 / 0.6 along the
// tube); the section round-trips into PointsView; a count that is not the hierarchy's or a
// size the count does not fill is refused with a named error.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "bake/asset_writer.h"
#include "bake/point_hierarchy.h"
#include "bake/principal_curvature.h"
#include "bake/scene_import.h"
#include "bake/scene_orientation.h"
#include "bake/vertex_normals.h"
#include "runtime/asset.h"
#include "runtime/asset_format.h"
#include "runtime/crc32.h"
#include "runtime/particle_transform.h"
#include "runtime/stroke_anchor.h"
#include "tests/common/bake_fixtures.h"

namespace {

using namespace stipple;

const stipple::test::Torus& torus() {
    return stipple::test::prepared_torus(4000);
}

SurfaceFrame frame_at(const bake::RawScene& s, uint32_t triangle, float u, float v) {
    auto at = [&](const std::vector<float>& data, int corner) {
        const size_t i = s.indices[size_t(triangle) * 3 + size_t(corner)];
        return glm::vec3(data[i * 3], data[i * 3 + 1], data[i * 3 + 2]);
    };
    return surface_frame(at(s.positions, 0), at(s.positions, 1), at(s.positions, 2),
                         at(s.normals, 0), at(s.normals, 1), at(s.normals, 2), u, v);
}

// Degrees between a direction in the frame at `angle` and the torus's direction around the
// tube at the frame's origin, as lines (0 to 90).
float degrees_off_around_the_tube(const SurfaceFrame& f, float angle) {
    const glm::vec3 d = std::cos(angle) * f.x + std::sin(angle) * f.y;
    const glm::vec3 along = glm::normalize(glm::vec3(-f.origin.z, 0.0f, f.origin.x));
    const glm::vec3 around = glm::normalize(glm::cross(f.z, along));
    return std::atan2(std::abs(glm::dot(d, along)), std::abs(glm::dot(d, around))) * 57.2958f;
}

TEST(PrincipalCurvature, OnTheTorusTheDirectionRunsAroundTheTube) {
    const stipple::test::Torus& t = torus();
    const bake::BakedCurvature baked = bake::bake_curvature(t.scene, t.points);
    ASSERT_EQ(baked.angle.size(), t.points.size());
    std::vector<float> off;
    uint32_t confident_outside = 0, outside = 0, confident_inside = 0, inside = 0;
    for (size_t i = 0; i < t.points.size(); ++i) {
        const SurfaceFrame f =
            frame_at(t.scene, t.points.host_triangle[i], t.points.bary_u[i], t.points.bary_v[i]);
        off.push_back(
            degrees_off_around_the_tube(f, float(baked.angle[i]) * format::kCurvatureAngleStep));
        // Outer half (|p| > 1): curvature 2.5 around, at most 0.71 along; inner half: up to
        // 1.67 along, so the direction is less distinct there.
        const bool out = glm::length(glm::vec2(f.origin.x, f.origin.z)) > 1.0f;
        const bool confident = baked.confidence[i] >= kCurvatureConfident;
        (out ? outside : inside) += 1;
        (out ? confident_outside : confident_inside) += confident;
    }
    std::sort(off.begin(), off.end());
    const float median = off[off.size() / 2], p95 = off[off.size() * 95 / 100];
    std::printf("degrees off around the tube: median %.2f, 95th percentile %.2f, worst %.2f\n",
                median, p95, off.back());
    std::printf("confident: outer half %u of %u, inner half %u of %u\n", confident_outside, outside,
                confident_inside, inside);
    EXPECT_LE(median, 2.0f);
    EXPECT_LE(p95, 5.0f);
    EXPECT_LE(off.back(), 15.0f);
    EXPECT_EQ(confident_outside, outside);     // 2.5 against at most 0.71: never ambiguous
    EXPECT_GT(inside - confident_inside, 0u);  // near the hole |k2| -> 1.67: the runtime falls back
}

// Unsmoothed, the estimate is within 6% on the torus's 24-gon tube; smoothing (the default two
// rounds) averages tensors of neighbours turned by 15 degrees and shrinks them a little.
TEST(PrincipalCurvature, CurvaturesOfTheTorusAreItsRadii) {
    const stipple::test::Torus& t = torus();
    bake::CurvatureConfig raw;
    raw.smoothing = 0;
    const bake::VertexCurvature v = bake::vertex_curvature(t.scene, raw);
    // The top of the tube (y = 0.4): 1 / 0.4 around, 0 along.
    size_t top = 0;
    for (size_t i = 0; i < t.points.size(); ++i) {
        const SurfaceFrame f =
            frame_at(t.scene, t.points.host_triangle[i], t.points.bary_u[i], t.points.bary_v[i]);
        if (f.origin.y < 0.39f) continue;
        const bake::PointCurvature p = bake::point_curvature(
            t.scene, v, t.points.host_triangle[i], t.points.bary_u[i], t.points.bary_v[i]);
        EXPECT_NEAR(p.k_major, 2.5f, 0.15f);
        EXPECT_LT(p.k_minor, 0.2f);
        ++top;
    }
    EXPECT_GT(top, 10u);
}

// A two-triangle square and a four-point hierarchy, with and without CURV.
std::vector<uint8_t> encoded(const bake::BakedCurvature& curvature) {
    bake::RawScene s;
    bake::PointHierarchy p;
    test::tiny_square(&s, &p);
    return bake::encode_asset(s, p, bake::BakedStrokes(), bake::BakedLooks(), {}, curvature);
}

const bake::BakedCurvature kFour = {{0, 64, 128, 255}, {255, 50, 51, 0}};

// Rewrites the CURV section's count and size (bytes dropped from its end) and fixes the
// checksums, so only the loader's own checks can refuse it.
void corrupt(std::vector<uint8_t>* bytes, uint32_t count, uint64_t shorter) {
    format::FileHeader h;
    std::memcpy(&h, bytes->data(), sizeof(h));
    auto* table = reinterpret_cast<format::SectionEntry*>(bytes->data() + sizeof(h));
    for (uint32_t i = 0; i < h.section_count; ++i)
        if (table[i].tag == format::kTagCurvature) {
            std::memcpy(bytes->data() + table[i].offset, &count, 4);
            table[i].size -= shorter;
            table[i].crc = format::crc32(bytes->data() + table[i].offset, table[i].size);
        }
    h.table_crc = format::crc32(table, h.section_count * sizeof(format::SectionEntry));
    std::memcpy(bytes->data(), &h, sizeof(h));
}

TEST(AssetCurvature, TheStoredDirectionsLoad) {
    const std::vector<uint8_t> bytes = encoded(kFour);
    Asset a;
    ASSERT_TRUE(load_asset_memory(bytes.data(), bytes.size(), &a).ok());
    ASSERT_NE(a.points.curvature_angle, nullptr);
    ASSERT_NE(a.points.curvature_confidence, nullptr);
    for (uint32_t i = 0; i < 4; ++i) {
        EXPECT_EQ(a.points.curvature_angle[i], kFour.angle[i]);
        EXPECT_EQ(a.points.curvature_confidence[i], kFour.confidence[i]);
    }
    EXPECT_EQ(a.section_size[kSectionCurvature], 12u);  // count + 4 angles + 4 confidences
    EXPECT_STREQ(section_name(kSectionCurvature), "CURV");
    // The field: the stored angle where confident (>= 51), the random field elsewhere.
    EXPECT_FLOAT_EQ(curvature_field_angle(a.points, 0), 0.0f);
    EXPECT_FLOAT_EQ(curvature_field_angle(a.points, 1), random_field_angle(1));
    EXPECT_FLOAT_EQ(curvature_field_angle(a.points, 2), 1.57079632679f);
    EXPECT_FLOAT_EQ(curvature_field_angle(a.points, 3), random_field_angle(3));
    EXPECT_FLOAT_EQ(curvature_field_angle(a.points, 7), random_field_angle(7));  // past the points

    const std::vector<uint8_t> none = encoded(bake::BakedCurvature());
    Asset b;
    ASSERT_TRUE(load_asset_memory(none.data(), none.size(), &b).ok());
    EXPECT_EQ(b.points.curvature_angle, nullptr);
    EXPECT_EQ(b.section_size[kSectionCurvature], 0u);
    for (uint32_t i = 0; i < 4; ++i)
        EXPECT_FLOAT_EQ(curvature_field_angle(b.points, i), random_field_angle(i));
    EXPECT_GT(bytes.size(), none.size());  // an opt-in section
    // Mismatched arrays are not written.
    const std::vector<uint8_t> odd = encoded({{1, 2, 3}, {1, 2, 3}});
    EXPECT_EQ(odd, none);
}

TEST(AssetCurvature, TheCountMustBeTheHierarchys) {
    for (uint32_t count : {0u, 3u, 5u, 0xFFFFFFFFu}) {
        std::vector<uint8_t> bytes = encoded(kFour);
        corrupt(&bytes, count, 0);
        Asset a;
        const Status st = load_asset_memory(bytes.data(), bytes.size(), &a);
        EXPECT_EQ(st.error, LoadError::malformed_section) << count << ": " << st.message;
        EXPECT_NE(std::strstr(st.message, "CURV: "), nullptr) << st.message;
        EXPECT_EQ(a.points.curvature_angle, nullptr);
    }
}

TEST(AssetCurvature, TheDirectionsMustFillTheSection) {
    for (uint64_t shorter : {1u, 4u, 9u, 12u}) {
        std::vector<uint8_t> bytes = encoded(kFour);
        corrupt(&bytes, 4, shorter);
        Asset a;
        const Status st = load_asset_memory(bytes.data(), bytes.size(), &a);
        EXPECT_EQ(st.error, LoadError::malformed_section) << shorter << ": " << st.message;
        EXPECT_NE(std::strstr(st.message, "CURV: "), nullptr) << st.message;
    }
}

}  // namespace
