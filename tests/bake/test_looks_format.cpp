// The LOOK section (runtime/asset_looks.cpp): the writer's bytes round-trip through the
// loader into LooksView; an asset with nothing to say about looks has no LOOK and the same
// bytes as before; every rule refuses a hostile section with its LoadError and a one-line
// message naming LOOK, and no count can make the loader read past the section.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "bake/asset_writer.h"
#include "runtime/asset.h"
#include "runtime/asset_format.h"
#include "runtime/asset_limits.h"

namespace {

using namespace stipple;

// A quad (4 vertices, 2 triangles, shared edge 0-2) with a three-point hierarchy.
void make_scene(bake::RawScene* s, bake::PointHierarchy* p) {
    s->positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    s->normals = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    s->indices = {0, 1, 2, 0, 2, 3};
    p->host_triangle = {0, 1, 1};
    p->bary_u = {0.25f, 0.5f, 0.0f};
    p->bary_v = {0.25f, 0.5f, 1.0f};
    p->radius = {0.8f, 0.5f, 0.3f};
    p->neighbour_offsets = {0, 2, 3, 5};
    p->neighbours = {1, 2, 0, 0, 1};
}

// Colours for the three points, two parts (the first transparent), one crease.
bake::BakedLooks make_looks() {
    bake::BakedLooks l;
    l.point_colour = {10, 20, 30, 255, 40, 50, 60, 255, 70, 80, 90, 128};
    l.part_colour = {255, 255, 255, 77, 128, 64, 255, 255};
    l.part_flags = {format::kLookPartTransparent, 0};
    l.triangle_part = {0, 1};
    l.creases = {0, 2, 0, 1};
    return l;
}

std::vector<uint8_t> encoded(const bake::BakedLooks& looks) {
    bake::RawScene s;
    bake::PointHierarchy p;
    make_scene(&s, &p);
    return bake::encode_asset(s, p, bake::BakedStrokes(), looks);
}

// The file `bytes` with its LOOK section's bytes replaced by `look` (sections re-laid out
// and checksummed as encode_asset does).
std::vector<uint8_t> with_look(const std::vector<uint8_t>& bytes,
                               const std::vector<uint8_t>& look) {
    format::FileHeader h;
    std::memcpy(&h, bytes.data(), sizeof(h));
    std::vector<format::SectionEntry> table(h.section_count);
    std::memcpy(table.data(), bytes.data() + sizeof(h), table.size() * sizeof(table[0]));
    std::vector<std::vector<uint8_t>> sections;
    for (const format::SectionEntry& e : table)
        sections.push_back(e.tag == format::kTagLooks
                               ? look
                               : std::vector<uint8_t>(bytes.begin() + long(e.offset),
                                                      bytes.begin() + long(e.offset + e.size)));
    uint64_t offset = sizeof(h) + table.size() * sizeof(table[0]);
    for (size_t i = 0; i < table.size(); ++i) {
        offset = (offset + 15) / 16 * 16;
        table[i].offset = offset;
        table[i].size = sections[i].size();
        table[i].crc = format::crc32(sections[i].data(), sections[i].size());
        offset += sections[i].size();
    }
    h.file_size = offset;
    h.table_crc = format::crc32(table.data(), table.size() * sizeof(table[0]));
    std::vector<uint8_t> out(offset, 0);
    std::memcpy(out.data(), &h, sizeof(h));
    std::memcpy(out.data() + sizeof(h), table.data(), table.size() * sizeof(table[0]));
    for (size_t i = 0; i < table.size(); ++i)
        if (!sections[i].empty())  // (an empty vector's data() may be null)
            std::memcpy(out.data() + table[i].offset, sections[i].data(), sections[i].size());
    return out;
}

// The LOOK section of make_looks() edited by `edit`, as raw bytes.
std::vector<uint8_t> look_bytes(format::LooksHeader h, const bake::BakedLooks& l) {
    std::vector<uint8_t> b(sizeof(h));
    std::memcpy(b.data(), &h, sizeof(h));
    auto put = [&b](const void* data, size_t size) {
        const uint8_t* p = static_cast<const uint8_t*>(data);
        b.insert(b.end(), p, p + size);
    };
    put(l.creases.data(), l.creases.size() * 4);
    put(l.point_colour.data(), l.point_colour.size());
    put(l.part_colour.data(), l.part_colour.size());
    put(l.triangle_part.data(), l.triangle_part.size() * 2);
    put(l.part_flags.data(), l.part_flags.size());
    return b;
}

format::LooksHeader header_of(const bake::BakedLooks& l) {
    return {uint32_t(l.point_colour.size() / 4), uint32_t(l.part_flags.size()),
            uint32_t(l.triangle_part.size()), uint32_t(l.creases.size() / 4), 0};
}

Status load(const std::vector<uint8_t>& bytes, Asset* a) {
    return load_asset_memory(bytes.data(), bytes.size(), a);
}

// Loads the quad with LOOK section `look`; expects `error` and a one-line message naming LOOK.
void expect_refused(const std::vector<uint8_t>& look, LoadError error, const char* words) {
    Asset a;
    const Status st = load(with_look(encoded(make_looks()), look), &a);
    ASSERT_FALSE(st.ok());
    EXPECT_EQ(st.error, error) << st.message;
    EXPECT_EQ(std::string(st.message).rfind("LOOK: ", 0), 0u) << st.message;
    EXPECT_NE(std::string(st.message).find(words), std::string::npos) << st.message;
    EXPECT_EQ(std::string(st.message).find('\n'), std::string::npos);
    EXPECT_EQ(a.looks.part_count, 0u);
}

TEST(AssetLooks, RoundTripFillsTheView) {
    const bake::BakedLooks l = make_looks();
    Asset a;
    const Status st = load(encoded(l), &a);
    ASSERT_TRUE(st.ok()) << st.message;
    const LooksView& v = a.looks;
    ASSERT_EQ(v.part_count, 2u);
    ASSERT_EQ(v.crease_count, 1u);
    ASSERT_NE(v.point_colour, nullptr);
    EXPECT_EQ(std::memcmp(v.point_colour, l.point_colour.data(), 12), 0);
    EXPECT_EQ(std::memcmp(v.part_colour, l.part_colour.data(), 8), 0);
    EXPECT_EQ(v.part_flags[0], kPartTransparent);
    EXPECT_EQ(v.part_flags[1], 0);
    EXPECT_EQ(v.triangle_part[0], 0);
    EXPECT_EQ(v.triangle_part[1], 1);
    EXPECT_EQ(std::memcmp(v.creases, l.creases.data(), 16), 0);
    EXPECT_EQ(a.section_size[kSectionLooks], 20u + 16 + 12 + 8 + 4 + 2);
    EXPECT_STREQ(section_name(kSectionLooks), "LOOK");
}

TEST(AssetLooks, NothingToSayWritesTheSameBytesAndLoadsEmpty) {
    bake::RawScene s;
    bake::PointHierarchy p;
    make_scene(&s, &p);
    const std::vector<uint8_t> plain = bake::encode_asset(s, p);
    EXPECT_EQ(plain, bake::encode_asset(s, p, bake::BakedStrokes(), bake::BakedLooks()));
    Asset a;
    ASSERT_TRUE(load(plain, &a).ok());
    EXPECT_EQ(a.section_size[kSectionLooks], 0u);
    EXPECT_EQ(a.looks.point_colour, nullptr);
    EXPECT_EQ(a.looks.triangle_part, nullptr);
    EXPECT_EQ(a.looks.creases, nullptr);
    EXPECT_EQ(a.looks.part_count + a.looks.crease_count, 0u);
}

TEST(AssetLooks, EachArrayMayBeAbsent) {
    bake::BakedLooks creases_only;
    creases_only.creases = {0, 2, 0, 1};
    bake::BakedLooks parts_only = make_looks();
    parts_only.creases.clear();
    parts_only.point_colour.clear();
    for (const bake::BakedLooks& l : {creases_only, parts_only}) {
        Asset a;
        const Status st = load(encoded(l), &a);
        ASSERT_TRUE(st.ok()) << st.message;
        EXPECT_EQ(a.looks.point_colour, nullptr);
        EXPECT_EQ(a.looks.crease_count, l.creases.size() / 4);
        EXPECT_EQ(a.looks.part_count, l.part_flags.size());
        EXPECT_EQ(a.looks.triangle_part == nullptr, l.part_flags.empty());
    }
}

TEST(AssetLooks, RefusesCountsPastTheBytes) {
    const bake::BakedLooks l = make_looks();
    for (uint32_t format::LooksHeader::*count :
         {&format::LooksHeader::point_colour_count, &format::LooksHeader::triangle_part_count,
          &format::LooksHeader::crease_count}) {
        for (uint32_t value : {4u, 1000u, 0xFFFFFFFFu}) {
            format::LooksHeader h = header_of(l);
            h.*count = value;
            expect_refused(look_bytes(h, l), LoadError::malformed_section, "does not match");
        }
    }
    format::LooksHeader h = header_of(l);
    h.part_count = limits::kMaxParts + 1;
    expect_refused(look_bytes(h, l), LoadError::count_over_limit, "part count 65537");
    expect_refused(std::vector<uint8_t>(12, 0), LoadError::malformed_section, "shorter");
    std::vector<uint8_t> longer = look_bytes(header_of(l), l);
    longer.push_back(0);
    expect_refused(longer, LoadError::malformed_section, "does not match");
}

TEST(AssetLooks, RefusesCountsThatDisagreeWithTheAsset) {
    bake::BakedLooks l = make_looks();
    l.point_colour.resize(8);  // 2 colours for 3 points
    expect_refused(look_bytes(header_of(l), l), LoadError::malformed_section, "2 point colours");
    l = make_looks();
    l.triangle_part.resize(1);  // 1 part id for 2 triangles
    expect_refused(look_bytes(header_of(l), l), LoadError::malformed_section, "1 triangle parts");
    l = make_looks();
    l.part_flags.clear();  // part ids without parts
    l.part_colour.clear();
    expect_refused(look_bytes(header_of(l), l), LoadError::malformed_section, "0 parts");
    expect_refused(look_bytes(header_of(bake::BakedLooks()), bake::BakedLooks()),
                   LoadError::zero_count, "no colours, parts or creases");
}

TEST(AssetLooks, RefusesBadPartIdsFlagsAndReservedBytes) {
    bake::BakedLooks l = make_looks();
    l.triangle_part[1] = 2;
    expect_refused(look_bytes(header_of(l), l), LoadError::out_of_range,
                   "triangle 1 part 2 >= part count 2");
    l = make_looks();
    l.part_flags[1] = 0x80;
    expect_refused(look_bytes(header_of(l), l), LoadError::bad_value, "part 1 flags 0x80");
    l = make_looks();
    format::LooksHeader h = header_of(l);
    h.reserved = 1;
    expect_refused(look_bytes(h, l), LoadError::bad_value, "reserved");
}

TEST(AssetLooks, RefusesCreasesOutsideTheMesh) {
    const std::vector<std::vector<uint32_t>> bad = {{4, 2, 0, 1},
                                                    {0, 0xFFFFFFFFu, 0, 1},
                                                    {0, 2, 2, 1},
                                                    {0, 2, 0, format::kNoFace},
                                                    {0, 2, 1, 1}};
    for (const std::vector<uint32_t>& crease : bad) {
        bake::BakedLooks l = make_looks();
        l.creases = crease;
        expect_refused(look_bytes(header_of(l), l), LoadError::out_of_range, "crease 0");
    }
}

TEST(AssetLooks, TruncatedOrCorruptedSectionsNeverCrash) {
    // Every prefix of the section, and every byte flipped, loads or fails with a Status.
    const std::vector<uint8_t> full = look_bytes(header_of(make_looks()), make_looks());
    const std::vector<uint8_t> base = encoded(make_looks());
    for (size_t n = 0; n < full.size(); ++n) {
        Asset a;
        EXPECT_FALSE(
            load(with_look(base, std::vector<uint8_t>(full.begin(), full.begin() + long(n))), &a)
                .ok());
    }
    for (size_t i = 0; i < full.size(); ++i) {
        std::vector<uint8_t> flipped = full;
        flipped[i] ^= 0xFF;
        Asset a;
        const Status st = load(with_look(base, flipped), &a);
        if (!st.ok()) {
            EXPECT_EQ(a.looks.part_count, 0u);
        }
    }
}

}  // namespace
