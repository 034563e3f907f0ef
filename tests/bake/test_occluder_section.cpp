// The depth pass's simplified occluder (bake/occluder.h) and the OCCL section
// (runtime/asset_occluder.cpp): on assets/torus.obj the decimated occluder keeps about the
// asked share of the triangles, indexes only mesh vertices, and its measured deviation is
// positive (the torus's inner side is concave, where chords cut in front of the surface) and
// small; the section round-trips into the Asset; bad counts, indices and deviations are
// refused with named errors.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "bake/asset_writer.h"
#include "bake/occluder.h"
#include "runtime/asset.h"
#include "runtime/asset_format.h"
#include "runtime/crc32.h"
#include "tests/common/bake_fixtures.h"

namespace {

using namespace stipple;

TEST(OccluderBake, DecimatesTheTorusWithASmallMeasuredDeviation) {
    const bake::RawScene& s = test::prepared_torus(4000).scene;
    const bake::BakedOccluder o = bake::bake_occluder(s, 0.1);
    const size_t triangles = o.indices.size() / 3;
    EXPECT_GT(triangles, s.triangle_count() / 20);
    EXPECT_LE(triangles, s.triangle_count() / 8);
    for (uint32_t i : o.indices) ASSERT_LT(i, s.vertex_count());
    // The torus (radii 1 and 0.4): the occluder lies in front of the surface somewhere, by a
    // small fraction of the tube's radius.
    EXPECT_GT(o.deviation, 0.0f);
    EXPECT_LT(o.deviation, 0.1f);
    // The full mesh as its own occluder deviates by nothing (up to rounding).
    EXPECT_LT(bake::occluder_deviation(s, s.indices), 1e-5f);
    // A coarser occluder deviates more.
    EXPECT_GT(bake::bake_occluder(s, 0.02).deviation, o.deviation);
}

std::vector<uint8_t> encoded(const bake::BakedOccluder& occluder) {
    bake::RawScene s;
    bake::PointHierarchy p;
    test::tiny_square(&s, &p);
    return bake::encode_asset(s, p, bake::BakedStrokes(), bake::BakedLooks(), {},
                              bake::BakedCurvature(), occluder);
}

// Rewrites the OCCL section's word `word` (0: count, 1: deviation, 2...: indices) and drops
// `shorter` bytes from its end, fixing the checksums, so only the loader's checks can refuse.
void corrupt(std::vector<uint8_t>* bytes, size_t word, uint32_t value, uint64_t shorter) {
    format::FileHeader h;
    std::memcpy(&h, bytes->data(), sizeof(h));
    auto* table = reinterpret_cast<format::SectionEntry*>(bytes->data() + sizeof(h));
    for (uint32_t i = 0; i < h.section_count; ++i)
        if (table[i].tag == format::kTagOccluder) {
            std::memcpy(bytes->data() + table[i].offset + word * 4, &value, 4);
            table[i].size -= shorter;
            table[i].crc = format::crc32(bytes->data() + table[i].offset, table[i].size);
        }
    h.table_crc = format::crc32(table, h.section_count * sizeof(format::SectionEntry));
    std::memcpy(bytes->data(), &h, sizeof(h));
}

LoadError load_error(const std::vector<uint8_t>& bytes) {
    Asset a;
    return load_asset_memory(bytes.data(), bytes.size(), &a).error;
}

TEST(AssetOccluder, TheSectionLoadsAndBadOnesAreRefused) {
    bake::BakedOccluder one;
    one.indices = {0, 1, 2};
    one.deviation = 0.25f;
    const std::vector<uint8_t> bytes = encoded(one);
    Asset a;
    ASSERT_TRUE(load_asset_memory(bytes.data(), bytes.size(), &a).ok());
    ASSERT_NE(a.occluder_indices, nullptr);
    EXPECT_EQ(a.occluder_triangle_count, 1u);
    EXPECT_FLOAT_EQ(a.occluder_deviation, 0.25f);
    EXPECT_EQ(a.occluder_indices[2], 2u);
    EXPECT_EQ(a.section_size[kSectionOccluder], 20u);
    EXPECT_STREQ(section_name(kSectionOccluder), "OCCL");

    const std::vector<uint8_t> none = encoded(bake::BakedOccluder());
    Asset b;
    ASSERT_TRUE(load_asset_memory(none.data(), none.size(), &b).ok());
    EXPECT_EQ(b.occluder_indices, nullptr);
    EXPECT_EQ(b.section_size[kSectionOccluder], 0u);
    EXPECT_GT(bytes.size(), none.size());  // an opt-in section

    std::vector<uint8_t> bad = bytes;
    corrupt(&bad, 4, 4, 0);  // index 4 of a 4-vertex mesh
    EXPECT_EQ(load_error(bad), LoadError::out_of_range);
    bad = bytes;
    corrupt(&bad, 0, 0, 0);
    EXPECT_EQ(load_error(bad), LoadError::zero_count);
    bad = bytes;
    corrupt(&bad, 0, 3, 0);  // more triangles than the mesh's 2
    EXPECT_EQ(load_error(bad), LoadError::count_over_limit);
    bad = bytes;
    corrupt(&bad, 0, 2, 0);  // two triangles in the bytes of one
    EXPECT_EQ(load_error(bad), LoadError::malformed_section);
    bad = bytes;
    corrupt(&bad, 0, 1, 16);  // the header cut
    EXPECT_EQ(load_error(bad), LoadError::malformed_section);
    const float nan = std::nanf(""), negative = -1.0f;
    uint32_t word = 0;
    for (float d : {nan, negative}) {
        bad = bytes;
        std::memcpy(&word, &d, 4);
        corrupt(&bad, 1, word, 0);
        EXPECT_EQ(load_error(bad), LoadError::bad_value);
    }
}

}  // namespace
