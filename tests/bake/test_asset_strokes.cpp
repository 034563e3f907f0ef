// The STRK section (paintstrokes): the writer's bytes round-trip through the loader, every
// rule of runtime/asset_strokes.cpp refuses a hostile record with its LoadError and a
// one-line message naming STRK, truncated or corrupted strokes never crash the loader, and
// assets without strokes keep their bytes and load with no strokes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "bake/asset_writer.h"
#include "bake/bake_random.h"
#include "runtime/asset.h"
#include "runtime/asset_format.h"
#include "runtime/asset_limits.h"

namespace {

using namespace stipple;

// A skinned quad (2 triangles, 2 joints) with a three-point hierarchy; `skinned` false drops
// the skin.
void make_scene(bake::RawScene* s, bake::PointHierarchy* p, bool skinned = true) {
    *s = bake::RawScene();
    *p = bake::PointHierarchy();
    s->positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    s->normals = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    s->indices = {0, 1, 2, 0, 2, 3};
    if (skinned) {
        s->joints = {0, 0, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0};
        s->weights = {1, 0, 0, 0, 0.5f, 0.5f, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
        s->nodes.resize(2);
        s->nodes[1].parent = 0;
        s->joint_nodes = {0, 1};
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

format::StrokePointRecord control_point(float x, float y, float z, float r) {
    format::StrokePointRecord p = {};
    p.position[0] = x;
    p.position[1] = y;
    p.position[2] = z;
    p.radius = r;
    p.colour[0] = 10;
    p.colour[1] = 20;
    p.colour[2] = 30;
    p.reflectance = 77;
    p.op_min = 200;
    p.op_max = 255;
    p.global_depth = 128;
    p.global_normal[2] = 127;
    return p;
}

// Three strokes, one per anchor kind: surface (rooted on point 2), object, joint 1.
bake::BakedStrokes make_strokes() {
    bake::BakedStrokes b;
    format::StrokeRecord s = {};
    s.first_point = 0;
    s.point_count = 3;
    s.anchor = format::kAnchorSurface;
    s.host = 1;
    s.bary_u = 0.0f;
    s.bary_v = 1.0f;
    s.root_point = 2;
    s.op_centre = 255;
    s.op_edge = 40;
    b.strokes.push_back(s);
    s = {};
    s.first_point = 3;
    s.point_count = 2;
    s.anchor = format::kAnchorObject;
    s.root_point = format::kNoRootPoint;
    b.strokes.push_back(s);
    s.first_point = 5;
    s.point_count = 4;
    s.anchor = format::kAnchorJoint;
    s.host = 1;
    b.strokes.push_back(s);
    for (int i = 0; i < 9; ++i) b.points.push_back(control_point(0.1f * i, 0, 0.05f * i, 0.01f));
    b.points[4].global_normal[2] = 0;  // no global shading
    return b;
}

std::vector<uint8_t> encoded(const bake::BakedStrokes& strokes, bool skinned = true) {
    bake::RawScene s;
    bake::PointHierarchy p;
    make_scene(&s, &p, skinned);
    return bake::encode_asset(s, p, strokes);
}

Status load(const std::vector<uint8_t>& bytes, Asset* a) {
    return load_asset_memory(bytes.data(), bytes.size(), a);
}

// Loads an asset whose strokes are make_strokes() edited by `edit`; expects `error` and a
// one-line message naming STRK.
void expect_refused(const std::function<void(bake::BakedStrokes*)>& edit, LoadError error,
                    const char* words, bool skinned = true) {
    bake::BakedStrokes b = make_strokes();
    edit(&b);
    Asset a;
    const Status st = load(encoded(b, skinned), &a);
    ASSERT_FALSE(st.ok());
    EXPECT_EQ(st.error, error) << st.message;
    EXPECT_EQ(std::string(st.message).rfind("STRK: ", 0), 0u) << st.message;
    EXPECT_NE(std::string(st.message).find(words), std::string::npos) << st.message;
    EXPECT_EQ(std::string(st.message).find('\n'), std::string::npos);
    EXPECT_EQ(a.strokes.stroke_count, 0u);
}

TEST(AssetStrokes, RoundTripKeepsEveryRecord) {
    const bake::BakedStrokes b = make_strokes();
    Asset a;
    const Status st = load(encoded(b), &a);
    ASSERT_TRUE(st.ok()) << st.message;
    ASSERT_EQ(a.strokes.stroke_count, 3u);
    ASSERT_EQ(a.strokes.point_count, 9u);
    EXPECT_EQ(a.strokes.max_points_per_stroke, 4u);
    EXPECT_EQ(std::memcmp(a.strokes.strokes, b.strokes.data(), 3 * sizeof(format::StrokeRecord)),
              0);
    EXPECT_EQ(std::memcmp(a.strokes.points, b.points.data(), 9 * sizeof(format::StrokePointRecord)),
              0);
    EXPECT_EQ(a.section_size[kSectionStrokes],
              8 + 3 * sizeof(format::StrokeRecord) + 9 * sizeof(format::StrokePointRecord));
    EXPECT_STREQ(section_name(kSectionStrokes), "STRK");
}

TEST(AssetStrokes, NoStrokesWritesTheSameBytesAndLoadsEmpty) {
    bake::RawScene s;
    bake::PointHierarchy p;
    make_scene(&s, &p);
    const std::vector<uint8_t> plain = bake::encode_asset(s, p);
    EXPECT_EQ(plain, bake::encode_asset(s, p, bake::BakedStrokes()));
    Asset a;
    const Status st = load(plain, &a);
    ASSERT_TRUE(st.ok()) << st.message;
    EXPECT_EQ(a.strokes.stroke_count, 0u);
    EXPECT_EQ(a.strokes.strokes, nullptr);
    EXPECT_EQ(a.section_size[kSectionStrokes], 0u);
    // The strokes only add a section: the others are unchanged.
    const std::vector<uint8_t> stroked = encoded(make_strokes());
    EXPECT_GT(stroked.size(), plain.size());
}

TEST(AssetStrokes, StaticAssetWithSurfaceAndObjectStrokesLoads) {
    bake::BakedStrokes b = make_strokes();
    b.strokes.pop_back();  // the joint stroke
    b.points.resize(5);
    Asset a;
    const Status st = load(encoded(b, false), &a);
    ASSERT_TRUE(st.ok()) << st.message;
    EXPECT_EQ(a.strokes.stroke_count, 2u);
}

TEST(AssetStrokes, RefusesBadRuns) {
    expect_refused([](bake::BakedStrokes* b) { b->strokes[1].point_count = 1; },
                   LoadError::bad_value, "control points (< 2)");
    expect_refused(
        [](bake::BakedStrokes* b) { b->strokes[1].point_count = limits::kMaxPointsPerStroke + 1; },
        LoadError::count_over_limit, "point count 257");
    expect_refused([](bake::BakedStrokes* b) { b->strokes[2].point_count = 5; },
                   LoadError::out_of_range, "stroke 2 points");
    expect_refused([](bake::BakedStrokes* b) { b->strokes[1].first_point = 2; },
                   LoadError::out_of_range, "overlap");
    expect_refused([](bake::BakedStrokes* b) { b->strokes[2].first_point = 0xFFFFFFFFu; },
                   LoadError::out_of_range, "stroke 2 points");
    expect_refused(
        [](bake::BakedStrokes* b) {
            std::swap(b->strokes[0], b->strokes[1]);  // runs out of order
        },
        LoadError::out_of_range, "overlap");
}

TEST(AssetStrokes, RefusesBadAnchors) {
    expect_refused([](bake::BakedStrokes* b) { b->strokes[0].anchor = 3; }, LoadError::bad_value,
                   "anchor kind 3 unknown");
    expect_refused([](bake::BakedStrokes* b) { b->strokes[0].host = 2; }, LoadError::out_of_range,
                   "host triangle 2 >= triangle count 2");
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (auto uv : {std::pair<float, float>{nan, 0.0f},
                    {0.0f, -0.01f},
                    {0.6f, 0.6f},
                    {std::numeric_limits<float>::infinity(), 0.0f}})
        expect_refused(
            [uv](bake::BakedStrokes* b) {
                b->strokes[0].bary_u = uv.first;
                b->strokes[0].bary_v = uv.second;
            },
            LoadError::bad_value, "outside the triangle");
    expect_refused([](bake::BakedStrokes* b) { b->strokes[2].host = 2; }, LoadError::out_of_range,
                   "joint 2 >= joint count 2");
    expect_refused([](bake::BakedStrokes* b) { (void)b; }, LoadError::missing_section,
                   "joint-anchored but the asset has no SKIN", /*skinned=*/false);
    expect_refused([](bake::BakedStrokes* b) { b->strokes[1].host = 1; }, LoadError::bad_value,
                   "object anchor with host 1");
    expect_refused([](bake::BakedStrokes* b) { b->strokes[2].bary_u = 0.5f; }, LoadError::bad_value,
                   "non-surface anchor");
    expect_refused([](bake::BakedStrokes* b) { b->strokes[0].root_point = 3; },
                   LoadError::out_of_range, "root point 3 >= point count 3");
}

TEST(AssetStrokes, AcceptsBarycentricsWithinTheTolerance) {
    bake::BakedStrokes b = make_strokes();
    b.strokes[0].bary_u = -0.5f * limits::kStrokeBaryTolerance;
    b.strokes[0].bary_v = 1.0f;
    Asset a;
    EXPECT_TRUE(load(encoded(b), &a).ok());
}

TEST(AssetStrokes, RefusesReservedBytes) {
    expect_refused([](bake::BakedStrokes* b) { b->strokes[0].reserved[1] = 1; },
                   LoadError::bad_value, "stroke 0 reserved");
    expect_refused([](bake::BakedStrokes* b) { b->strokes[1].reserved2 = 7; }, LoadError::bad_value,
                   "stroke 1 reserved");
    expect_refused([](bake::BakedStrokes* b) { b->points[3].reserved = 1; }, LoadError::bad_value,
                   "point 3 reserved");
    expect_refused([](bake::BakedStrokes* b) { b->points[8].reserved2 = 1; }, LoadError::bad_value,
                   "point 8 reserved");
}

TEST(AssetStrokes, RefusesBadControlPoints) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    for (float x : {nan, inf, -inf, 2 * limits::kMaxStrokeCoordinate})
        expect_refused([x](bake::BakedStrokes* b) { b->points[4].position[1] = x; },
                       LoadError::bad_value, "point 4 position");
    for (float r : {0.0f, -1.0f, nan, inf, 2 * limits::kMaxStrokeCoordinate})
        expect_refused([r](bake::BakedStrokes* b) { b->points[6].radius = r; },
                       LoadError::bad_radius, "point 6 radius");
    expect_refused(
        [](bake::BakedStrokes* b) {
            b->points[2].global_normal[0] = 40;
            b->points[2].global_normal[2] = 0;
        },
        LoadError::bad_normal, "point 2 global normal");
    expect_refused([](bake::BakedStrokes* b) { b->points[2].global_normal[0] = 127; },
                   LoadError::bad_normal, "point 2 global normal");
}

TEST(AssetStrokes, AcceptsQuantizedUnitGlobalNormals) {
    bake::BakedStrokes b = make_strokes();
    const int8_t normals[][3] = {{73, 73, 73}, {-128, 0, 0}, {0, -127, 0}, {90, -90, 0}};
    for (size_t i = 0; i < 4; ++i) std::memcpy(b.points[i].global_normal, normals[i], 3);
    Asset a;
    const Status st = load(encoded(b), &a);
    EXPECT_TRUE(st.ok()) << st.message;
}

// Every checksum recomputed, so an edit reaches the semantic checks.
void fix_checksums(std::vector<uint8_t>* bytes) {
    format::FileHeader h;
    std::memcpy(&h, bytes->data(), sizeof(h));
    auto* table = reinterpret_cast<format::SectionEntry*>(bytes->data() + sizeof(h));
    for (uint32_t i = 0; i < h.section_count; ++i)
        table[i].crc = format::crc32(bytes->data() + table[i].offset, table[i].size);
    h.table_crc = format::crc32(table, h.section_count * sizeof(format::SectionEntry));
    std::memcpy(bytes->data(), &h, sizeof(h));
}

format::SectionEntry* strokes_entry(std::vector<uint8_t>* bytes) {
    format::FileHeader h;
    std::memcpy(&h, bytes->data(), sizeof(h));
    auto* table = reinterpret_cast<format::SectionEntry*>(bytes->data() + sizeof(h));
    for (uint32_t i = 0; i < h.section_count; ++i)
        if (table[i].tag == format::kTagStrokes) return &table[i];
    return nullptr;
}

// The STRK section of `bytes` with its header counts replaced, checksums recomputed.
std::vector<uint8_t> with_counts(std::vector<uint8_t> bytes, uint32_t strokes, uint32_t points) {
    const format::SectionEntry* e = strokes_entry(&bytes);
    std::memcpy(bytes.data() + e->offset, &strokes, 4);
    std::memcpy(bytes.data() + e->offset + 4, &points, 4);
    fix_checksums(&bytes);
    return bytes;
}

TEST(AssetStrokes, RefusesHeaderCountsThatDisagreeWithTheSize) {
    const std::vector<uint8_t> bytes = encoded(make_strokes());
    struct Case {
        uint32_t strokes, points;
        LoadError error;
    };
    const Case cases[] = {
        {4, 9, LoadError::malformed_section},
        {3, 8, LoadError::malformed_section},
        {0xFFFFFFFFu, 9, LoadError::count_over_limit},
        {3, limits::kMaxStrokePoints + 1, LoadError::count_over_limit},
        {limits::kMaxStrokes, limits::kMaxStrokePoints, LoadError::malformed_section}};
    for (const Case& c : cases) {
        Asset a;
        const Status st = load(with_counts(bytes, c.strokes, c.points), &a);
        EXPECT_EQ(st.error, c.error) << c.strokes << " " << c.points << ": " << st.message;
        EXPECT_EQ(std::string(st.message).rfind("STRK: ", 0), 0u) << st.message;
    }
}

TEST(AssetStrokes, RefusesAnEmptySection) {
    std::vector<uint8_t> bytes = encoded(make_strokes());
    strokes_entry(&bytes)->size = 8;  // counts 0, 0 and the records cut away
    bytes = with_counts(bytes, 0, 0);
    Asset a;
    const Status st = load(bytes, &a);
    EXPECT_EQ(st.error, LoadError::zero_count) << st.message;
}

TEST(AssetStrokes, TruncatedOrCorruptedStrokesNeverCrash) {
    const std::vector<uint8_t> bytes = encoded(make_strokes());
    for (size_t n = 1; n < bytes.size(); n += 7) {
        Asset a;
        EXPECT_FALSE(load(std::vector<uint8_t>(bytes.begin(), bytes.begin() + long(n)), &a).ok());
    }
    // Random bytes of the STRK section (counts included), checksums fixed so the edits reach
    // the checks.
    std::vector<uint8_t> copy = bytes;
    const format::SectionEntry strk = *strokes_entry(&copy);
    bake::Rng rng{42};
    int loaded = 0;
    for (int trial = 0; trial < 3000; ++trial) {
        std::vector<uint8_t> edited = bytes;
        for (int k = 0, n = 1 + int(rng.below(4)); k < n; ++k)
            edited[size_t(strk.offset) + rng.below(strk.size)] = uint8_t(rng.next());
        fix_checksums(&edited);
        Asset a;
        const Status st = load(edited, &a);
        if (st.ok()) {
            ++loaded;
            EXPECT_LE(a.strokes.max_points_per_stroke, limits::kMaxPointsPerStroke);
        } else {
            EXPECT_EQ(std::string(st.message).find('\n'), std::string::npos);
        }
    }
    EXPECT_LT(loaded, 3000);
}

TEST(AssetStrokes, VersionTwoAssetsIgnoreTheSection) {
    std::vector<uint8_t> bytes = encoded(make_strokes());
    const uint16_t v2 = 2;
    std::memcpy(bytes.data() + 4, &v2, 2);
    Asset a;
    const Status st = load(bytes, &a);
    ASSERT_TRUE(st.ok()) << st.message;
    EXPECT_EQ(a.strokes.stroke_count, 0u);
}

}  // namespace
