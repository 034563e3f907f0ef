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

#include "tools/image_write.h"

namespace {

const char* kUsage =
    "usage: stipple-compare ACTUAL.png GOLDEN.png [options]\n"
    "  --tolerance N       per-channel absolute difference allowed, 0..255 (default 3)\n"
    "  --max-fraction F    fraction of pixels allowed to fail, 0..1 (default 0.001)\n"
    "  --shift N           a pixel passes if it matches within N pixels (default 0, max 4)\n"
    "  --diff OUT.png      write a diff image (failing pixels red over a faded golden)\n"
    "exit status: 0 passed, 1 failed, 2 bad usage or unreadable input\n";

struct Image {
    int w = 0, h = 0;
    std::vector<uint8_t> rgba;
    const uint8_t* at(int x, int y) const { return &rgba[(size_t(y) * size_t(w) + size_t(x)) * 4]; }
};

[[noreturn]] void usage_error(const std::string& message) {
    std::fprintf(stderr, "stipple-compare: %s\n", message.c_str());
    std::exit(2);
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
    std::vector<const char*> files;
    int tolerance = 3, shift = 0;
    double max_fraction = 0.001;
    const char* diff_path = nullptr;
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        auto value = [&]() -> const char* {
            if (i + 1 >= argc) usage_error("option " + a + " needs a value");
            return argv[++i];
        };
        if (a == "-h" || a == "--help") {
            std::fputs(kUsage, stdout);
            return 0;
        } else if (a == "--tolerance") {
            tolerance = std::atoi(value());
            if (tolerance < 0 || tolerance > 255) usage_error("--tolerance must be in [0, 255]");
        } else if (a == "--max-fraction") {
            max_fraction = std::atof(value());
            if (!(max_fraction >= 0 && max_fraction <= 1))
                usage_error("--max-fraction must be in [0, 1]");
        } else if (a == "--shift") {
            shift = std::atoi(value());
            if (shift < 0 || shift > 4) usage_error("--shift must be in [0, 4]");
        } else if (a == "--diff") {
            diff_path = value();
        } else if (!a.empty() && a[0] == '-') {
            usage_error("unknown option '" + a + "' (see --help)");
        } else {
            files.push_back(argv[i]);
        }
    }
    if (files.size() != 2) usage_error("need ACTUAL.png and GOLDEN.png (see --help)");
    Image actual = load(files[0]), golden = load(files[1]);
    if (actual.w != golden.w || actual.h != golden.h) {
        std::printf("{\"passed\": false, \"reason\": \"size %dx%d vs golden %dx%d\"}\n", actual.w,
                    actual.h, golden.w, golden.h);
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
    std::printf(
        "{\"passed\": %s, \"failing_pixels\": %zu, \"failing_fraction\": %.6f, "
        "\"max_difference\": %d, \"tolerance\": %d, \"max_fraction\": %g, \"shift\": %d}\n",
        passed ? "true" : "false", failing, fraction, max_difference, tolerance, max_fraction,
        shift);
    std::string error;
    if (diff_path &&
        !stipple::image::write_png(diff_path, golden.w, golden.h, diff.data(), false, &error)) {
        std::fprintf(stderr, "stipple-compare: %s\n", error.c_str());
        return 2;
    }
    return passed ? 0 : 1;
}
