// stipple-compare: golden-image check for headless frames. Compares two PNGs with a
// per-channel tolerance and a maximum fraction of failing pixels, optionally forgiving a
// one-pixel shift (a pixel passes if any pixel of the other image within the shift matches),
// prints a JSON verdict and writes a diff image on request.
#include <stb/stb_image.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "tools/cli_options.h"
#include "tools/image_write.h"
#include "tools/json_line.h"

namespace {

using stipple::cli::Json;

const char* kUsage =
    "usage: stipple-compare ACTUAL.png GOLDEN.png [options]\n"
    "  --tolerance N       per-channel absolute difference allowed, 0..255 (default 3)\n"
    "  --max-fraction F    fraction of pixels allowed to fail, 0..1 (default 0.001)\n"
    "  --shift N           a pixel passes if it matches within N pixels (default 0, max 4)\n"
    "  --diff OUT.png      write a diff image (failing pixels red over a faded golden;\n"
    "                      default none)\n"
    "  -h, --help          this text\n"
    "exit status: 0 passed, 1 failed, 2 bad usage or unreadable input\n";

struct Image {
    int w = 0, h = 0;
    std::vector<uint8_t> rgba;
    const uint8_t* at(int x, int y) const { return &rgba[(size_t(y) * size_t(w) + size_t(x)) * 4]; }
};

constexpr int kUsageStatus = 2;  // exit status: 0 passed, 1 failed, 2 bad usage

[[noreturn]] void usage_error(const std::string& message) {
    std::fprintf(stderr, "stipple-compare: %s\n", message.c_str());
    std::exit(kUsageStatus);
}

Image load(const char* path) {
    Image img;
    int channels = 0;
    uint8_t* data = stbi_load(path, &img.w, &img.h, &channels, 4);
    if (!data) usage_error(std::string("cannot read '") + path + "': " + stbi_failure_reason());
    img.rgba.assign(data, data + size_t(img.w) * size_t(img.h) * 4);
    stbi_image_free(data);
    return img;
}

int difference(const uint8_t* a, const uint8_t* b) {
    int d = 0;
    for (int c = 0; c < 4; ++c) d = std::max(d, std::abs(int(a[c]) - int(b[c])));
    return d;
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> files;
    int tolerance = 3, shift = 0;
    double max_fraction = 0.001;
    std::string diff_path;
    stipple::cli::Parser p("stipple-compare", kUsage, kUsageStatus);
    p.integer("--tolerance", 0, 255, &tolerance)
        .number("--max-fraction", 0, 1, &max_fraction)
        .integer("--shift", 0, 4, &shift)
        .text("--diff", &diff_path)
        .rest(&files);
    p.parse(argc, argv);
    if (files.size() != 2) usage_error("need ACTUAL.png and GOLDEN.png (see --help)");
    Image actual = load(files[0].c_str()), golden = load(files[1].c_str());
    if (actual.w != golden.w || actual.h != golden.h) {
        Json j;
        j["passed"] = false;
        j["reason"] = "size " + std::to_string(actual.w) + "x" + std::to_string(actual.h) +
                      " vs golden " + std::to_string(golden.w) + "x" + std::to_string(golden.h);
        stipple::cli::print_json(j);
        return 1;
    }
    size_t failing = 0;
    int max_difference = 0;
    std::vector<uint8_t> diff(golden.rgba.size());
    for (int y = 0; y < golden.h; ++y)
        for (int x = 0; x < golden.w; ++x) {
            int best = 256;
            for (int dy = -shift; dy <= shift && best > tolerance; ++dy)
                for (int dx = -shift; dx <= shift && best > tolerance; ++dx) {
                    int u = x + dx, v = y + dy;
                    if (u < 0 || v < 0 || u >= golden.w || v >= golden.h) continue;
                    best = std::min(best, difference(actual.at(x, y), golden.at(u, v)));
                }
            max_difference = std::max(max_difference, best);
            bool fail = best > tolerance;
            failing += fail;
            uint8_t* d = &diff[(size_t(y) * size_t(golden.w) + size_t(x)) * 4];
            const uint8_t* g = golden.at(x, y);
            for (int c = 0; c < 3; ++c) d[c] = fail ? (c == 0 ? 255 : 0) : uint8_t(192 + g[c] / 4);
            d[3] = 255;
        }
    const double fraction = double(failing) / (double(golden.w) * double(golden.h));
    const bool passed = fraction <= max_fraction;
    Json j;
    j["passed"] = passed;
    j["failing_pixels"] = failing;
    j["failing_fraction"] = stipple::cli::fixed(fraction, 6);
    j["max_difference"] = max_difference;
    j["tolerance"] = tolerance;
    j["max_fraction"] = stipple::cli::significant(max_fraction, 6);
    j["shift"] = shift;
    stipple::cli::print_json(j);
    std::string error;
    if (!diff_path.empty() && !stipple::image::write_png(diff_path.c_str(), golden.w, golden.h,
                                                         diff.data(), false, &error)) {
        std::fprintf(stderr, "stipple-compare: %s\n", error.c_str());
        return 2;
    }
    return passed ? 0 : 1;
}
