// The .stip format: encode/decode round trip, and a loader that names what is wrong with a
// truncated, corrupted or lying asset instead of crashing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <string>

#include "bake/asset_writer.h"
#include "runtime/asset.h"
#include "runtime/asset_format.h"

namespace {

using namespace stipple;

// A skinned quad with one clip and a three-point hierarchy.
void make_scene(bake::RawScene* s, bake::PointHierarchy* p) {
    *s = bake::RawScene();
    *p = bake::PointHierarchy();
    s->positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    s->normals = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    s->indices = {0, 1, 2, 0, 2, 3};
    s->joints = {0, 0, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0};
    s->weights = {1, 0, 0, 0, 0.5f, 0.5f, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
    s->nodes.resize(2);
    s->nodes[1].parent = 0;
    s->nodes[1].translation[1] = 0.5f;
    s->joint_nodes = {0, 1};
    s->inverse_bind.assign(32, 0.0f);
    for (int j = 0; j < 2; ++j)
        for (int k = 0; k < 4; ++k) s->inverse_bind[size_t(j) * 16 + size_t(k) * 5] = 1.0f;
    s->inverse_bind[16 + 13] = -0.5f;
    bake::RawClip clip;
    clip.name = "wave";
    clip.duration = 1.0f;
    bake::RawChannel ch;
    ch.node = 1;
    ch.path = bake::RawPath::rotation;
    ch.times = {0.0f, 1.0f};
    ch.values = {0, 0, 0, 1, 0, 0, 0.7071068f, 0.7071068f};
    clip.channels.push_back(ch);
    s->clips.push_back(clip);

    p->host_triangle = {0, 1, 1};
    p->bary_u = {0.25f, 0.5f, 0.0f};
    p->bary_v = {0.25f, 0.5f, 1.0f};
    p->radius = {0.8f, 0.5f, 0.3f};
    p->neighbour_offsets = {0, 2, 3, 5};
    p->neighbours = {1, 2, 0, 0, 1};
}

std::vector<uint8_t> encoded() {
    bake::RawScene s;
    bake::PointHierarchy p;
    make_scene(&s, &p);
    return bake::encode_asset(s, p);
}

// Recomputes every checksum, so a test can change a value and reach the semantic checks.
void fix_checksums(std::vector<uint8_t>* bytes) {
    format::FileHeader h;
    std::memcpy(&h, bytes->data(), sizeof(h));
    auto* table = reinterpret_cast<format::SectionEntry*>(bytes->data() + sizeof(h));
    for (uint32_t i = 0; i < h.section_count; ++i)
        table[i].crc = format::crc32(bytes->data() + table[i].offset, table[i].size);
    h.table_crc = format::crc32(table, h.section_count * sizeof(format::SectionEntry));
    std::memcpy(bytes->data(), &h, sizeof(h));
}

size_t section_offset(const std::vector<uint8_t>& bytes, uint32_t tag) {
    format::FileHeader h;
    std::memcpy(&h, bytes.data(), sizeof(h));
    const auto* table = reinterpret_cast<const format::SectionEntry*>(bytes.data() + sizeof(h));
    for (uint32_t i = 0; i < h.section_count; ++i)
        if (table[i].tag == tag) return size_t(table[i].offset);
    return 0;
}

TEST(AssetFormat, RoundTripKeepsEveryField) {
    bake::RawScene s;
    bake::PointHierarchy p;
    make_scene(&s, &p);
    std::vector<uint8_t> bytes = bake::encode_asset(s, p);
    Asset a;
    Status st = load_asset_memory(bytes.data(), bytes.size(), &a);
    ASSERT_TRUE(st.ok()) << st.message;
    EXPECT_EQ(a.file_size, bytes.size());
    ASSERT_EQ(a.mesh.vertex_count, 4u);
    ASSERT_EQ(a.mesh.triangle_count, 2u);
    EXPECT_EQ(0, std::memcmp(a.mesh.positions, s.positions.data(), 48));
    EXPECT_EQ(0, std::memcmp(a.mesh.indices, s.indices.data(), 24));
    ASSERT_TRUE(a.skinned);
    EXPECT_EQ(a.skin.skeleton.node_count, 2u);
    EXPECT_EQ(a.skin.skeleton.parents[1], 0);
    EXPECT_FLOAT_EQ(a.skin.skeleton.rest[1].translation[1], 0.5f);
    EXPECT_FLOAT_EQ(a.skin.skeleton.inverse_bind[16 + 13], -0.5f);
    EXPECT_EQ(a.skin.joints[5], 1);
    EXPECT_FLOAT_EQ(a.skin.weights[5], 0.5f);
    ASSERT_EQ(a.clip_count, 1u);
    EXPECT_STREQ(a.clips[0].name, "wave");
    ASSERT_EQ(a.clips[0].channel_count, 1u);
    EXPECT_EQ(a.clips[0].channels[0].key_count, 2u);
    EXPECT_FLOAT_EQ(a.clips[0].channels[0].times[1], 1.0f);  // key times are exact
    // Values are 16-bit codes over each column's range: error <= range / 131070.
    EXPECT_NEAR(a.clips[0].channels[0].values[7], 0.7071068f, 0.3f / 131070);
    EXPECT_NEAR(a.clips[0].channels[0].values[3], 1.0f, 0.3f / 131070);
    EXPECT_EQ(find_clip(a, "wave"), 0);
    EXPECT_EQ(find_clip(a, "0"), 0);
    EXPECT_EQ(find_clip(a, "1"), -1);
    ASSERT_EQ(a.points.point_count, 3u);
    EXPECT_EQ(a.points.host_triangle[2], 1u);
    EXPECT_FLOAT_EQ(a.points.bary_v[2], 1.0f);
    EXPECT_NEAR(a.points.radius[0], 0.8f, 0.8f * 0.0014f);
    EXPECT_EQ(a.points.neighbour_offsets[3], 5u);
    EXPECT_EQ(a.edges.edge_count, 5u);  // a quad: 4 boundary edges and its diagonal
    // Re-encoding is byte-identical (deterministic writer).
    EXPECT_EQ(bytes, bake::encode_asset(s, p));
}

// The point hierarchy is coded: the quantisation stays within the bounds that
// runtime/point_codec.h and docs/format.md state, and neighbour lists survive exactly.
TEST(AssetFormat, CompactPointsRoundTripWithinStatedError) {
    bake::RawScene s;
    bake::PointHierarchy p;
    make_scene(&s, &p);
    // A larger hierarchy with random values, so every code path is exercised.
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const uint32_t n = 5000;
    p = bake::PointHierarchy();
    p.neighbour_offsets.push_back(0);
    for (uint32_t i = 0; i < n; ++i) {
        float u = unit(rng), v = unit(rng) * (1.0f - u);
        p.host_triangle.push_back(rng() % 2);
        p.bary_u.push_back(u);
        p.bary_v.push_back(v);
        p.radius.push_back(i == 17 ? 0.0f : 2.0f / std::sqrt(float(i + 1)));
        uint32_t count = i == 0 ? 0 : 1 + rng() % 6;
        for (uint32_t k = 0; k < count; ++k) {
            uint32_t j = i - 1 - rng() % std::min(i, 40u);
            if (rng() % 8 == 0) j = rng() % n;  // a few forward references
            if (j == i) j = (i + 1) % n;
            p.neighbours.push_back(j);
        }
        p.neighbour_offsets.push_back(uint32_t(p.neighbours.size()));
    }
    std::vector<uint8_t> bytes = bake::encode_asset(s, p);
    Asset a;
    Status st = load_asset_memory(bytes.data(), bytes.size(), &a);
    ASSERT_TRUE(st.ok()) << st.message;
    EXPECT_EQ(a.version, 3);
    ASSERT_EQ(a.points.point_count, n);
    const float bary_error = 0.5f / 4095.0f + 1e-6f;
    for (uint32_t i = 0; i < n; ++i) {
        ASSERT_EQ(a.points.host_triangle[i], p.host_triangle[i]);
        ASSERT_NEAR(a.points.bary_u[i], p.bary_u[i], bary_error);
        ASSERT_LE(a.points.bary_u[i] + a.points.bary_v[i], 1.0f + 1e-6f);
        ASSERT_NEAR(a.points.bary_v[i], p.bary_v[i], 2 * bary_error);
        ASSERT_NEAR(a.points.radius[i], p.radius[i], 0.0014f * p.radius[i] + 1e-9f);
        std::vector<uint32_t> want(p.neighbours.begin() + p.neighbour_offsets[i],
                                   p.neighbours.begin() + p.neighbour_offsets[i + 1]);
        std::sort(want.begin(), want.end());
        want.erase(std::unique(want.begin(), want.end()), want.end());
        std::vector<uint32_t> got(a.points.neighbours + a.points.neighbour_offsets[i],
                                  a.points.neighbours + a.points.neighbour_offsets[i + 1]);
        std::sort(got.begin(), got.end());
        ASSERT_EQ(got, want) << i;
    }
    size_t point_bytes = a.section_size[kSectionPoints];
    std::printf("point stream: %.2f bytes per point\n", double(point_bytes) / n);
}

TEST(AssetFormat, MorphTargetsRoundTrip) {
    bake::RawScene s;
    bake::PointHierarchy p;
    make_scene(&s, &p);
    s.morph_weights = {0.25f, 0.0f};
    s.morph_weight_nodes = {1, 1};
    bake::RawMorphTarget t;
    t.weight = 1;
    t.vertex_begin = 2;
    t.vertex_count = 2;
    t.position_deltas = {0, 0, 1, 0, 0, 2};
    s.morph_targets.push_back(t);
    bake::RawChannel w;
    w.node = 1;
    w.path = bake::RawPath::weights;
    w.interp = bake::RawInterp::cubic_spline;
    w.weight_begin = 0;
    w.weight_count = 2;
    w.times = {0.0f, 0.5f};
    w.values.assign(2 * 3 * 2, 0.0f);  // (in, value, out) x 2 slots x 2 keys
    w.values[2 * 1 + 1] = 0.75f;       // key 0 value of slot 1
    s.clips[0].channels.push_back(w);
    std::vector<uint8_t> bytes = bake::encode_asset(s, p);
    Asset a;
    Status st = load_asset_memory(bytes.data(), bytes.size(), &a);
    ASSERT_TRUE(st.ok()) << st.message;
    ASSERT_TRUE(a.has_morph());
    EXPECT_EQ(a.morph.weight_count, 2u);
    EXPECT_FLOAT_EQ(a.morph.default_weights[0], 0.25f);
    EXPECT_EQ(a.morph.targets[0].vertex_begin, 2u);
    EXPECT_FLOAT_EQ(a.morph.targets[0].position_deltas[5], 2.0f);
    EXPECT_EQ(a.morph.targets[0].normal_deltas, nullptr);
    const anim::Channel& c = a.clips[0].channels[1];
    EXPECT_EQ(c.path, anim::Path::weights);
    EXPECT_EQ(c.interp, anim::Interp::cubic_spline);
    EXPECT_NEAR(c.values[3], 0.75f, 1e-5);
}

TEST(AssetFormat, TruncatedAssetIsRejectedAtEveryLength) {
    std::vector<uint8_t> bytes = encoded();
    for (size_t len = 0; len < bytes.size(); ++len) {
        Asset a;
        Status st = load_asset_memory(bytes.data(), len, &a);
        ASSERT_FALSE(st.ok()) << len;
        ASSERT_NE(st.message[0], '\0');
        EXPECT_EQ(a.points.point_count, 0u);
    }
    Asset a;
    Status st = load_asset_memory(bytes.data(), bytes.size() - 7, &a);
    EXPECT_EQ(st.error, LoadError::truncated);
    EXPECT_NE(std::strstr(st.message, "header says"), nullptr) << st.message;
}

TEST(AssetFormat, CorruptedSectionIsNamed) {
    std::vector<uint8_t> bytes = encoded();
    bytes[section_offset(bytes, format::kTagPointStream) + 17] ^= 0x40;
    Asset a;
    Status st = load_asset_memory(bytes.data(), bytes.size(), &a);
    EXPECT_EQ(st.error, LoadError::checksum_mismatch);
    EXPECT_NE(std::strstr(st.message, "PNTQ"), nullptr) << st.message;
}

TEST(AssetFormat, BadMagicAndVersionAreNamed) {
    std::vector<uint8_t> bytes = encoded();
    Asset a;
    std::vector<uint8_t> other = bytes;
    other[0] = 'X';
    EXPECT_EQ(load_asset_memory(other.data(), other.size(), &a).error, LoadError::bad_magic);
    other = bytes;
    other[4] = 9;
    Status st = load_asset_memory(other.data(), other.size(), &a);
    EXPECT_EQ(st.error, LoadError::unsupported_version);
    EXPECT_NE(std::strstr(st.message, "version 9"), nullptr) << st.message;
}

TEST(AssetFormat, OutOfRangeIndicesAreRejectedEvenWithValidChecksums) {
    // The writer does not check; the loader must: point 1's host triangle 7 of 2, then a
    // neighbour 99 of 3 points, then a clip channel on node 5 of 2.
    bake::RawScene s;
    bake::PointHierarchy p;
    make_scene(&s, &p);
    p.host_triangle[1] = 7;
    std::vector<uint8_t> bytes = bake::encode_asset(s, p);
    Asset a;
    Status st = load_asset_memory(bytes.data(), bytes.size(), &a);
    EXPECT_EQ(st.error, LoadError::out_of_range);
    EXPECT_NE(std::strstr(st.message, "host triangle 7"), nullptr) << st.message;

    make_scene(&s, &p);
    p.neighbours[0] = 99;
    bytes = bake::encode_asset(s, p);
    st = load_asset_memory(bytes.data(), bytes.size(), &a);
    EXPECT_EQ(st.error, LoadError::out_of_range);
    EXPECT_NE(std::strstr(st.message, "neighbour 99"), nullptr) << st.message;

    make_scene(&s, &p);
    s.clips[0].channels[0].node = 5;
    bytes = bake::encode_asset(s, p);
    st = load_asset_memory(bytes.data(), bytes.size(), &a);
    EXPECT_EQ(st.error, LoadError::out_of_range);
    EXPECT_NE(std::strstr(st.message, "'wave' channel 0"), nullptr) << st.message;

    bytes = encoded();
    // MESH: u32 V, u32 T, positions: the first becomes NaN.
    float nan = std::numeric_limits<float>::quiet_NaN();
    std::memcpy(&bytes[section_offset(bytes, format::kTagMesh) + 8], &nan, 4);
    fix_checksums(&bytes);
    st = load_asset_memory(bytes.data(), bytes.size(), &a);
    EXPECT_EQ(st.error, LoadError::bad_value);
}

// Version 3: BNDS (up axis, rest and clip boxes) and SIDE (double-sided triangle runs).
TEST(AssetFormat, BoundsAndSidesRoundTrip) {
    bake::RawScene s;
    bake::PointHierarchy p;
    make_scene(&s, &p);
    s.up_axis = format::kUpZ;
    s.double_sided = {0, 1};
    std::vector<uint8_t> bytes = bake::encode_asset(s, p);
    Asset a;
    Status st = load_asset_memory(bytes.data(), bytes.size(), &a);
    ASSERT_TRUE(st.ok()) << st.message;
    EXPECT_EQ(a.version, format::kVersion);
    ASSERT_TRUE(a.bounds.present);
    EXPECT_EQ(a.bounds.up_axis, format::kUpZ);
    // Rest pose: the quad as stored (identity skin at rest).
    const float rest[6] = {0, 0, 0, 1, 1, 0};
    for (int k = 0; k < 6; ++k) EXPECT_NEAR(a.bounds.rest[k], rest[k], 1e-6) << k;
    // "wave" turns node 1 (vertices 1 and 2, half and fully) by 90 degrees about z around
    // (0, 0.5): vertex 2 (1, 1) ends at (-0.5, 1.5) and on the way passes straight above the
    // pivot, at y = 0.5 + |(1, 0.5)| = 1.618; the box holds every pose sampled (60 per second).
    ASSERT_NE(a.bounds.clips, nullptr);
    EXPECT_NEAR(a.bounds.clips[0], -0.5f, 1e-5);
    EXPECT_NEAR(a.bounds.clips[4], 0.5f + std::sqrt(1.25f), 1e-3);
    EXPECT_GE(a.bounds.clips[3], 1.0f);
    ASSERT_EQ(a.sides.run_count, 1u);
    EXPECT_EQ(a.sides.triangle_count, 1u);
    EXPECT_EQ(a.sides.triangle_double_sided[0], 0);
    EXPECT_EQ(a.sides.triangle_double_sided[1], 1);
    ASSERT_NE(a.edges.double_sided_boundary, nullptr);
    uint32_t rims = 0;
    for (uint32_t e = 0; e < a.edges.edge_count; ++e) rims += a.edges.double_sided_boundary[e];
    EXPECT_EQ(rims, 2u);                            // triangle 1's two boundary edges
    EXPECT_EQ(a.section_size[kSectionSides], 12u);  // one run: count + (first, count)
    // No double-sided triangle: no SIDE section.
    s.double_sided = {0, 0};
    bytes = bake::encode_asset(s, p);
    st = load_asset_memory(bytes.data(), bytes.size(), &a);
    ASSERT_TRUE(st.ok()) << st.message;
    EXPECT_EQ(a.section_size[kSectionSides], 0u);
    EXPECT_EQ(a.sides.triangle_double_sided, nullptr);
    EXPECT_EQ(a.edges.double_sided_boundary, nullptr);
}

TEST(AssetFormat, BadBoundsAndSidesAreRejected) {
    bake::RawScene s;
    bake::PointHierarchy p;
    make_scene(&s, &p);
    s.double_sided = {1, 1};
    const std::vector<uint8_t> good = bake::encode_asset(s, p);
    const size_t sides = section_offset(good, format::kTagSides);
    const size_t bounds = section_offset(good, format::kTagBounds);
    ASSERT_NE(sides, 0u);
    ASSERT_NE(bounds, 0u);
    Asset a;
    auto load = [&](std::vector<uint8_t> b) {
        fix_checksums(&b);
        return load_asset_memory(b.data(), b.size(), &a);
    };
    auto put = [](std::vector<uint8_t>* b, size_t at, uint32_t v) {
        std::memcpy(&(*b)[at], &v, 4);
    };
    std::vector<uint8_t> b = good;
    put(&b, sides + 8, 3);  // run (0, 3): beyond the 2 triangles
    Status st = load(b);
    EXPECT_EQ(st.error, LoadError::out_of_range);
    EXPECT_NE(std::strstr(st.message, "SIDE: run 0"), nullptr) << st.message;
    b = good;
    put(&b, sides + 8, 0);  // an empty run
    EXPECT_EQ(load(b).error, LoadError::out_of_range);
    b = good;
    put(&b, bounds, 7);  // up axis 7
    st = load(b);
    EXPECT_EQ(st.error, LoadError::bad_value);
    EXPECT_NE(std::strstr(st.message, "BNDS: up axis 7"), nullptr) << st.message;
    b = good;
    put(&b, bounds + 4, 2);  // two clip boxes for one clip
    EXPECT_EQ(load(b).error, LoadError::malformed_section);
    b = good;
    const float flipped = 5.0f;  // rest min x 5 > max x 1
    std::memcpy(&b[bounds + 8], &flipped, 4);
    st = load(b);
    EXPECT_EQ(st.error, LoadError::bad_value);
    EXPECT_NE(std::strstr(st.message, "BNDS: rest"), nullptr) << st.message;
}

// Version-2 assets (no BNDS, no SIDE) still load: the runtime frames the rest pose and
// draws every triangle single-sided. Sections with those tags in a version-2 file were
// unknown tags then and are ignored.
TEST(AssetFormat, VersionTwoStillLoads) {
    bake::RawScene s;
    bake::PointHierarchy p;
    make_scene(&s, &p);
    s.double_sided = {1, 1};
    std::vector<uint8_t> bytes = bake::encode_asset(s, p);
    const uint16_t two = 2;
    std::memcpy(&bytes[4], &two, 2);
    Asset a;
    Status st = load_asset_memory(bytes.data(), bytes.size(), &a);
    ASSERT_TRUE(st.ok()) << st.message;
    EXPECT_EQ(a.version, 2);
    EXPECT_FALSE(a.bounds.present);
    EXPECT_EQ(a.sides.triangle_double_sided, nullptr);
    EXPECT_EQ(a.section_size[kSectionBounds], 0u);
    EXPECT_EQ(a.points.point_count, 3u);
    const uint16_t one = 1;
    std::memcpy(&bytes[4], &one, 2);
    st = load_asset_memory(bytes.data(), bytes.size(), &a);
    EXPECT_EQ(st.error, LoadError::unsupported_version);
    EXPECT_NE(std::strstr(st.message, "version 1"), nullptr) << st.message;
}

// Random byte changes with repaired checksums reach every validation path: the loader must
// either accept the asset or reject it with a message, never crash (run under ASan to see
// any overrun).
TEST(AssetFormat, RandomCorruptionNeverCrashes) {
    {
        const std::vector<uint8_t> bytes = encoded();
        const size_t payload = section_offset(bytes, format::kTagMesh);
        std::mt19937 rng(1234);
        int rejected = 0;
        for (int trial = 0; trial < 3000; ++trial) {
            std::vector<uint8_t> b = bytes;
            int flips = 1 + int(rng() % 4);
            // Odd trials change section payloads and repair the checksums; even trials change
            // anything, header and section table included.
            size_t from = trial % 2 ? payload : 0;
            for (int k = 0; k < flips; ++k) b[from + rng() % (b.size() - from)] = uint8_t(rng());
            if (trial % 2) fix_checksums(&b);
            Asset a;
            Status st = load_asset_memory(b.data(), b.size(), &a);
            if (!st.ok()) {
                ++rejected;
                ASSERT_NE(st.message[0], '\0');
            }
        }
        EXPECT_GT(rejected, 1000);
    }
}

}  // namespace
