// PNG and animated PNG (APNG) writers for frame dumps and golden images.
//
// Input is always tightly packed RGBA8. `bottom_up` says that row 0 of the input is the bottom
// row of the picture, as glReadPixels and OSMesa return it; the writers flip while encoding, so
// callers never need a second copy of the frame. Every function reports failure with `false` and
// a one-line message in `*error` (when `error` is not null); none of them throws or aborts.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

namespace stipple::image {

// Writes one RGBA8 image as a PNG file. `rgba` holds width * height * 4 bytes.
bool write_png(const char* path, int width, int height, const uint8_t* rgba, bool bottom_up,
               std::string* error);

// Writes an animated PNG one frame at a time (APNG 1.0 spec: acTL, fcTL, fdAT chunks).
//
// Frames are encoded and written to the file as they arrive, so memory use is one encoded frame
// whatever the frame count; finish() seeks back to patch acTL's num_frames. The first frame is
// also the PNG default image, so viewers without APNG support show it.
//
//   ApngWriter apng;
//   if (!apng.open("out.png", 30, 1, &error)) ...          // 30 frames per second
//   for (...) if (!apng.add_frame(w, h, pixels, true, &error)) ...
//   if (!apng.finish(&error)) ...
class ApngWriter {
  public:
    ApngWriter() = default;
    // Finishes the file if at least one frame was written and finish() was not called; otherwise
    // closes it (an APNG with no frames is invalid, so that file is removed).
    ~ApngWriter();
    ApngWriter(const ApngWriter&) = delete;
    ApngWriter& operator=(const ApngWriter&) = delete;

    // Creates `path` and writes the PNG signature. Frames are shown at fps_num / fps_den frames
    // per second: each fcTL gets delay_num = fps_den, delay_den = fps_num (seconds per frame), so
    // both must be in [1, 65535]. The frame size is fixed by the first add_frame().
    bool open(const char* path, int fps_num, int fps_den, std::string* error);

    // Encodes and appends one frame of width * height * 4 bytes. A frame whose size differs from
    // the first one is rejected (nothing is written and the writer stays usable); an I/O failure
    // leaves the writer failed, and every later call returns false.
    bool add_frame(int width, int height, const uint8_t* rgba, bool bottom_up, std::string* error);

    // Writes IEND, patches acTL with the frame count, and closes the file. Fails when no frame
    // was added (the file is removed) or when the writer failed earlier.
    bool finish(std::string* error);

    bool is_open() const { return file_ != nullptr; }
    int frame_count() const { return frame_count_; }

  private:
    void close_and_remove();

    std::FILE* file_ = nullptr;
    std::string path_;
    bool failed_ = false;
    int width_ = 0;
    int height_ = 0;
    uint16_t delay_num_ = 1;
    uint16_t delay_den_ = 30;
    int frame_count_ = 0;
    // Shared by fcTL and fdAT, starts at 0 (APNG spec, "Chunk Sequence Numbers").
    uint32_t sequence_number_ = 0;
    long actl_offset_ = 0;  // file offset of the acTL chunk's length field
};

}  // namespace stipple::image
