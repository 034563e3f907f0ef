// Tests for tools/image_write (PNG and APNG writers). The APNG file is checked chunk by chunk
// against the APNG 1.0 spec (acTL, fcTL, fdAT) with a CRC written independently of the writer's
// table-driven one.
#include <gtest/gtest.h>
#include <stb/stb_image.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "tests/common/fixtures.h"
#include "tools/image_write.h"

namespace {

namespace fs = std::filesystem;
using stipple::image::ApngWriter;
using stipple::image::write_png;

using stipple::test::ScratchDir;

// A w x h RGBA8 image in which every byte depends on its row, column, channel and `seed`, so a
// flip, a transposition or a frame mix-up all show.
std::vector<uint8_t> make_image(int w, int h, int seed) {
    std::vector<uint8_t> rgba(static_cast<size_t>(w) * h * 4);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            uint8_t* p = &rgba[(static_cast<size_t>(y) * w + x) * 4];
            p[0] = static_cast<uint8_t>(x * 37 + seed * 11);
            p[1] = static_cast<uint8_t>(y * 53 + seed * 7);
            p[2] = static_cast<uint8_t>((x ^ y) * 19 + seed);
            p[3] = static_cast<uint8_t>(255 - (x + y + seed) % 64);
        }
    }
    return rgba;
}

std::vector<uint8_t> flip_rows(const std::vector<uint8_t>& rgba, int w, int h) {
    std::vector<uint8_t> out(rgba.size());
    const size_t row = static_cast<size_t>(w) * 4;
    for (int y = 0; y < h; ++y) {
        std::memcpy(&out[(h - 1 - y) * row], &rgba[y * row], row);
    }
    return out;
}

std::vector<uint8_t> read_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), {});
}

// Decodes a PNG file or buffer to RGBA8; empty on failure.
std::vector<uint8_t> decode(const uint8_t* png, size_t size, int expect_w, int expect_h) {
    int w = 0, h = 0, comp = 0;
    stbi_uc* pixels = stbi_load_from_memory(png, static_cast<int>(size), &w, &h, &comp, 4);
    if (!pixels) return {};
    std::vector<uint8_t> out;
    if (w == expect_w && h == expect_h) out.assign(pixels, pixels + static_cast<size_t>(w) * h * 4);
    stbi_image_free(pixels);
    return out;
}

uint32_t be32(const uint8_t* p) {
    return (uint32_t{p[0]} << 24) | (uint32_t{p[1]} << 16) | (uint32_t{p[2]} << 8) | p[3];
}
uint16_t be16(const uint8_t* p) {
    return static_cast<uint16_t>((p[0] << 8) | p[1]);
}

// Bit-at-a-time CRC-32 (PNG spec Annex D), deliberately not the writer's table-driven one.
uint32_t reference_crc(const uint8_t* data, size_t size) {
    uint32_t crc = 0xFFFFFFFFu;
    for (size_t i = 0; i < size; ++i) {
        crc ^= data[i];
        for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
    }
    return ~crc;
}

struct PngChunk {
    std::string type;
    std::vector<uint8_t> data;
    bool crc_ok;
};

// Splits a PNG file into chunks; fails the test on a bad signature or truncation.
std::vector<PngChunk> parse_png(const std::vector<uint8_t>& file) {
    static const uint8_t kSignature[8] = {137, 80, 78, 71, 13, 10, 26, 10};
    std::vector<PngChunk> chunks;
    EXPECT_GE(file.size(), 8u);
    if (file.size() < 8) return chunks;
    EXPECT_EQ(0, std::memcmp(file.data(), kSignature, 8)) << "PNG signature";
    size_t pos = 8;
    while (pos < file.size()) {
        EXPECT_GE(file.size() - pos, 12u) << "truncated chunk header at " << pos;
        if (file.size() - pos < 12) break;
        const uint32_t length = be32(&file[pos]);
        EXPECT_LE(length, file.size() - pos - 12) << "truncated chunk at " << pos;
        if (length > file.size() - pos - 12) break;
        PngChunk chunk;
        chunk.type.assign(reinterpret_cast<const char*>(&file[pos + 4]), 4);
        chunk.data.assign(file.begin() + pos + 8, file.begin() + pos + 8 + length);
        chunk.crc_ok = reference_crc(&file[pos + 4], length + 4) == be32(&file[pos + 8 + length]);
        chunks.push_back(std::move(chunk));
        pos += 12 + size_t{length};
    }
    return chunks;
}

void append_chunk(std::vector<uint8_t>* png, const char* type, const uint8_t* data, size_t size) {
    const size_t start = png->size();
    png->resize(start + 12 + size);
    uint8_t* p = png->data() + start;
    p[0] = static_cast<uint8_t>(size >> 24);
    p[1] = static_cast<uint8_t>(size >> 16);
    p[2] = static_cast<uint8_t>(size >> 8);
    p[3] = static_cast<uint8_t>(size);
    std::memcpy(p + 4, type, 4);
    if (size) std::memcpy(p + 8, data, size);
    const uint32_t crc = reference_crc(p + 4, size + 4);
    for (int i = 0; i < 4; ++i) p[8 + size + i] = static_cast<uint8_t>(crc >> (24 - 8 * i));
}

// ---------------------------------------------------------------------------------------------
// PNG

TEST(ImageWrite, PngRoundTripTopDownIsExact) {
    ScratchDir dir;
    const int w = 7, h = 5;  // odd sizes catch stride mistakes
    const std::vector<uint8_t> image = make_image(w, h, 1);
    const std::string path = dir.file("top_down.png");
    std::string error;
    ASSERT_TRUE(write_png(path.c_str(), w, h, image.data(), false, &error)) << error;
    const std::vector<uint8_t> file = read_file(path);
    EXPECT_EQ(decode(file.data(), file.size(), w, h), image);
}

TEST(ImageWrite, PngRoundTripBottomUpIsFlipped) {
    ScratchDir dir;
    const int w = 6, h = 9;
    const std::vector<uint8_t> gl_rows = make_image(w, h, 2);  // row 0 = bottom of the picture
    const std::string path = dir.file("bottom_up.png");
    std::string error;
    ASSERT_TRUE(write_png(path.c_str(), w, h, gl_rows.data(), true, &error)) << error;
    const std::vector<uint8_t> file = read_file(path);
    const std::vector<uint8_t> decoded = decode(file.data(), file.size(), w, h);
    ASSERT_EQ(decoded.size(), gl_rows.size());
    EXPECT_EQ(decoded, flip_rows(gl_rows, w, h));
    // The decoded top row is the input's last row.
    EXPECT_EQ(0, std::memcmp(decoded.data(), &gl_rows[static_cast<size_t>(h - 1) * w * 4], w * 4));
}

TEST(ImageWrite, PngChunksHaveValidCrcs) {
    ScratchDir dir;
    const std::vector<uint8_t> image = make_image(3, 4, 3);
    const std::string path = dir.file("crc.png");
    ASSERT_TRUE(write_png(path.c_str(), 3, 4, image.data(), false, nullptr));
    const std::vector<PngChunk> chunks = parse_png(read_file(path));
    ASSERT_GE(chunks.size(), 3u);
    EXPECT_EQ(chunks.front().type, "IHDR");
    EXPECT_EQ(chunks.back().type, "IEND");
    for (const PngChunk& c : chunks) EXPECT_TRUE(c.crc_ok) << c.type;
}

TEST(ImageWrite, PngToMissingDirectoryFailsWithMessage) {
    ScratchDir dir;
    const std::vector<uint8_t> image = make_image(2, 2, 4);
    const std::string path = dir.file("no_such_dir/out.png");
    std::string error;
    EXPECT_FALSE(write_png(path.c_str(), 2, 2, image.data(), false, &error));
    EXPECT_FALSE(error.empty());
    EXPECT_EQ(error.find('\n'), std::string::npos) << "one line: " << error;
    EXPECT_NE(error.find("no_such_dir"), std::string::npos) << error;
    EXPECT_FALSE(fs::exists(path));
    EXPECT_FALSE(write_png(path.c_str(), 2, 2, image.data(), false, nullptr));  // no crash
}

TEST(ImageWrite, PngRejectsBadArguments) {
    ScratchDir dir;
    const std::string path = dir.file("bad.png");
    const std::vector<uint8_t> image = make_image(2, 2, 5);
    std::string error;
    EXPECT_FALSE(write_png(path.c_str(), 0, 2, image.data(), false, &error));
    EXPECT_FALSE(error.empty());
    error.clear();
    EXPECT_FALSE(write_png(path.c_str(), 2, -1, image.data(), false, &error));
    EXPECT_FALSE(error.empty());
    error.clear();
    EXPECT_FALSE(write_png(path.c_str(), 2, 2, nullptr, false, &error));
    EXPECT_FALSE(error.empty());
    error.clear();
    EXPECT_FALSE(write_png(nullptr, 2, 2, image.data(), false, &error));
    EXPECT_FALSE(error.empty());
    EXPECT_FALSE(fs::exists(path));
}

// ---------------------------------------------------------------------------------------------
// APNG

TEST(Apng, ThreeFramesHaveValidChunkStructure) {
    ScratchDir dir;
    const int w = 5, h = 4;
    const std::vector<uint8_t> frames[3] = {make_image(w, h, 10), make_image(w, h, 20),
                                            make_image(w, h, 30)};
    const bool bottom_up[3] = {false, true, false};
    const std::string path = dir.file("anim.png");
    std::string error;
    {
        ApngWriter apng;
        ASSERT_TRUE(apng.open(path.c_str(), 25, 1, &error)) << error;
        for (int f = 0; f < 3; ++f) {
            ASSERT_TRUE(apng.add_frame(w, h, frames[f].data(), bottom_up[f], &error)) << error;
        }
        EXPECT_EQ(apng.frame_count(), 3);
        ASSERT_TRUE(apng.finish(&error)) << error;
        EXPECT_FALSE(apng.is_open());
    }
    const std::vector<uint8_t> file = read_file(path);
    const std::vector<PngChunk> chunks = parse_png(file);
    ASSERT_GE(chunks.size(), 5u);

    EXPECT_EQ(chunks.front().type, "IHDR");
    ASSERT_EQ(chunks.front().data.size(), 13u);
    EXPECT_EQ(be32(&chunks.front().data[0]), uint32_t(w));
    EXPECT_EQ(be32(&chunks.front().data[4]), uint32_t(h));
    EXPECT_EQ(chunks.back().type, "IEND");
    EXPECT_TRUE(chunks.back().data.empty());

    int actl_count = 0, fctl_count = 0, idat_count = 0, fdat_count = 0;
    bool seen_idat = false;
    int64_t last_sequence = -1;
    // Per frame, the compressed data (IDAT, or fdAT without its sequence number).
    std::vector<std::vector<std::vector<uint8_t>>> frame_data;
    for (size_t i = 0; i < chunks.size(); ++i) {
        const PngChunk& c = chunks[i];
        EXPECT_TRUE(c.crc_ok) << "chunk " << i << " " << c.type;
        if (c.type == "IEND") {
            EXPECT_EQ(i, chunks.size() - 1) << "IEND must be last";
        }
        if (c.type == "IHDR") {
            EXPECT_EQ(i, 0u) << "IHDR must be first";
        }
        if (c.type == "acTL") {
            ++actl_count;
            EXPECT_FALSE(seen_idat) << "acTL must precede IDAT";
            ASSERT_EQ(c.data.size(), 8u);
            EXPECT_EQ(be32(&c.data[0]), 3u) << "num_frames";
            EXPECT_EQ(be32(&c.data[4]), 0u) << "num_plays (0 = loop)";
        } else if (c.type == "fcTL") {
            ++fctl_count;
            ASSERT_EQ(c.data.size(), 26u);
            const uint32_t sequence = be32(&c.data[0]);
            EXPECT_EQ(int64_t{sequence}, last_sequence + 1) << "fcTL sequence";
            last_sequence = sequence;
            EXPECT_EQ(be32(&c.data[4]), uint32_t(w));
            EXPECT_EQ(be32(&c.data[8]), uint32_t(h));
            EXPECT_EQ(be32(&c.data[12]), 0u);
            EXPECT_EQ(be32(&c.data[16]), 0u);
            EXPECT_EQ(be16(&c.data[20]), 1) << "delay_num: 1/25 s per frame";
            EXPECT_EQ(be16(&c.data[22]), 25) << "delay_den";
            EXPECT_EQ(c.data[24], 0) << "dispose_op NONE";
            EXPECT_EQ(c.data[25], 0) << "blend_op SOURCE";
            frame_data.emplace_back();
        } else if (c.type == "IDAT") {
            ++idat_count;
            seen_idat = true;
            EXPECT_EQ(fctl_count, 1) << "IDAT belongs to the first frame";
            EXPECT_EQ(fdat_count, 0);
            ASSERT_FALSE(frame_data.empty());
            frame_data.back().push_back(c.data);
        } else if (c.type == "fdAT") {
            ++fdat_count;
            ASSERT_GE(c.data.size(), 4u);
            const uint32_t sequence = be32(&c.data[0]);
            EXPECT_EQ(int64_t{sequence}, last_sequence + 1) << "fdAT sequence";
            last_sequence = sequence;
            EXPECT_GE(fctl_count, 2) << "fdAT only for later frames";
            ASSERT_FALSE(frame_data.empty());
            frame_data.back().emplace_back(c.data.begin() + 4, c.data.end());
        }
    }
    EXPECT_EQ(actl_count, 1);
    EXPECT_EQ(fctl_count, 3);
    EXPECT_GE(idat_count, 1);
    EXPECT_GE(fdat_count, 2);

    // The default image (what a plain PNG decoder shows) is the first frame.
    EXPECT_EQ(decode(file.data(), file.size(), w, h), frames[0]);

    // Every frame decodes to its input: rebuild a plain PNG from IHDR and the frame's data.
    ASSERT_EQ(frame_data.size(), 3u);
    for (int f = 0; f < 3; ++f) {
        std::vector<uint8_t> png(file.begin(), file.begin() + 8);
        append_chunk(&png, "IHDR", chunks.front().data.data(), 13);
        for (const auto& data : frame_data[f]) append_chunk(&png, "IDAT", data.data(), data.size());
        append_chunk(&png, "IEND", nullptr, 0);
        const std::vector<uint8_t> expected = bottom_up[f] ? flip_rows(frames[f], w, h) : frames[f];
        EXPECT_EQ(decode(png.data(), png.size(), w, h), expected) << "frame " << f;
    }
}

TEST(Apng, SizeMismatchIsRejectedAndWriterStaysUsable) {
    ScratchDir dir;
    const std::vector<uint8_t> a = make_image(4, 4, 1), b = make_image(5, 4, 2);
    const std::string path = dir.file("mismatch.png");
    std::string error;
    ApngWriter apng;
    ASSERT_TRUE(apng.open(path.c_str(), 30, 1, &error)) << error;
    ASSERT_TRUE(apng.add_frame(4, 4, a.data(), false, &error)) << error;
    EXPECT_FALSE(apng.add_frame(5, 4, b.data(), false, &error));
    EXPECT_NE(error.find("5x4"), std::string::npos) << error;
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
    ASSERT_TRUE(apng.add_frame(4, 4, a.data(), true, &error)) << error;
    ASSERT_TRUE(apng.finish(&error)) << error;
    int actl_frames = -1;
    for (const PngChunk& c : parse_png(read_file(path))) {
        EXPECT_TRUE(c.crc_ok) << c.type;
        if (c.type == "acTL") actl_frames = static_cast<int>(be32(&c.data[0]));
    }
    EXPECT_EQ(actl_frames, 2);
}

TEST(Apng, ErrorsReturnFalseWithMessage) {
    ScratchDir dir;
    const std::vector<uint8_t> a = make_image(2, 2, 1);
    std::string error;
    {
        ApngWriter apng;
        const std::string missing = dir.file("no_such_dir/anim.png");
        EXPECT_FALSE(apng.open(missing.c_str(), 30, 1, &error));
        EXPECT_NE(error.find("no_such_dir"), std::string::npos) << error;
        error.clear();
        EXPECT_FALSE(apng.add_frame(2, 2, a.data(), false, &error));  // not open
        EXPECT_FALSE(error.empty());
        error.clear();
        EXPECT_FALSE(apng.finish(&error));
        EXPECT_FALSE(error.empty());
    }
    {
        ApngWriter apng;
        error.clear();
        EXPECT_FALSE(apng.open(dir.file("rate.png").c_str(), 0, 1, &error));
        EXPECT_FALSE(error.empty());
        error.clear();
        EXPECT_FALSE(apng.open(dir.file("rate.png").c_str(), 30, 70000, &error));
        EXPECT_FALSE(error.empty());
    }
    {
        // No frames: finish fails and leaves no invalid file behind.
        ApngWriter apng;
        const std::string empty = dir.file("empty.png");
        ASSERT_TRUE(apng.open(empty.c_str(), 30, 1, &error)) << error;
        error.clear();
        EXPECT_FALSE(apng.add_frame(2, 2, nullptr, false, &error));
        EXPECT_FALSE(error.empty());
        error.clear();
        EXPECT_FALSE(apng.finish(&error));
        EXPECT_FALSE(error.empty());
        EXPECT_FALSE(fs::exists(empty));
    }
}

TEST(Apng, DestructorFinishesAnOpenFile) {
    ScratchDir dir;
    const std::vector<uint8_t> a = make_image(3, 3, 1);
    const std::string path = dir.file("raii.png");
    {
        ApngWriter apng;
        ASSERT_TRUE(apng.open(path.c_str(), 10, 1, nullptr));
        ASSERT_TRUE(apng.add_frame(3, 3, a.data(), false, nullptr));
    }
    const std::vector<uint8_t> file = read_file(path);
    const std::vector<PngChunk> chunks = parse_png(file);
    ASSERT_FALSE(chunks.empty());
    EXPECT_EQ(chunks.back().type, "IEND");
    EXPECT_EQ(decode(file.data(), file.size(), 3, 3), a);
}

}  // namespace
