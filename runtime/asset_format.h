// The .stip asset: one little-endian binary file holding everything the runtime needs.
// See docs/format.md for the byte layout. Shared by the bake's writer and the runtime's
// loader; plain constants and POD records only.
#pragma once
#include <cstddef>
#include <cstdint>

namespace stipple::format {

constexpr char kMagic[4] = {'S', 'T', 'I', 'P'};
constexpr uint16_t kVersion = 1;        // written by the bake
constexpr uint16_t kOldestVersion = 0;  // still read: v0 stores points uncompressed
constexpr uint16_t kEndianTag = 0xFEFF;  // reads as 0xFFFE on a big-endian machine
constexpr uint32_t kSectionAlign = 16;

constexpr uint32_t fourcc(char a, char b, char c, char d) {
    return uint32_t(uint8_t(a)) | uint32_t(uint8_t(b)) << 8 | uint32_t(uint8_t(c)) << 16 |
           uint32_t(uint8_t(d)) << 24;
}
constexpr uint32_t kTagMesh = fourcc('M', 'E', 'S', 'H');
constexpr uint32_t kTagSkin = fourcc('S', 'K', 'I', 'N');
constexpr uint32_t kTagClips = fourcc('C', 'L', 'I', 'P');
constexpr uint32_t kTagPoints = fourcc('P', 'N', 'T', 'S');
constexpr uint32_t kTagNeighbours = fourcc('N', 'B', 'R', 'S');
constexpr uint32_t kTagEdges = fourcc('E', 'D', 'G', 'E');
constexpr uint32_t kTagPointStream = fourcc('P', 'N', 'T', 'Q');  // v1: PNTS + NBRS, coded
constexpr uint32_t kNoFace = 0xFFFFFFFFu;  // second face of a boundary edge

struct FileHeader {         // 32 bytes at offset 0
    char magic[4];
    uint16_t version;
    uint16_t endian_tag;
    uint32_t section_count;
    uint32_t table_crc;     // CRC-32 of the section table
    uint64_t file_size;
    uint64_t reserved;
};
static_assert(sizeof(FileHeader) == 32, "header layout");

struct SectionEntry {       // section_count entries right after the header
    uint32_t tag;
    uint32_t crc;           // CRC-32 of the section's bytes
    uint64_t offset;        // from the start of the file, kSectionAlign-aligned
    uint64_t size;
};
static_assert(sizeof(SectionEntry) == 24, "section entry layout");

struct ClipRecord {         // one per clip in the CLIP section
    uint32_t name_offset;   // into the name pool, NUL-terminated
    uint32_t channel_begin;
    uint32_t channel_count;
    float duration;
};
struct ChannelRecord {      // one per channel in the CLIP section
    uint32_t node;
    uint8_t path;           // 0 translation, 1 rotation, 2 scale
    uint8_t interp;         // 0 step, 1 linear
    uint16_t reserved;
    uint32_t key_count;
    uint32_t times_offset;  // into the float pool
    uint32_t values_offset; // into the float pool
};
static_assert(sizeof(ClipRecord) == 16 && sizeof(ChannelRecord) == 20, "clip layout");

// CRC-32 (ISO-HDLC / zlib polynomial), used for section checksums.
uint32_t crc32(const void* data, size_t size, uint32_t crc = 0);

}  // namespace stipple::format
