// Shared test fixtures, the one place for what several test files need:
//   paths        source(), bin(), play_checked() (stipple-play --check-gl), and the assets
//                baked once per ctest run (baked_asset());
//   processes    run() a built CLI and capture its output;
//   scratch      scratch_path(), a file in the process's scratch directory (removed at exit,
//                tests/common/scratch.h); ScratchDir, a fresh directory per test in it,
//                removed afterwards;
//   frames       Image / load_png, the paper-frame silhouette, mean darkness, dot lists;
//   GL           HeadlessGl, a headless context with the GL API loaded (link stipple_platform
//                and stipple_runtime to use it);
//   assets       load_baked(), a baked asset loaded with the runtime's loader.
// glTF files written by tests: tests/common/gltf_writer.h; anim skeletons and clips built
// by hand: tests/common/anim_builders.h.
#pragma once
#include <gtest/gtest.h>
#include <stb/stb_image.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "platform/headless_context.h"
#include "runtime/asset.h"
#include "runtime/gl_api.h"
#include "tests/common/scratch.h"

namespace stipple::test {

// ---------------------------------------------------------------------------------------
// Paths

inline std::string source(const std::string& path) {
    return std::string(STIPPLE_SOURCE_DIR) + "/" + path;
}
inline std::string bin(const std::string& name) {
    return std::string(STIPPLE_BIN_DIR) + "/" + name;
}

// stipple-play with --check-gl: the frame checks run every player through it, so a GL error
// in any pass fails them (exit 1, the pass named in the log).
inline std::string play_checked() {
    return bin("stipple-play") + " --check-gl";
}

namespace detail {
inline std::string trim(const std::string& s) {
    const size_t b = s.find_first_not_of(" \t\r\n");
    if (b == std::string::npos) return "";
    return s.substr(b, s.find_last_not_of(" \t\r\n") - b + 1);
}
// Trimmed, runs of blanks collapsed to one space (as tests/CMakeLists.txt does).
inline std::string normalise(const std::string& s) {
    std::string out;
    bool blank = false;
    for (char c : trim(s)) {
        if (c == ' ' || c == '\t') {
            blank = true;
            continue;
        }
        if (blank && !out.empty()) out += ' ';
        blank = false;
        out += c;
    }
    return out;
}
}  // namespace detail

// The asset baked from `input` (repo-relative) with `options` by the ctest fixture step
// (bake_test_assets.<name>, FIXTURES_SETUP test_assets): its path under the build tree.
// The bakes are listed in tests/test_assets.txt and tests/golden/cases.txt (first three
// columns: name | input | options); tests/CMakeLists.txt reads the same files in the same
// order. Fails the test (and returns "") when no line bakes that input with those options.
inline std::string baked_asset(const std::string& input, const std::string& options) {
    const std::string want_input = detail::normalise(input),
                      want_options = detail::normalise(options);
    for (const char* list : {"tests/test_assets.txt", "tests/golden/cases.txt"}) {
        std::ifstream f(source(list));
        std::string line;
        while (std::getline(f, line)) {
            if (line.empty() || line[0] == '#') continue;
            std::vector<std::string> fields;
            std::stringstream ss(line + "|");  // a trailing empty column (no options) is a field
            for (std::string field; std::getline(ss, field, '|');)
                fields.push_back(detail::trim(field));
            if (fields.size() < 3) continue;
            if (detail::normalise(fields[1]) == want_input &&
                detail::normalise(fields[2]) == want_options) {
                const std::string name = std::string(list).find("golden") != std::string::npos
                                             ? "golden_" + fields[0]
                                             : fields[0];
                const std::string path =
                    std::string(STIPPLE_TEST_ASSETS_DIR) + "/" + name + ".stip";
                EXPECT_TRUE(std::ifstream(path).good())
                    << path << " is missing: run the tests with ctest (its bake_test_assets."
                    << name << " step bakes it)";
                return path;
            }
        }
    }
    ADD_FAILURE() << "no baked test asset for '" << input << "' with '" << options
                  << "': add a line to tests/test_assets.txt";
    return "";
}

// ---------------------------------------------------------------------------------------
// Processes

// Runs a command line through the shell; returns its exit status, or -1 if it did not exit
// normally (a crash). Its stdout and stderr go to `log` if given.
inline int run(const std::string& command, std::string* log = nullptr) {
    static std::atomic<int> counter{0};
    const std::string log_path = scratch_path("cmd_" + std::to_string(counter++) + ".log");
    const std::string full = command + " > '" + log_path + "' 2>&1";
    const int status = std::system(full.c_str());
    if (log) {
        std::ifstream f(log_path);
        std::stringstream ss;
        ss << f.rdbuf();
        *log = ss.str();
    }
    std::remove(log_path.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// ---------------------------------------------------------------------------------------
// Scratch directories

// A fresh directory for the current test (named after it) in the process's scratch
// directory, removed when it goes out of scope. Construct it inside a test (or
// SetUpTestSuite, with a `tag`).
class ScratchDir {
  public:
    explicit ScratchDir(const std::string& tag = "") {
        std::string name = "dir";
        if (const auto* info = ::testing::UnitTest::GetInstance()->current_test_info())
            name += std::string("_") + info->test_suite_name() + "_" + info->name();
        if (!tag.empty()) name += "_" + tag;
        for (char& c : name)
            if (c == '/') c = '_';  // parameterised test names
        path_ = scratch_path(name);
        std::filesystem::remove_all(path_);
        std::filesystem::create_directories(path_);
        str_ = path_.string();
    }
    ~ScratchDir() {
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    ScratchDir(const ScratchDir&) = delete;
    ScratchDir& operator=(const ScratchDir&) = delete;

    const std::string& path() const { return str_; }
    std::string file(const std::string& name) const { return (path_ / name).string(); }

  private:
    std::filesystem::path path_;
    std::string str_;
};

// ---------------------------------------------------------------------------------------
// Frames written by stipple-play: PNGs and dot lists

struct Image {
    int width = 0, height = 0;
    std::vector<uint8_t> rgba;
    float luminance(int x, int y) const {
        const uint8_t* p = &rgba[(size_t(y) * size_t(width) + size_t(x)) * 4];
        return (0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2]) / 255.0f;
    }
};

// Needs stb_image's implementation: link stipple_image (or stipple_measure).
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

// A stipple-play --dots-out CSV (header line, then id,x,y,size).
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

// ---------------------------------------------------------------------------------------
// Headless GL and assets (link stipple_platform and stipple_runtime)

// A headless context, current on this thread, with the GL API loaded.
class HeadlessGl {
  public:
    HeadlessGl() = default;
    HeadlessGl(const HeadlessGl&) = delete;
    HeadlessGl& operator=(const HeadlessGl&) = delete;
    ~HeadlessGl() {
        if (ready_) platform::destroy_headless_context(&context_);
    }
    bool open(std::string* error, const platform::HeadlessConfig& config = {}) {
        if (ready_) return true;
        const platform::ContextStatus context =
            platform::create_headless_context(config, &context_);
        if (!context.ok()) {
            *error = context.message;
            return false;
        }
        ready_ = true;
        const Status gl = load_gl_api(platform::proc_loader(context_), &gl_);
        if (!gl.ok()) {
            *error = gl.message;
            return false;
        }
        return true;
    }
    const GlApi& gl() const { return gl_; }
    const platform::HeadlessContext& context() const { return context_; }

  private:
    platform::HeadlessContext context_;
    GlApi gl_{};
    bool ready_ = false;
};

// Loads an asset file with the runtime's loader; on failure returns false with the message.
// A framebuffer of the test's own, as an application has: RGBA8 colour and 24-bit depth
// renderbuffers, bound by create(). Deleted with the object (the context must be current).
class TestFramebuffer {
  public:
    TestFramebuffer() = default;
    TestFramebuffer(const TestFramebuffer&) = delete;
    TestFramebuffer& operator=(const TestFramebuffer&) = delete;
    ~TestFramebuffer() {
        if (!gl_) return;
        gl_->BindFramebuffer(GL_FRAMEBUFFER, 0);
        gl_->DeleteFramebuffers(1, &fbo_);
        gl_->DeleteRenderbuffers(2, rb_);
    }
    bool create(const GlApi& gl, int width, int height) {
        gl_ = &gl;
        gl.GenFramebuffers(1, &fbo_);
        gl.BindFramebuffer(GL_FRAMEBUFFER, fbo_);
        gl.GenRenderbuffers(2, rb_);
        gl.BindRenderbuffer(GL_RENDERBUFFER, rb_[0]);
        gl.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
        gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb_[0]);
        gl.BindRenderbuffer(GL_RENDERBUFFER, rb_[1]);
        gl.RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
        gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, rb_[1]);
        return gl.CheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    }
    GLuint fbo() const { return fbo_; }

  private:
    const GlApi* gl_ = nullptr;
    GLuint fbo_ = 0, rb_[2] = {};
};

inline bool load_baked(const std::string& path, Asset* out, std::string* error) {
    const Status status = load_asset_file(path.c_str(), out);
    if (!status.ok()) *error = path + ": " + status.message;
    return status.ok();
}

}  // namespace stipple::test
