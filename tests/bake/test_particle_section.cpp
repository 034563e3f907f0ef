// The PTRE section (runtime/asset_particles.cpp): the particle tree the bake stores with
// --particles round-trips into Asset::particle_parent; a tree whose parent does not precede
// its child, or whose count is not the hierarchy's, is refused with a named error.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "bake/asset_writer.h"
#include "runtime/asset.h"
#include "runtime/asset_format.h"
#include "runtime/crc32.h"
#include "tests/common/bake_fixtures.h"

namespace {

using namespace stipple;

std::vector<uint8_t> encoded(const std::vector<uint32_t>& parents) {
    bake::RawScene s;
    bake::PointHierarchy p;
    test::tiny_square(&s, &p);
    return bake::encode_asset(s, p, bake::BakedStrokes(), bake::BakedLooks(), parents);
}

// Sets the PTRE section's first word (its count) and fixes the checksums.
void set_count(std::vector<uint8_t>* bytes, uint32_t count) {
    format::FileHeader h;
    std::memcpy(&h, bytes->data(), sizeof(h));
    auto* table = reinterpret_cast<format::SectionEntry*>(bytes->data() + sizeof(h));
    for (uint32_t i = 0; i < h.section_count; ++i)
        if (table[i].tag == format::kTagParticles) {
            std::memcpy(bytes->data() + table[i].offset, &count, 4);
            table[i].crc = format::crc32(bytes->data() + table[i].offset, table[i].size);
        }
    h.table_crc = format::crc32(table, h.section_count * sizeof(format::SectionEntry));
    std::memcpy(bytes->data(), &h, sizeof(h));
}

TEST(AssetParticles, TheStoredTreeLoads) {
    const uint32_t root = format::kNoParticleParent;
    const std::vector<uint8_t> bytes = encoded({root, 0, 0, 1});
    Asset a;
    ASSERT_TRUE(load_asset_memory(bytes.data(), bytes.size(), &a).ok());
    ASSERT_NE(a.particle_parent, nullptr);
    EXPECT_EQ(a.particle_parent[0], root);
    EXPECT_EQ(a.particle_parent[3], 1u);
    EXPECT_EQ(a.section_size[kSectionParticles], 20u);  // count + 4 parents
    const std::vector<uint8_t> none = encoded({});
    Asset b;
    ASSERT_TRUE(load_asset_memory(none.data(), none.size(), &b).ok());
    EXPECT_EQ(b.particle_parent, nullptr);  // no PTRE: the runtime builds the tree
    EXPECT_GT(bytes.size(), none.size());
}

TEST(AssetParticles, ParentsMustPrecedeTheirChildren) {
    const uint32_t root = format::kNoParticleParent;
    for (const std::vector<uint32_t>& bad : std::vector<std::vector<uint32_t>>{
             {root, 1, 0, 0}, {root, 0, 3, 0}, {0, root, 0, 0}, {root, 0, 0, 4}}) {
        const std::vector<uint8_t> bytes = encoded(bad);
        Asset a;
        const Status st = load_asset_memory(bytes.data(), bytes.size(), &a);
        EXPECT_EQ(st.error, LoadError::out_of_range) << st.message;
        EXPECT_NE(std::strstr(st.message, "PTRE"), nullptr) << st.message;
    }
}

TEST(AssetParticles, TheCountMustBeTheHierarchys) {
    for (uint32_t count : {3u, 5u, 0xFFFFFFFFu}) {
        std::vector<uint8_t> bytes = encoded({format::kNoParticleParent, 0, 0, 1});
        set_count(&bytes, count);
        Asset a;
        const Status st = load_asset_memory(bytes.data(), bytes.size(), &a);
        EXPECT_EQ(st.error, LoadError::malformed_section) << count << ": " << st.message;
    }
}

}  // namespace
