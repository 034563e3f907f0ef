// Helpers shared by the fuzz targets (tests/fuzz/, docs/fuzzing.md).
#pragma once
#include <sys/stat.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "runtime/asset_format.h"
#include "runtime/crc32.h"

namespace stipple::fuzz {

// The input as an asset whose checksums match, unless the loader was built with
// STIPPLE_FUZZ_SKIP_CRC: then the bytes as they are. Without the option (the replay tests of
// a normal or sanitizer build) rewriting the table and section CRCs lets the same inputs
// reach the decoders, so a crash found in a fuzz build replays everywhere.
inline std::vector<uint8_t> asset_bytes(const uint8_t* data, size_t size) {
    std::vector<uint8_t> bytes(data, data + size);
#ifndef STIPPLE_FUZZ_SKIP_CRC
    format::FileHeader h;
    if (size < sizeof(h)) return bytes;
    std::memcpy(&h, bytes.data(), sizeof(h));
    const size_t table_bytes = size_t(h.section_count) * sizeof(format::SectionEntry);
    if (h.section_count > 4096 || sizeof(h) + table_bytes > size) return bytes;
    uint8_t* table = bytes.data() + sizeof(h);
    for (uint32_t i = 0; i < h.section_count; ++i) {
        format::SectionEntry s;
        std::memcpy(&s, table + i * sizeof(s), sizeof(s));
        if (s.offset > size || s.size > size - s.offset) continue;
        s.crc = format::crc32(bytes.data() + s.offset, s.size);
        std::memcpy(table + i * sizeof(s), &s, sizeof(s));
    }
    h.table_crc = format::crc32(table, table_bytes);
    std::memcpy(bytes.data(), &h, sizeof(h));
#endif
    return bytes;
}

inline std::string& scratch_dir() {
    static std::string dir;
    return dir;
}

// Writes `data` to `name` in a per-process scratch folder under /dev/shm (or /tmp), removed
// at exit, and returns its path; the importers read files. Empty on failure.
inline std::string write_scratch(const std::string& name, const uint8_t* data, size_t size) {
    static const std::string dir = [] {
        std::string d = access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp";
        d += "/stipple_fuzz_" + std::to_string(getpid());
        mkdir(d.c_str(), 0700);
        scratch_dir() = d;
        std::atexit([] {
            std::error_code ec;
            std::filesystem::remove_all(scratch_dir(), ec);
        });
        return d;
    }();
    const std::string path = dir + "/" + name;
    FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) return std::string();
    const bool ok = size == 0 || std::fwrite(data, 1, size, f) == size;
    return std::fclose(f) == 0 && ok ? path : std::string();
}

}  // namespace stipple::fuzz
