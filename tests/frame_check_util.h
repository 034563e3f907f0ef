// Helpers for headless frame checks: run the CLIs, read PNG frames and dot lists, and
// measure tone inside the object's silhouette.
#pragma once
#include <stb/stb_image.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace stipple::test {

inline std::string bin(const char* name) { return std::string(STIPPLE_BIN_DIR) + "/" + name; }
inline std::string source(const char* path) { return std::string(STIPPLE_SOURCE_DIR) + "/" + path; }

// Runs a command line; returns its exit status (stdout/stderr go to `log` if given).
// The log file is per process: ctest runs tests in parallel processes.
inline int run(const std::string& command, std::string* log = nullptr) {
    const std::string log_path = "/tmp/stipple_test_cmd_" + std::to_string(getpid()) + ".log";
    std::string full = command + " > " + log_path + " 2>&1";
    int status = std::system(full.c_str());
    if (log) {
        std::ifstream f(log_path);
        std::stringstream ss;
        ss << f.rdbuf();
        *log = ss.str();
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

struct Image {
    int width = 0, height = 0;
    std::vector<uint8_t> rgba;
    float luminance(int x, int y) const {
        const uint8_t* p = &rgba[(size_t(y) * size_t(width) + size_t(x)) * 4];
        return (0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2]) / 255.0f;
    }
};

inline bool load_png(const std::string& path, Image* out) {
    int channels = 0;
    uint8_t* data = stbi_load(path.c_str(), &out->width, &out->height, &channels, 4);
    if (!data) return false;
    out->rgba.assign(data, data + size_t(out->width) * size_t(out->height) * 4);
    stbi_image_free(data);
    return true;
}

// Silhouette mask from a frame rendered without dots (--tone 0) on a grey background:
// the object is the white "paper" pass.
inline std::vector<uint8_t> silhouette(const Image& paper_only) {
    std::vector<uint8_t> mask(size_t(paper_only.width) * size_t(paper_only.height));
    for (int y = 0; y < paper_only.height; ++y)
        for (int x = 0; x < paper_only.width; ++x)
            mask[size_t(y) * size_t(paper_only.width) + size_t(x)] =
                paper_only.luminance(x, y) > 0.99f;
    return mask;
}

// Mean darkness (1 - luminance) over the mask, and the mask's pixel count.
inline double mean_darkness(const Image& frame, const std::vector<uint8_t>& mask,
                            size_t* count = nullptr) {
    double sum = 0;
    size_t n = 0;
    for (int y = 0; y < frame.height; ++y)
        for (int x = 0; x < frame.width; ++x)
            if (mask[size_t(y) * size_t(frame.width) + size_t(x)]) {
                sum += 1.0 - frame.luminance(x, y);
                ++n;
            }
    if (count) *count = n;
    return n ? sum / double(n) : 0.0;
}

struct Dot {
    unsigned id;
    float x, y, size;
};

inline std::vector<Dot> load_dots(const std::string& path) {
    std::vector<Dot> dots;
    std::ifstream f(path);
    std::string line;
    std::getline(f, line);  // header
    while (std::getline(f, line)) {
        Dot d;
        if (std::sscanf(line.c_str(), "%u,%f,%f,%f", &d.id, &d.x, &d.y, &d.size) == 4)
            dots.push_back(d);
    }
    return dots;
}

}  // namespace stipple::test
