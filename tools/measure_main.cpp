// stipple-measure: measurements of headless stipple frames as JSON (see docs/measure.md):
// tone inside the object mask, screen-space evenness of the drawn dots, and frame-to-frame
// persistence and pops from stipple-play's dots_NNNN.csv lists.
#include <dirent.h>
#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "tools/cli_options.h"
#include "tools/frame_measure.h"
#include "tools/json_line.h"

namespace {

namespace m = stipple::measure;

const char* kUsage =
    "usage: stipple-measure COMMAND ... (each prints one JSON object; see docs/measure.md)\n"
    "  tone FRAME.png --mask MASK.png [--rows A:B]\n"
    "                       mean darkness (1 - luminance) inside the mask\n"
    "  evenness DOTS.csv --mask MASK.png [--block N]\n"
    "                       nearest-neighbour spacing CV, clump share, empty blocks\n"
    "  coherence DIR [--from N] [--to N]\n"
    "                       persistence and pops between consecutive dots_NNNN.csv in DIR\n"
    "  frames DIR           tone and evenness of every frame_NNNN.png with a mask_NNNN.png\n"
    "                       in DIR, plus a coherence summary\n"
    "A mask is white (luminance > 0.99) where the object is: stipple-play --mask-out, or a\n"
    "frame rendered with --tone 0 --background 808080 --no-silhouettes.\n"
    "`stipple-measure COMMAND --help` describes one command. Errors: one line, exit status 1.\n";

const char* kToneUsage =
    "usage: stipple-measure tone FRAME.png --mask MASK.png [--rows A:B]\n"
    "  Mean darkness 1 - luminance (Rec.709) of FRAME over the pixels inside MASK (same size).\n"
    "  --rows A:B   only image rows A..B-1 (0 = top row): a horizontal band; integers with\n"
    "               0 <= A <= B <= 1000000 (default: all rows)\n"
    "  Prints {frame, mask, width, height, [rows,] tone, mask_pixels (inside pixels averaged),\n"
    "  mask_rows: [top, bottom], mask_columns: [left, right]} (the whole mask's extent).\n";

const char* kEvennessUsage =
    "usage: stipple-measure evenness DOTS.csv --mask MASK.png [--block N]\n"
    "  Screen-space evenness of the dots whose centre pixel is inside MASK.\n"
    "  --block N    side of the square blocks for empty-block counts, in [1, 4096]\n"
    "               (default 16)\n"
    "  Prints {dots_file, mask, block, dots_listed, dots, median_nn, mean_nn, nn_cv,\n"
    "  clump_share, blocks_inside, empty_blocks, empty_share}.\n";

const char* kCoherenceUsage =
    "usage: stipple-measure coherence DIR [--from N] [--to N] [--contours DIR2] [--hidden]\n"
    "  Reads DIR/dots_NNNN.csv and DIR/mask_NNNN.png for frames N..M and measures each\n"
    "  consecutive pair: persistence, appeared, vanished, pops (big dots appearing or vanishing\n"
    "  more than 4 px inside the mask), pop_share. Default: from 0 (or the first dots file) to\n"
    "  the last of the consecutive run of dots files.\n"
    "  --from N, --to N  first and last frame, integers in [0, 999999999] (defaults above)\n"
    "  --contours DIR2  DIR2/frame_NNNN.png are the same frames drawn with --tone 0 and\n"
    "                   silhouettes on: their line pixels (luminance < 0.5) leave the mask, so\n"
    "                   'away from silhouettes' also means away from inner contours (a leg\n"
    "                   passing in front of the other)\n"
    "  --hidden         also read DIR/hidden_NNNN.csv (stipple-play --hidden-out: dots sized\n"
    "                   but hidden by the mesh in front) and tell occlusion apart: occluded,\n"
    "                   disoccluded, persistence_unoccluded, pops_unoccluded,\n"
    "                   pop_share_unoccluded per pair, and their summary (docs/measure.md)\n"
    "  Prints {dir, from, to, pairs: [...], summary: {...}}.\n";

const char* kFramesUsage =
    "usage: stipple-measure frames DIR\n"
    "  For every DIR/frame_NNNN.png that has a DIR/mask_NNNN.png: tone, and evenness when\n"
    "  DIR/dots_NNNN.csv exists; then a coherence summary over consecutive frames with dots.\n"
    "  Prints {dir, frames: [...], summary: {...}}.\n";

// ---- JSON output (tools/json_line.h) ----------------------------------------------------

using stipple::cli::Json;

// Measured values keep the 6 significant digits the tool always printed; NaN and infinity
// become null.
double number(double v) {
    return stipple::cli::significant(v, 6);
}

// ---- helpers ----------------------------------------------------------------------------

stipple::cli::Parser g_tool("stipple-measure", kUsage);

[[noreturn]] void die(const std::string& message) {
    g_tool.fail(message);
}

m::Mask load_mask(const std::string& path) {
    m::Mask mask;
    std::string error;
    if (!m::load_mask_png(path, &mask, &error)) die(error);
    return mask;
}

std::vector<m::Dot> load_dots(const std::string& path) {
    std::vector<m::Dot> dots;
    std::string error;
    if (!m::load_dots_csv(path, &dots, &error)) die(error);
    return dots;
}

bool file_exists(const std::string& path) {
    struct stat info;
    return stat(path.c_str(), &info) == 0 && S_ISREG(info.st_mode);
}

std::string numbered(const std::string& dir, const char* stem, long frame, const char* ext) {
    char name[64];
    std::snprintf(name, sizeof(name), "/%s_%04ld.%s", stem, frame, ext);
    return dir + name;
}

void check_dir(const std::string& dir) {
    struct stat info;
    if (stat(dir.c_str(), &info) != 0 || !S_ISDIR(info.st_mode))
        die("'" + dir + "' is not a directory");
}

// Frame numbers of DIR/STEM_NNNN.EXT files (four or more digits), ascending.
std::vector<long> numbered_files(const std::string& dir, const std::string& stem,
                                 const std::string& ext) {
    std::vector<long> frames;
    DIR* d = opendir(dir.c_str());
    if (!d) die("cannot list '" + dir + "'");
    const std::string prefix = stem + "_", suffix = "." + ext;
    while (dirent* e = readdir(d)) {
        const std::string name = e->d_name;
        if (name.size() < prefix.size() + 4 + suffix.size() || name.rfind(prefix, 0) != 0 ||
            name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0)
            continue;
        const std::string digits =
            name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
        if (digits.size() > 9 ||
            !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
            continue;
        const long n = std::strtol(digits.c_str(), nullptr, 10);
        if (numbered(dir, stem.c_str(), n, ext.c_str()) == dir + "/" + name) frames.push_back(n);
    }
    closedir(d);
    std::sort(frames.begin(), frames.end());
    return frames;
}

void require_same_size(const m::Mask& a, int w, int h, const std::string& what) {
    if (a.width != w || a.height != h)
        die("size mismatch: mask is " + std::to_string(a.width) + "x" + std::to_string(a.height) +
            ", " + what + " is " + std::to_string(w) + "x" + std::to_string(h));
}

void add_evenness(const m::Evenness& e, Json* o) {
    Json& j = *o;
    j["dots"] = e.dots;
    j["median_nn"] = number(e.median_nn);
    j["mean_nn"] = number(e.mean_nn);
    j["nn_cv"] = number(e.nn_cv);
    j["clump_share"] = number(e.clump_share);
    j["blocks_inside"] = e.blocks_inside;
    j["empty_blocks"] = e.empty_blocks;
    j["empty_share"] =
        number(e.blocks_inside ? double(e.empty_blocks) / double(e.blocks_inside) : 0.0);
}

Json pair_json(long from, long to, size_t dots_before, size_t dots_after, const m::FramePair& p) {
    Json j;
    j["from"] = from;
    j["to"] = to;
    j["dots_before"] = dots_before;
    j["dots_after"] = dots_after;
    j["persistence"] = number(p.persistence);
    j["appeared"] = p.appeared;
    j["vanished"] = p.vanished;
    j["pops"] = p.pops;
    j["pop_share"] = number(p.pop_share);
    if (p.occlusion_known) {
        j["occluded"] = p.occluded;
        j["disoccluded"] = p.disoccluded;
        j["persistence_unoccluded"] = number(p.persistence_unoccluded);
        j["pops_unoccluded"] = p.pops_unoccluded;
        j["pop_share_unoccluded"] = number(p.pop_share_unoccluded);
    }
    return j;
}

Json summary_json(const m::Coherence& c, const std::vector<long>& pair_start) {
    auto frame_of = [&](int pair) { return pair >= 0 ? Json(pair_start[size_t(pair)]) : Json(); };
    Json j;
    j["pairs"] = c.pairs;
    j["mean_persistence"] = number(c.mean_persistence);
    j["worst_persistence"] = number(c.worst_persistence);
    j["worst_persistence_from"] = frame_of(c.worst_persistence_pair);
    j["mean_pop_share"] = number(c.mean_pop_share);
    j["max_pop_share"] = number(c.max_pop_share);
    j["max_pop_share_from"] = frame_of(c.max_pop_share_pair);
    j["pops"] = c.pops;
    if (c.occlusion_known) {
        j["occluded"] = c.occluded;
        j["disoccluded"] = c.disoccluded;
        j["mean_persistence_unoccluded"] = number(c.mean_persistence_unoccluded);
        j["worst_persistence_unoccluded"] = number(c.worst_persistence_unoccluded);
        j["worst_persistence_unoccluded_from"] = frame_of(c.worst_persistence_unoccluded_pair);
        j["mean_pop_share_unoccluded"] = number(c.mean_pop_share_unoccluded);
        j["max_pop_share_unoccluded"] = number(c.max_pop_share_unoccluded);
        j["max_pop_share_unoccluded_from"] = frame_of(c.max_pop_share_unoccluded_pair);
        j["pops_unoccluded"] = c.pops_unoccluded;
    }
    return j;
}

// ---- commands ---------------------------------------------------------------------------

constexpr int kMaxFrameNumber = 999999999;

int tone(int argc, char** argv) {
    std::string frame, mask_path;
    int row_begin = 0, row_end = -1;
    bool rows = false;
    stipple::cli::Parser p("stipple-measure", kToneUsage);
    p.command("tone")
        .positional("frame", &frame)
        .text("--mask", &mask_path)
        .custom("--rows", [&](const std::string& name, const std::string& v) {
            const size_t colon = v.find(':');
            if (colon == std::string::npos) p.bad_value(name, "A:B", v);
            row_begin = int(p.integer_value(name + " A", v.substr(0, colon), 0, 1000000));
            row_end = int(p.integer_value(name + " B", v.substr(colon + 1), 0, 1000000));
            if (row_end < row_begin) die("--rows A:B needs A <= B, got '" + v + "'");
            rows = true;
        });
    p.parse(argc, argv, 2);
    if (frame.empty()) die("tone: no frame given (see tone --help)");
    if (mask_path.empty()) die("tone: no mask given: pass --mask MASK.png");
    m::Image image;
    std::string error;
    if (!m::load_png(frame, &image, &error)) die(error);
    const m::Mask mask = load_mask(mask_path);
    require_same_size(mask, image.width, image.height, "frame '" + frame + "'");
    if (!rows) row_end = image.height;
    size_t pixels = 0;
    const double t = m::mean_tone_rows(image.rgba.data(), image.width, image.height, mask,
                                       row_begin, row_end, &pixels);
    const m::MaskExtent e = m::mask_extent(mask);
    Json o;
    o["frame"] = frame;
    o["mask"] = mask_path;
    o["width"] = image.width;
    o["height"] = image.height;
    if (rows) o["rows"] = {row_begin, row_end};
    o["tone"] = number(t);
    o["mask_pixels"] = pixels;
    o["mask_rows"] = {e.top, e.bottom};
    o["mask_columns"] = {e.left, e.right};
    stipple::cli::print_json(o);
    return 0;
}

int evenness(int argc, char** argv) {
    std::string dots_path, mask_path;
    int block = 16;
    stipple::cli::Parser p("stipple-measure", kEvennessUsage);
    p.command("evenness")
        .positional("dots file", &dots_path)
        .text("--mask", &mask_path)
        .integer("--block", 1, 4096, &block);
    p.parse(argc, argv, 2);
    if (dots_path.empty()) die("evenness: no dots file given (see evenness --help)");
    if (mask_path.empty()) die("evenness: no mask given: pass --mask MASK.png");
    const std::vector<m::Dot> dots = load_dots(dots_path);
    const m::Mask mask = load_mask(mask_path);
    Json o;
    o["dots_file"] = dots_path;
    o["mask"] = mask_path;
    o["block"] = block;
    o["dots_listed"] = dots.size();
    add_evenness(m::evenness(dots, mask, block), &o);
    stipple::cli::print_json(o);
    return 0;
}

// Measures consecutive pairs of `frames` (each must have dots and a mask); a pair never spans
// a gap in the numbering.
struct CoherenceJson {
    Json pairs = Json::array();
    Json summary;
};

// Removes the silhouette line pixels of `lines` (a --tone 0 frame with silhouettes) from `mask`.
void remove_contours(const std::string& lines_path, m::Mask* mask) {
    m::Image lines;
    std::string error;
    if (!m::load_png(lines_path, &lines, &error)) die(error);
    if (lines.width != mask->width || lines.height != mask->height)
        die("size mismatch: '" + lines_path + "' and its mask differ in size");
    for (size_t i = 0; i < mask->inside.size(); ++i)
        if (m::luminance(&lines.rgba[i * 4]) < 0.5) mask->inside[i] = 0;
}

CoherenceJson coherence_json(const std::string& dir, const std::vector<long>& frames,
                             const std::string& contours = std::string(), bool hidden = false) {
    std::vector<m::FramePair> pairs;
    std::vector<long> pair_start;
    Json list = Json::array();
    std::vector<m::Dot> before, after;
    m::Mask mask_before, mask_after;
    std::vector<float> dist_before, dist_after;
    std::vector<m::Dot> hidden_before, hidden_after;  // --hidden
    long previous = -2;
    for (long f : frames) {
        after = load_dots(numbered(dir, "dots", f, "csv"));
        if (hidden) {
            const std::string hidden_path = numbered(dir, "hidden", f, "csv");
            if (!file_exists(hidden_path)) die("missing hidden dots file '" + hidden_path + "'");
            hidden_after = load_dots(hidden_path);
        }
        const std::string mask_path = numbered(dir, "mask", f, "png");
        if (!file_exists(mask_path)) die("missing mask '" + mask_path + "'");
        mask_after = load_mask(mask_path);
        if (!contours.empty()) remove_contours(numbered(contours, "frame", f, "png"), &mask_after);
        dist_after = m::distance_to_outside(mask_after);
        if (previous == f - 1) {
            if (mask_before.width != mask_after.width || mask_before.height != mask_after.height)
                die("size mismatch: masks of frames " + std::to_string(previous) + " and " +
                    std::to_string(f) + " differ in size");
            const m::FramePair p =
                hidden ? m::frame_pair(before, mask_before, dist_before, hidden_before, after,
                                       mask_after, dist_after, hidden_after)
                       : m::frame_pair(before, mask_before, dist_before, after, mask_after,
                                       dist_after);
            pairs.push_back(p);
            pair_start.push_back(previous);
            list.push_back(pair_json(previous, f, before.size(), after.size(), p));
        }
        before.swap(after);
        hidden_before.swap(hidden_after);
        mask_before = std::move(mask_after);
        dist_before.swap(dist_after);
        previous = f;
    }
    return {list, summary_json(m::summarize(pairs), pair_start)};
}

int coherence(int argc, char** argv) {
    std::string dir, contours;
    long from = -1, to = -1;
    bool hidden = false;
    stipple::cli::Parser p("stipple-measure", kCoherenceUsage);
    p.command("coherence")
        .positional("directory", &dir)
        .text("--contours", &contours)
        .flag("--hidden", &hidden)
        .integer("--from", 0, kMaxFrameNumber, &from)
        .integer("--to", 0, kMaxFrameNumber, &to);
    p.parse(argc, argv, 2);
    if (dir.empty()) die("coherence: no directory given (see coherence --help)");
    check_dir(dir);
    if (from < 0) {
        const std::vector<long> all = numbered_files(dir, "dots", "csv");
        if (all.empty()) die("no dots_NNNN.csv in '" + dir + "'");
        from = all.front();
    }
    if (to >= 0 && to <= from) die("coherence: --to must be greater than --from");
    std::vector<long> frames;
    for (long f = from; to < 0 || f <= to; ++f) {
        const std::string path = numbered(dir, "dots", f, "csv");
        if (!file_exists(path)) {
            if (to >= 0) die("missing dots file '" + path + "'");
            break;
        }
        frames.push_back(f);
    }
    if (frames.size() < 2)
        die("coherence needs at least two consecutive dots files in '" + dir + "'");
    if (!contours.empty()) check_dir(contours);
    const CoherenceJson c = coherence_json(dir, frames, contours, hidden);
    Json o;
    o["dir"] = dir;
    o["from"] = frames.front();
    o["to"] = frames.back();
    o["pairs"] = c.pairs;
    o["summary"] = c.summary;
    stipple::cli::print_json(o);
    return 0;
}

int frames_command(int argc, char** argv) {
    std::string dir;
    stipple::cli::Parser p("stipple-measure", kFramesUsage);
    p.command("frames").positional("directory", &dir);
    p.parse(argc, argv, 2);
    if (dir.empty()) die("frames: no directory given (see frames --help)");
    check_dir(dir);
    Json list = Json::array();
    std::vector<long> with_dots;
    double tone_sum = 0, tone_min = 0, tone_max = 0;
    size_t measured = 0;
    for (long f : numbered_files(dir, "frame", "png")) {
        const std::string mask_path = numbered(dir, "mask", f, "png");
        if (!file_exists(mask_path)) continue;
        const std::string frame_path = numbered(dir, "frame", f, "png");
        m::Image image;
        std::string error;
        if (!m::load_png(frame_path, &image, &error)) die(error);
        const m::Mask mask = load_mask(mask_path);
        require_same_size(mask, image.width, image.height, "frame '" + frame_path + "'");
        size_t pixels = 0;
        const double t = m::mean_tone(image.rgba.data(), image.width, image.height, mask, &pixels);
        tone_sum += t;
        tone_min = measured ? std::min(tone_min, t) : t;
        tone_max = measured ? std::max(tone_max, t) : t;
        ++measured;
        Json o;
        o["frame"] = f;
        o["tone"] = number(t);
        o["mask_pixels"] = pixels;
        const std::string dots_path = numbered(dir, "dots", f, "csv");
        if (file_exists(dots_path)) {
            Json e;
            add_evenness(m::evenness(load_dots(dots_path), mask), &e);
            o["evenness"] = e;
            with_dots.push_back(f);
        }
        list.push_back(o);
    }
    if (measured == 0) die("no frame_NNNN.png with a mask_NNNN.png in '" + dir + "'");
    Json summary;
    summary["frames"] = measured;
    summary["mean_tone"] = number(tone_sum / double(measured));
    summary["min_tone"] = number(tone_min);
    summary["max_tone"] = number(tone_max);
    // Coherence over runs of consecutive frames with dots (pairs never span a gap).
    bool has_pair = false;
    for (size_t i = 1; i < with_dots.size(); ++i) has_pair |= with_dots[i] == with_dots[i - 1] + 1;
    summary["coherence"] = has_pair ? coherence_json(dir, with_dots).summary : Json();
    Json out;
    out["dir"] = dir;
    out["frames"] = list;
    out["summary"] = summary;
    stipple::cli::print_json(out);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) die("no command given (see --help)");
    const std::string command = argv[1];
    if (command == "-h" || command == "--help") {
        std::fputs(kUsage, stdout);
        return 0;
    }
    struct Command {
        const char* name;
        int (*run)(int, char**);
    };
    const Command commands[] = {{"tone", tone},
                                {"evenness", evenness},
                                {"coherence", coherence},
                                {"frames", frames_command}};
    for (const Command& c : commands)
        if (command == c.name) return c.run(argc, argv);
    die("unknown command '" + command + "' (see --help)");
}
