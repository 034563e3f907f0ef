#include "tools/image_write.h"

#include <stb/stb_image_write.h>

#include <cerrno>
#include <climits>
#include <cstring>
#include <vector>

#include "runtime/crc32.h"

namespace stipple::image {
namespace {

// --- Small helpers ---

constexpr uint8_t kPngSignature[8] = {137, 80, 78, 71, 13, 10, 26, 10};

bool fail(std::string* error, const std::string& message) {
    if (error) *error = message;
    return false;
}

// Read errno before building any message: allocating the message may overwrite it.
std::string errno_text(int errnum) {
    return std::strerror(errnum);
}

void put_u32(uint8_t* out, uint32_t v) {
    out[0] = static_cast<uint8_t>(v >> 24);
    out[1] = static_cast<uint8_t>(v >> 16);
    out[2] = static_cast<uint8_t>(v >> 8);
    out[3] = static_cast<uint8_t>(v);
}

void put_u16(uint8_t* out, uint16_t v) {
    out[0] = static_cast<uint8_t>(v >> 8);
    out[1] = static_cast<uint8_t>(v);
}

uint32_t get_u32(const uint8_t* in) {
    return (uint32_t{in[0]} << 24) | (uint32_t{in[1]} << 16) | (uint32_t{in[2]} << 8) |
           uint32_t{in[3]};
}

// stb encodes rows into int-sized buffers of (width * 4 + 1) * height bytes; refuse anything
// that would overflow them instead of letting stb wrap around.
bool check_size(const char* what, int width, int height, const uint8_t* rgba, std::string* error) {
    if (width <= 0 || height <= 0) {
        return fail(error, std::string(what) + ": image size " + std::to_string(width) + "x" +
                               std::to_string(height) + " is not positive");
    }
    if ((static_cast<long long>(width) * 4 + 1) * height > INT_MAX) {
        return fail(error, std::string(what) + ": image size " + std::to_string(width) + "x" +
                               std::to_string(height) + " is too large");
    }
    if (!rgba) return fail(error, std::string(what) + ": no pixel data");
    return true;
}

void append_to_vector(void* context, void* data, int size) {
    auto* out = static_cast<std::vector<uint8_t>*>(context);
    const auto* bytes = static_cast<const uint8_t*>(data);
    out->insert(out->end(), bytes, bytes + size);
}

// Encodes a complete PNG in memory. A bottom-up image is flipped by handing stb its last row and
// a negative stride (stb's row filters only ever step by the stride), which avoids both a copy
// of the frame and stbi_flip_vertically_on_write, a global that other callers may rely on.
bool encode_png(const char* what, int width, int height, const uint8_t* rgba, bool bottom_up,
                std::vector<uint8_t>* png, std::string* error) {
    if (!check_size(what, width, height, rgba, error)) return false;
    const int stride = width * 4;
    const uint8_t* first_row = bottom_up ? rgba + static_cast<size_t>(stride) * (height - 1) : rgba;
    png->clear();
    if (!stbi_write_png_to_func(append_to_vector, png, width, height, 4, first_row,
                                bottom_up ? -stride : stride) ||
        png->empty()) {
        return fail(error, std::string(what) + ": PNG encoding failed (out of memory?)");
    }
    return true;
}

// One chunk of an encoded PNG: 4-byte type and a view of its data (PNG spec §5.3).
struct Chunk {
    char type[4];
    const uint8_t* data;
    uint32_t length;
};

// Splits an encoded PNG into its chunks, checking every length against the buffer so a
// malformed encoder output is reported instead of read past.
bool parse_chunks(const std::vector<uint8_t>& png, std::vector<Chunk>* chunks, std::string* error) {
    chunks->clear();
    if (png.size() < sizeof(kPngSignature) ||
        std::memcmp(png.data(), kPngSignature, sizeof(kPngSignature)) != 0) {
        return fail(error, "apng: encoded frame has no PNG signature");
    }
    size_t pos = sizeof(kPngSignature);
    while (pos < png.size()) {
        if (png.size() - pos < 12) return fail(error, "apng: encoded frame is truncated");
        const uint32_t length = get_u32(&png[pos]);
        if (length > png.size() - pos - 12) return fail(error, "apng: encoded frame is truncated");
        Chunk chunk;
        std::memcpy(chunk.type, &png[pos + 4], 4);
        chunk.data = png.data() + pos + 8;
        chunk.length = length;
        chunks->push_back(chunk);
        pos += 12 + size_t{length};
    }
    return true;
}

bool is_type(const Chunk& chunk, const char* type) {
    return std::memcmp(chunk.type, type, 4) == 0;
}

// Writes length, type, `prefix` then `data` as one chunk's payload, and the CRC over type and
// payload (PNG spec §5.3). The prefix carries fdAT's sequence number, so IDAT data is rewrapped
// without being copied.
bool write_chunk(std::FILE* file, const char* type, const uint8_t* prefix, size_t prefix_size,
                 const uint8_t* data, size_t data_size) {
    uint8_t header[8];
    put_u32(header, static_cast<uint32_t>(prefix_size + data_size));
    std::memcpy(header + 4, type, 4);
    uint32_t crc = format::crc32(header + 4, 4);
    if (prefix_size) crc = format::crc32(prefix, prefix_size, crc);
    if (data_size) crc = format::crc32(data, data_size, crc);
    uint8_t trailer[4];
    put_u32(trailer, crc);
    return std::fwrite(header, 1, 8, file) == 8 &&
           (prefix_size == 0 || std::fwrite(prefix, 1, prefix_size, file) == prefix_size) &&
           (data_size == 0 || std::fwrite(data, 1, data_size, file) == data_size) &&
           std::fwrite(trailer, 1, 4, file) == 4;
}

// acTL: num_frames, num_plays (0 = loop forever). APNG spec, "acTL: The Animation Control
// Chunk".
bool write_actl(std::FILE* file, uint32_t num_frames) {
    uint8_t actl[8];
    put_u32(actl, num_frames);
    put_u32(actl + 4, 0);
    return write_chunk(file, "acTL", nullptr, 0, actl, sizeof(actl));
}

// fcTL: the whole canvas, shown for delay_num / delay_den seconds, then left as it is
// (APNG_DISPOSE_OP_NONE) and the next frame replaces every pixel (APNG_BLEND_OP_SOURCE), since
// each frame is a complete image. APNG spec, "fcTL: The Frame Control Chunk".
bool write_fctl(std::FILE* file, uint32_t sequence_number, int width, int height,
                uint16_t delay_num, uint16_t delay_den) {
    uint8_t fctl[26];
    put_u32(fctl + 0, sequence_number);
    put_u32(fctl + 4, static_cast<uint32_t>(width));
    put_u32(fctl + 8, static_cast<uint32_t>(height));
    put_u32(fctl + 12, 0);  // x_offset
    put_u32(fctl + 16, 0);  // y_offset
    put_u16(fctl + 20, delay_num);
    put_u16(fctl + 22, delay_den);
    fctl[24] = 0;  // dispose_op: APNG_DISPOSE_OP_NONE
    fctl[25] = 0;  // blend_op: APNG_BLEND_OP_SOURCE
    return write_chunk(file, "fcTL", nullptr, 0, fctl, sizeof(fctl));
}

}  // namespace

bool write_png(const char* path, int width, int height, const uint8_t* rgba, bool bottom_up,
               std::string* error) {
    if (!path) return fail(error, "write_png: no path");
    std::vector<uint8_t> png;
    if (!encode_png("write_png", width, height, rgba, bottom_up, &png, error)) return false;
    std::FILE* file = std::fopen(path, "wb");
    if (!file) {
        const int errnum = errno;
        return fail(error,
                    "write_png: cannot open '" + std::string(path) + "': " + errno_text(errnum));
    }
    const bool written = std::fwrite(png.data(), 1, png.size(), file) == png.size();
    const int write_errnum = errno;
    const bool closed = std::fclose(file) == 0;
    const int close_errnum = errno;
    if (written && closed) return true;
    std::remove(path);
    return fail(error, "write_png: cannot write '" + std::string(path) +
                           "': " + errno_text(written ? close_errnum : write_errnum));
}

ApngWriter::~ApngWriter() {
    if (!file_) return;
    if (frame_count_ > 0 && !failed_) {
        finish(nullptr);
    } else {
        close_and_remove();
    }
}

void ApngWriter::close_and_remove() {
    if (file_) {
        std::fclose(file_);
        file_ = nullptr;
        std::remove(path_.c_str());
    }
}

bool ApngWriter::open(const char* path, int fps_num, int fps_den, std::string* error) {
    if (file_) return fail(error, "apng: '" + path_ + "' is still open; finish() it first");
    if (!path) return fail(error, "apng: no path");
    if (fps_num < 1 || fps_num > 65535 || fps_den < 1 || fps_den > 65535) {
        // fcTL's delay_num and delay_den are 16-bit (APNG spec, fcTL).
        return fail(error, "apng: frame rate " + std::to_string(fps_num) + "/" +
                               std::to_string(fps_den) + " needs both terms in [1, 65535]");
    }
    path_ = path;
    failed_ = false;
    width_ = 0;
    height_ = 0;
    frame_count_ = 0;
    sequence_number_ = 0;
    actl_offset_ = 0;
    delay_num_ = static_cast<uint16_t>(fps_den);
    delay_den_ = static_cast<uint16_t>(fps_num);
    file_ = std::fopen(path, "wb");
    if (!file_) {
        const int errnum = errno;
        return fail(error, "apng: cannot open '" + path_ + "': " + errno_text(errnum));
    }
    if (std::fwrite(kPngSignature, 1, sizeof(kPngSignature), file_) != sizeof(kPngSignature)) {
        const int errnum = errno;
        const std::string message = "apng: cannot write '" + path_ + "': " + errno_text(errnum);
        close_and_remove();
        return fail(error, message);
    }
    return true;
}

bool ApngWriter::add_frame(int width, int height, const uint8_t* rgba, bool bottom_up,
                           std::string* error) {
    if (!file_) return fail(error, "apng: add_frame() without an open file");
    if (failed_) return fail(error, "apng: '" + path_ + "' failed earlier");
    if (frame_count_ > 0 && (width != width_ || height != height_)) {
        // Our frames always cover the whole canvas, which IHDR fixed (APNG spec, fcTL: each
        // frame region must lie inside it).
        return fail(error, "apng: frame " + std::to_string(frame_count_) + " is " +
                               std::to_string(width) + "x" + std::to_string(height) +
                               ", but the animation is " + std::to_string(width_) + "x" +
                               std::to_string(height_));
    }
    if (frame_count_ == INT_MAX) return fail(error, "apng: too many frames");

    std::vector<uint8_t> png;
    std::vector<Chunk> chunks;
    if (!encode_png("apng", width, height, rgba, bottom_up, &png, error) ||
        !parse_chunks(png, &chunks, error)) {
        return false;
    }

    const auto io_error = [&]() {
        const int errnum = errno;
        failed_ = true;
        return fail(error, "apng: cannot write '" + path_ + "': " + errno_text(errnum));
    };

    if (frame_count_ == 0) {
        // The first frame is the default image: IHDR, then acTL (which must precede IDAT), then
        // its fcTL, then its IDAT chunks unchanged (APNG spec, "Structure").
        if (chunks.empty() || !is_type(chunks.front(), "IHDR") || chunks.front().length != 13) {
            return fail(error, "apng: encoded frame does not start with IHDR");
        }
        const Chunk& ihdr = chunks.front();
        if (!write_chunk(file_, "IHDR", nullptr, 0, ihdr.data, ihdr.length)) return io_error();
        actl_offset_ = std::ftell(file_);
        if (actl_offset_ < 0) return io_error();
        // num_frames is patched by finish() once the count is known.
        if (!write_actl(file_, 0)) return io_error();
        width_ = width;
        height_ = height;
    }

    if (!write_fctl(file_, sequence_number_++, width, height, delay_num_, delay_den_)) {
        return io_error();
    }
    for (const Chunk& chunk : chunks) {
        if (!is_type(chunk, "IDAT")) continue;  // IHDR was written once; IEND comes at the end
        if (frame_count_ == 0) {
            if (!write_chunk(file_, "IDAT", nullptr, 0, chunk.data, chunk.length)) {
                return io_error();
            }
        } else {
            // Later frames: fdAT = sequence number + the IDAT payload (APNG spec, fdAT).
            uint8_t sequence[4];
            put_u32(sequence, sequence_number_++);
            if (!write_chunk(file_, "fdAT", sequence, 4, chunk.data, chunk.length)) {
                return io_error();
            }
        }
    }
    ++frame_count_;
    return true;
}

bool ApngWriter::finish(std::string* error) {
    if (!file_) return fail(error, "apng: finish() without an open file");
    if (failed_) {
        close_and_remove();
        return fail(error, "apng: '" + path_ + "' failed earlier");
    }
    if (frame_count_ == 0) {
        close_and_remove();
        return fail(error, "apng: no frames were added to '" + path_ + "'");
    }
    // IEND, then go back and give acTL the real num_frames (APNG spec, acTL: it must equal the
    // number of fcTL chunks).
    bool ok = write_chunk(file_, "IEND", nullptr, 0, nullptr, 0) &&
              std::fseek(file_, actl_offset_, SEEK_SET) == 0 &&
              write_actl(file_, static_cast<uint32_t>(frame_count_));
    int errnum = ok ? 0 : errno;
    if (std::fclose(file_) != 0 && ok) {
        ok = false;
        errnum = errno;
    }
    file_ = nullptr;
    if (!ok) {
        std::remove(path_.c_str());
        return fail(error, "apng: cannot write '" + path_ + "': " + errno_text(errnum));
    }
    return true;
}

}  // namespace stipple::image
