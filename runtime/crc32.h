// CRC-32 (ISO-HDLC / ITU-T V.42: the polynomial zlib, PNG and the .stip section checksums
// use). The one implementation in the project: the asset loader and writer and the PNG
// writer (tools/image_write.cpp) share it.
#pragma once
#include <cstddef>
#include <cstdint>

namespace stipple::format {

// Continues a running CRC the way zlib's crc32() does: start with 0, feed pieces in order.
uint32_t crc32(const void* data, size_t size, uint32_t crc = 0);

}  // namespace stipple::format
