// Hostile assets: the loader's resource bounds (decoded size, counts against the bytes that
// hold them, the shared limits of runtime/asset_limits.h) and value domains (radii, normals,
// skin weights, empty hierarchies), each refused with its named LoadError; messages keep
// only printable ASCII. Assets are written by the bake's writer, then edited section by
// section and reassembled with valid checksums, so every edit reaches the semantic checks.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "bake/asset_writer.h"
#include "bake/scene_import.h"
#include "runtime/asset.h"
#include "runtime/asset_format.h"
#include "runtime/asset_limits.h"
#include "runtime/stipple.h"
#include "tests/common/gltf_writer.h"
#include "tests/common/scratch.h"

namespace {

using namespace stipple;

// A skinned quad with one clip ("wave") and a three-point hierarchy.
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
    s->joint_nodes = {0, 1};
    s->inverse_bind.assign(32, 0.0f);
    for (int j = 0; j < 2; ++j)
        for (int k = 0; k < 4; ++k) s->inverse_bind[size_t(j) * 16 + size_t(k) * 5] = 1.0f;
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

struct Section {
    uint32_t tag;
    std::vector<uint8_t> bytes;
};

std::vector<Section> split(const std::vector<uint8_t>& asset) {
    format::FileHeader h;
    std::memcpy(&h, asset.data(), sizeof(h));
    std::vector<Section> out;
    for (uint32_t i = 0; i < h.section_count; ++i) {
        format::SectionEntry e;
        std::memcpy(&e, asset.data() + sizeof(h) + i * sizeof(e), sizeof(e));
        out.push_back({e.tag, std::vector<uint8_t>(asset.begin() + long(e.offset),
                                                   asset.begin() + long(e.offset + e.size))});
    }
    return out;
}

// A version-3 file holding `sections`, with every offset, size and checksum right.
std::vector<uint8_t> assemble(const std::vector<Section>& sections) {
    format::FileHeader h = {{'S', 'T', 'I', 'P'},
                            format::kVersion,
                            format::kEndianTag,
                            uint32_t(sections.size()),
                            0,
                            0,
                            0};
    std::vector<format::SectionEntry> table;
    size_t at = sizeof(h) + sections.size() * sizeof(format::SectionEntry);
    for (const Section& s : sections) {
        at = (at + 15) / 16 * 16;
        table.push_back({s.tag, format::crc32(s.bytes.data(), s.bytes.size()), at, s.bytes.size()});
        at += s.bytes.size();
    }
    h.table_crc = format::crc32(table.data(), table.size() * sizeof(format::SectionEntry));
    h.file_size = at;
    std::vector<uint8_t> out(at, 0);
    std::memcpy(out.data(), &h, sizeof(h));
    std::memcpy(out.data() + sizeof(h), table.data(), table.size() * sizeof(table[0]));
    for (size_t i = 0; i < sections.size(); ++i)
        std::memcpy(out.data() + table[i].offset, sections[i].bytes.data(),
                    sections[i].bytes.size());
    return out;
}

Section* find(std::vector<Section>* sections, uint32_t tag) {
    for (Section& s : *sections)
        if (s.tag == tag) return &s;
    ADD_FAILURE() << "no section " << tag;
    return nullptr;
}

template <typename T>
void put(std::vector<uint8_t>* bytes, size_t at, T value) {
    std::memcpy(bytes->data() + at, &value, sizeof(T));
}
template <typename T>
void append(std::vector<uint8_t>* bytes, T value) {
    bytes->resize(bytes->size() + sizeof(T));
    std::memcpy(bytes->data() + bytes->size() - sizeof(T), &value, sizeof(T));
}

Status load(const std::vector<uint8_t>& bytes, const LoadOptions& options = LoadOptions()) {
    Asset a;
    return load_asset_memory(bytes.data(), bytes.size(), &a, options);
}

// The base asset with its CLIP section replaced by one clip of `channels` translation
// channels on node 1, all reading the same `keys` keys: one time array, one code block.
std::vector<uint8_t> shared_key_asset(uint32_t channels, uint32_t keys) {
    std::vector<Section> sections = split(encoded());
    std::vector<uint8_t> c;
    const uint32_t columns = 3, names = 5;
    for (uint32_t n : {1u, channels, 1u, keys, columns * 2, keys * columns, names}) append(&c, n);
    append(&c, format::ClipRecord{0, 0, channels, 1.0f});
    for (uint32_t i = 0; i < channels; ++i)
        append(&c, format::ChannelRecordV2{1, 0, 1, 0, keys, 0, 0, 0, 0, 0});
    append(&c, format::TimeArrayRecord{0, keys});
    for (uint32_t k = 0; k < keys; ++k) append(&c, float(k) / float(keys));
    for (uint32_t k = 0; k < columns; ++k) {
        append(&c, -1.0f);
        append(&c, 1.0f);
    }
    for (uint32_t k = 0; k < keys * columns; ++k) append(&c, uint16_t(k * 7));
    for (char ch : std::string("wave")) append(&c, ch);
    append(&c, '\0');
    find(&sections, format::kTagClips)->bytes = c;
    return assemble(sections);
}

// Peak resident set, in bytes, of a child process that loads `bytes`; *error gets the
// LoadError it exited with.
long child_peak_rss(const std::vector<uint8_t>& bytes, int* error) {
    const pid_t pid = fork();
    if (pid == 0) {
        Asset a;
        const Status st = load_asset_memory(bytes.data(), bytes.size(), &a);
        _exit(int(st.error));
    }
    int status = 0;
    rusage usage = {};
    wait4(pid, &status, 0, &usage);
    *error = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return usage.ru_maxrss * 1024L;
}

TEST(AssetHostile, SharedKeyBombIsRefusedBeforeDecoding) {
    // 4096 channels share one block of 20,000 keys: a 0.4 MB file that would decode into
    // 4096 * 20000 * 3 floats = 983 MB.
    const std::vector<uint8_t> bomb = shared_key_asset(4096, 20000);
    ASSERT_LT(bomb.size(), size_t(1) << 20);
    const Status st = load(bomb);
    EXPECT_EQ(st.error, LoadError::decoded_size_limit) << st.message;
    EXPECT_EQ(st.code, StatusCode::bad_asset);
    EXPECT_NE(std::strstr(st.message, "CLIP: decoding needs"), nullptr) << st.message;
    // Refused before the memory is taken: the child that loads it stays far below 983 MB.
    int error = -1;
    const long peak = child_peak_rss(bomb, &error);
    EXPECT_EQ(error, int(LoadError::decoded_size_limit));
    EXPECT_LT(peak, 200L << 20) << "peak RSS " << peak;
    // The C API reports it as a bad asset, and a configured cap decides it too.
    stipple_asset* asset = nullptr;
    EXPECT_EQ(stipple_asset_load_memory(bomb.data(), bomb.size(), &asset), STIPPLE_ERROR_BAD_ASSET);
    EXPECT_EQ(asset, nullptr);
}

TEST(AssetHostile, DecodedSizeLimitIsConfigurable) {
    // Eight channels sharing 100 keys: 9.6 KB decoded, well within the default limit.
    const std::vector<uint8_t> bytes = shared_key_asset(8, 100);
    EXPECT_TRUE(load(bytes).ok()) << load(bytes).message;
    LoadOptions tight;
    tight.max_decoded_bytes = 4096;
    EXPECT_EQ(load(bytes, tight).error, LoadError::decoded_size_limit);
    stipple_load_desc desc = {};
    desc.max_decoded_bytes = 4096;
    stipple_asset* asset = nullptr;
    EXPECT_EQ(stipple_asset_load_memory_ex(bytes.data(), bytes.size(), &desc, &asset),
              STIPPLE_ERROR_BAD_ASSET);
    desc.max_decoded_bytes = 0;  // default
    ASSERT_EQ(stipple_asset_load_memory_ex(bytes.data(), bytes.size(), &desc, &asset), STIPPLE_OK);
    EXPECT_EQ(stipple_asset_clip_count(asset), 1u);
    stipple_asset_destroy(asset);
    // A cap above the default lets through what the default refuses.
    const std::vector<uint8_t> bomb = shared_key_asset(64, 4000);  // 3 MB from 43 KB
    EXPECT_EQ(load(bomb).error, LoadError::decoded_size_limit);
    LoadOptions generous;
    generous.max_decoded_bytes = 64ull << 20;
    EXPECT_TRUE(load(bomb, generous).ok());
    EXPECT_EQ(decoded_size_limit(1000, LoadOptions()),
              1000 * limits::kDecodedPerFileByte + limits::kDecodedFloorBytes);
}

// Sets PNTQ's point count (its first u32) to `count`.
std::vector<uint8_t> with_point_count(uint32_t count) {
    std::vector<Section> sections = split(encoded());
    put(&find(&sections, format::kTagPointStream)->bytes, 0, count);
    return assemble(sections);
}

TEST(AssetHostile, PointCountBeyondTheStreamIsNamedNotOutOfMemory) {
    // 2^25 points need at least 2^25 * 41 bits; the stream has a few dozen bytes.
    Status st = load(with_point_count(1u << 25));
    EXPECT_EQ(st.error, LoadError::count_exceeds_data) << st.message;
    EXPECT_EQ(st.code, StatusCode::bad_asset);
    EXPECT_NE(std::strstr(st.message, "33554432 points need"), nullptr) << st.message;
    // Over the shared limit: named as such (it used to ask for 16 GiB).
    st = load(with_point_count(0xFFFFFFFFu));
    EXPECT_EQ(st.error, LoadError::count_over_limit) << st.message;
    st = load(with_point_count(0));
    EXPECT_EQ(st.error, LoadError::zero_count) << st.message;
}

TEST(AssetHostile, RadiusScaleMustBeFiniteAndNonNegative) {
    for (float r : {-1.0f, std::numeric_limits<float>::infinity()}) {
        std::vector<Section> sections = split(encoded());
        put(&find(&sections, format::kTagPointStream)->bytes, 4, r);
        const Status st = load(assemble(sections));
        EXPECT_EQ(st.error, LoadError::bad_radius) << st.message;
    }
}

TEST(AssetHostile, NormalsAreZeroOrUnitLength) {
    bake::RawScene s;
    bake::PointHierarchy p;
    make_scene(&s, &p);
    s.normals[2] = 0.5f;  // vertex 0: length 0.5
    Status st = load(bake::encode_asset(s, p));
    EXPECT_EQ(st.error, LoadError::bad_normal) << st.message;
    EXPECT_NE(std::strstr(st.message, "vertex 0 normal length 0.5"), nullptr) << st.message;
    s.normals[2] = 1e-20f;
    EXPECT_EQ(load(bake::encode_asset(s, p)).error, LoadError::bad_normal);
    // Zero is allowed: the bake writes it for a vertex whose faces are all degenerate.
    s.normals[2] = 0.0f;
    EXPECT_TRUE(load(bake::encode_asset(s, p)).ok());
}

TEST(AssetHostile, SkinWeightsAreInUnitRangeAndSumToOne) {
    bake::RawScene s;
    bake::PointHierarchy p;
    for (std::vector<float> w : {std::vector<float>{1e30f, 0, 0, 0},
                                 {-1e30f, 1, 0, 0},
                                 {0.5f, 0.2f, 0, 0},
                                 {1.0f, 0.01f, 0, 0}}) {
        make_scene(&s, &p);
        std::copy(w.begin(), w.end(), s.weights.begin() + 4);  // vertex 1
        const Status st = load(bake::encode_asset(s, p));
        EXPECT_EQ(st.error, LoadError::bad_skin_weight) << st.message;
        EXPECT_NE(std::strstr(st.message, "SKIN: vertex 1"), nullptr) << st.message;
    }
    make_scene(&s, &p);  // within the tolerance: a float renormalisation's rounding
    s.weights[4] = 0.5f + 1e-6f;
    EXPECT_TRUE(load(bake::encode_asset(s, p)).ok());
}

TEST(AssetHostile, EmptyMeshIsAZeroCount) {
    std::vector<Section> sections = split(encoded());
    find(&sections, format::kTagMesh)->bytes.assign(8, 0);  // V = 0, T = 0
    EXPECT_EQ(load(assemble(sections)).error, LoadError::zero_count);
}

TEST(AssetHostile, NoBytesIsAnInvalidArgument) {
    Asset a;
    Status st = load_asset_memory(nullptr, 0, &a);
    EXPECT_EQ(st.error, LoadError::invalid_argument);
    EXPECT_EQ(st.code, StatusCode::invalid_argument);
    const uint8_t byte = 0;
    EXPECT_EQ(load_asset_memory(&byte, 0, &a).code, StatusCode::invalid_argument);
    EXPECT_EQ(load_asset_memory(nullptr, 100, &a).code, StatusCode::invalid_argument);
    EXPECT_EQ(load_asset_file(nullptr, &a).code, StatusCode::invalid_argument);
    stipple_asset* asset = nullptr;
    EXPECT_EQ(stipple_asset_load_memory(nullptr, 0, &asset), STIPPLE_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(stipple_asset_load_memory(&byte, 0, &asset), STIPPLE_ERROR_INVALID_ARGUMENT);
}

TEST(AssetHostile, OnlyRegularFilesAreReadAsAssets) {
    // A directory "opens" with a size of 2^63 - 1 and /dev/zero never ends: both are named
    // I/O errors before anything is read or allocated.
    const std::string dir = std::filesystem::temp_directory_path().string();
    Asset a;
    Status st = load_asset_file(dir.c_str(), &a);
    EXPECT_EQ(st.error, LoadError::io_error);
    EXPECT_NE(std::string(st.message).find("is a directory"), std::string::npos) << st.message;
    st = load_asset_file("/dev/zero", &a);
    EXPECT_EQ(st.error, LoadError::io_error);
    EXPECT_NE(std::string(st.message).find("not a regular file"), std::string::npos) << st.message;
    st = load_asset_file("/nonexistent/asset.stip", &a);
    EXPECT_EQ(st.error, LoadError::io_error);
    EXPECT_NE(std::string(st.message).find("No such file or directory"), std::string::npos)
        << st.message;
}

TEST(AssetHostile, MessagesKeepOnlyPrintableAscii) {
    std::vector<Section> sections = split(encoded());
    sections.push_back({format::fourcc('\n', '\x1b', '[', 'J'), {1, 2, 3, 4}});
    std::vector<uint8_t> bytes = assemble(sections);
    // Corrupt the new section's bytes: its checksum error names its tag.
    bytes[bytes.size() - 1] ^= 0xFF;
    const Status st = load(bytes);
    EXPECT_EQ(st.error, LoadError::checksum_mismatch) << st.message;
    for (const char* c = st.message; *c; ++c)
        EXPECT_TRUE(*c >= 0x20 && *c < 0x7F) << "byte " << int(*c) << " in " << st.message;
    EXPECT_NE(std::strstr(st.message, "\\x0a\\x1b[J: checksum mismatch"), nullptr) << st.message;
}

// A scene of `joints` root nodes, each a joint; every vertex follows joint 0.
std::vector<uint8_t> joint_asset(uint32_t joints) {
    bake::RawScene s;
    bake::PointHierarchy p;
    make_scene(&s, &p);
    s.clips.clear();
    s.nodes.assign(joints, bake::RawNode());
    s.joint_nodes.resize(joints);
    s.inverse_bind.assign(size_t(joints) * 16, 0.0f);
    for (uint32_t j = 0; j < joints; ++j) {
        s.joint_nodes[j] = j;
        for (int k = 0; k < 4; ++k) s.inverse_bind[size_t(j) * 16 + size_t(k) * 5] = 1.0f;
    }
    return bake::encode_asset(s, p);
}

TEST(AssetHostile, ImporterAndLoaderShareTheJointLimit) {
    // The loader takes exactly limits::kMaxJoints (every u16 index) and refuses one more.
    EXPECT_TRUE(load(joint_asset(limits::kMaxJoints)).ok());
    const Status st = load(joint_asset(limits::kMaxJoints + 1));
    EXPECT_EQ(st.error, LoadError::count_over_limit) << st.message;
    EXPECT_NE(std::strstr(st.message, "joint count 65537 over the limit of 65536"), nullptr)
        << st.message;
    // The importer refuses a skin over the same limit, naming it.
    std::string joints = "0";
    for (uint32_t j = 1; j <= limits::kMaxJoints; ++j) joints += ",0";
    test::GltfBin bin;
    bin.put<float>({0, 0, 0, 1, 0, 0, 0, 1, 0});
    bin.put<uint16_t>({0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0});
    bin.put<float>({1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0});
    const std::string path = test::scratch_path("joint_limit.gltf");
    test::write_gltf(path,
                     R"({
      "asset": {"version": "2.0"},
      "scene": 0, "scenes": [{"nodes": [0, 1]}],
      "nodes": [{"mesh": 0, "skin": 0}, {}],
      "skins": [{"joints": [)" +
                         joints + R"(]}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "JOINTS_0": 1, "WEIGHTS_0": 2}}]}],
      "buffers": [@BUFFER@],
      "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                      {"buffer": 0, "byteOffset": 36, "byteLength": 24},
                      {"buffer": 0, "byteOffset": 60, "byteLength": 48}],
      "accessors": [
        {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
         "min": [0, 0, 0], "max": [1, 1, 0]},
        {"bufferView": 1, "componentType": 5123, "count": 3, "type": "VEC4"},
        {"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC4"}]
    })",
                     bin);
    bake::RawScene scene;
    const bake::BakeError e = bake::import_scene(path, &scene);
    std::filesystem::remove(path);
    EXPECT_FALSE(e.ok());
    EXPECT_NE(e.message.find("joint count 65537 out of range [1, 65536]"), std::string::npos)
        << e.message;
}

TEST(AssetHostile, NewLoadErrorsHaveNamesAndCodes) {
    EXPECT_EQ(status_code_of(LoadError::invalid_argument), StatusCode::invalid_argument);
    for (LoadError e : {LoadError::count_over_limit, LoadError::count_exceeds_data,
                        LoadError::decoded_size_limit, LoadError::zero_count, LoadError::bad_normal,
                        LoadError::bad_skin_weight, LoadError::bad_radius}) {
        EXPECT_EQ(status_code_of(e), StatusCode::bad_asset) << load_error_name(e);
        EXPECT_STRNE(load_error_name(e), "unknown");
    }
}

}  // namespace
