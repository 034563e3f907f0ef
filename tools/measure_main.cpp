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

#include "tools/cli_args.h"
#include "tools/frame_measure.h"

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
    "  --rows A:B   only image rows A..B-1 (0 = top row): a horizontal band\n"
    "  Prints {frame, mask, width, height, [rows,] tone, mask_pixels (inside pixels averaged),\n"
    "  mask_rows: [top, bottom], mask_columns: [left, right]} (the whole mask's extent).\n";

const char* kEvennessUsage =
    "usage: stipple-measure evenness DOTS.csv --mask MASK.png [--block N]\n"
    "  Screen-space evenness of the dots whose centre pixel is inside MASK.\n"
    "  --block N    side of the square blocks for empty-block counts (default 16)\n"
    "  Prints {dots_file, mask, block, dots_listed, dots, median_nn, mean_nn, nn_cv,\n"
    "  clump_share, blocks_inside, empty_blocks, empty_share}.\n";

const char* kCoherenceUsage =
    "usage: stipple-measure coherence DIR [--from N] [--to N] [--contours DIR2]\n"
    "  Reads DIR/dots_NNNN.csv and DIR/mask_NNNN.png for frames N..M and measures each\n"
    "  consecutive pair: persistence, appeared, vanished, pops (big dots appearing or vanishing\n"
    "  more than 4 px inside the mask), pop_share. Default: from 0 (or the first dots file) to\n"
    "  the last of the consecutive run of dots files.\n"
    "  --contours DIR2  DIR2/frame_NNNN.png are the same frames drawn with --tone 0 and\n"
    "                   silhouettes on: their line pixels (luminance < 0.5) leave the mask, so\n"
    "                   'away from silhouettes' also means away from inner contours (a leg\n"
    "                   passing in front of the other)\n"
    "  Prints {dir, from, to, pairs: [...], summary: {...}}.\n";

const char* kFramesUsage =
    "usage: stipple-measure frames DIR\n"
    "  For every DIR/frame_NNNN.png that has a DIR/mask_NNNN.png: tone, and evenness when\n"
    "  DIR/dots_NNNN.csv exists; then a coherence summary over consecutive frames with dots.\n"
    "  Prints {dir, frames: [...], summary: {...}}.\n";

// ---- JSON output -------------------------------------------------------------------------

std::string json_string(const std::string& s) {
    std::string out = "\"";
    for (unsigned char c : s) {
        switch (c) {
            case '"': out += "\\\""; break;
            case '\\': out += "\\\\"; break;
            case '\n': out += "\\n"; break;
            case '\r': out += "\\r"; break;
            case '\t': out += "\\t"; break;
            case '\b': out += "\\b"; break;
            case '\f': out += "\\f"; break;
            default:
                if (c < 0x20) {
                    char buf[8];
                    std::snprintf(buf, sizeof(buf), "\\u%04x", c);
                    out += buf;
                } else {
                    out += char(c);  // UTF-8 bytes pass through
                }
        }
    }
    return out + "\"";
}

std::string json_number(double v) {
    if (!std::isfinite(v)) return "null";
    char buf[64];
    std::snprintf(buf, sizeof(buf), "%.6g", v);
    return buf;
}

std::string json_int(long long v) { return std::to_string(v); }
std::string json_size(size_t v) { return std::to_string(v); }

// Builds one JSON object as "key": value pairs in insertion order.
struct Object {
    std::string text;
    Object& add(const char* key, const std::string& raw_value) {
        text += (text.empty() ? "" : ", ") + json_string(key) + ": " + raw_value;
        return *this;
    }
    std::string str() const { return "{" + text + "}"; }
};

// ---- helpers ----------------------------------------------------------------------------

stipple::cli::Args* g_args = nullptr;

[[noreturn]] void die(const std::string& message) { g_args->die(message); }

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

std::string evenness_fields(const m::Evenness& e, Object* o) {
    o->add("dots", json_size(e.dots))
        .add("median_nn", json_number(e.median_nn))
        .add("mean_nn", json_number(e.mean_nn))
        .add("nn_cv", json_number(e.nn_cv))
        .add("clump_share", json_number(e.clump_share))
        .add("blocks_inside", json_int(e.blocks_inside))
        .add("empty_blocks", json_int(e.empty_blocks))
        .add("empty_share", json_number(e.blocks_inside
                                            ? double(e.empty_blocks) / double(e.blocks_inside)
                                            : 0.0));
    return o->str();
}

std::string pair_json(long from, long to, size_t dots_before, size_t dots_after,
                      const m::FramePair& p) {
    Object o;
    o.add("from", json_int(from))
        .add("to", json_int(to))
        .add("dots_before", json_size(dots_before))
        .add("dots_after", json_size(dots_after))
        .add("persistence", json_number(p.persistence))
        .add("appeared", json_size(p.appeared))
        .add("vanished", json_size(p.vanished))
        .add("pops", json_size(p.pops))
        .add("pop_share", json_number(p.pop_share));
    return o.str();
}

std::string summary_json(const m::Coherence& c, const std::vector<long>& pair_start) {
    auto frame_of = [&](int pair) { return pair >= 0 ? json_int(pair_start[size_t(pair)]) : "null"; };
    Object o;
    o.add("pairs", json_size(c.pairs))
        .add("mean_persistence", json_number(c.mean_persistence))
        .add("worst_persistence", json_number(c.worst_persistence))
        .add("worst_persistence_from", frame_of(c.worst_persistence_pair))
        .add("mean_pop_share", json_number(c.mean_pop_share))
        .add("max_pop_share", json_number(c.max_pop_share))
        .add("max_pop_share_from", frame_of(c.max_pop_share_pair))
        .add("pops", json_size(c.pops));
    return o.str();
}

bool wants_help(int argc, char** argv) {
    for (int i = 2; i < argc; ++i)
        if (!std::strcmp(argv[i], "--help") || !std::strcmp(argv[i], "-h")) return true;
    return false;
}

long frame_number(stipple::cli::Args& args, const std::string& option) {
    return long(args.number(option, args.value(option), 0, 999999999));
}

// ---- commands ---------------------------------------------------------------------------

int tone(stipple::cli::Args& args) {
    std::string frame, mask_path, a;
    int row_begin = 0, row_end = -1;
    bool rows = false;
    while (args.next(&a)) {
        if (a == "--mask") {
            mask_path = args.value(a);
        } else if (a == "--rows") {
            const std::string v = args.value(a);
            const size_t colon = v.find(':');
            if (colon == std::string::npos) die("--rows takes A:B, got '" + v + "'");
            row_begin = int(args.number("--rows A", v.substr(0, colon).c_str(), 0, 1e6));
            row_end = int(args.number("--rows B", v.substr(colon + 1).c_str(), 0, 1e6));
            if (row_end < row_begin) die("--rows A:B needs A <= B, got '" + v + "'");
            rows = true;
        } else if (!a.empty() && a[0] == '-') {
            die("tone: unknown option '" + a + "' (see tone --help)");
        } else if (frame.empty()) {
            frame = a;
        } else {
            die("tone: more than one frame given ('" + frame + "', '" + a + "')");
        }
    }
    if (frame.empty()) die("tone: no frame given (see tone --help)");
    if (mask_path.empty()) die("tone: no mask given: pass --mask MASK.png");
    m::Image image;
    std::string error;
    if (!m::load_png(frame, &image, &error)) die(error);
    const m::Mask mask = load_mask(mask_path);
    require_same_size(mask, image.width, image.height, "frame '" + frame + "'");
    if (!rows) row_end = image.height;
    size_t pixels = 0;
    const double t =
        m::mean_tone_rows(image.rgba.data(), image.width, image.height, mask, row_begin, row_end,
                          &pixels);
    const m::MaskExtent e = m::mask_extent(mask);
    Object o;
    o.add("frame", json_string(frame))
        .add("mask", json_string(mask_path))
        .add("width", json_int(image.width))
        .add("height", json_int(image.height));
    if (rows) o.add("rows", "[" + json_int(row_begin) + ", " + json_int(row_end) + "]");
    o.add("tone", json_number(t))
        .add("mask_pixels", json_size(pixels))
        .add("mask_rows", "[" + json_int(e.top) + ", " + json_int(e.bottom) + "]")
        .add("mask_columns", "[" + json_int(e.left) + ", " + json_int(e.right) + "]");
    std::printf("%s\n", o.str().c_str());
    return 0;
}

int evenness(stipple::cli::Args& args) {
    std::string dots_path, mask_path, a;
    int block = 16;
    while (args.next(&a)) {
        if (a == "--mask") {
            mask_path = args.value(a);
        } else if (a == "--block") {
            block = int(args.number(a, args.value(a), 1, 4096));
        } else if (!a.empty() && a[0] == '-') {
            die("evenness: unknown option '" + a + "' (see evenness --help)");
        } else if (dots_path.empty()) {
            dots_path = a;
        } else {
            die("evenness: more than one dots file given ('" + dots_path + "', '" + a + "')");
        }
    }
    if (dots_path.empty()) die("evenness: no dots file given (see evenness --help)");
    if (mask_path.empty()) die("evenness: no mask given: pass --mask MASK.png");
    const std::vector<m::Dot> dots = load_dots(dots_path);
    const m::Mask mask = load_mask(mask_path);
    Object o;
    o.add("dots_file", json_string(dots_path))
        .add("mask", json_string(mask_path))
        .add("block", json_int(block))
        .add("dots_listed", json_size(dots.size()));
    std::printf("%s\n", evenness_fields(m::evenness(dots, mask, block), &o).c_str());
    return 0;
}

// Measures consecutive pairs of `frames` (each must have dots and a mask); a pair never spans
// a gap in the numbering.
struct CoherenceJson {
    std::string pairs;    // JSON array
    std::string summary;  // JSON object
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
                             const std::string& contours = std::string()) {
    std::vector<m::FramePair> pairs;
    std::vector<long> pair_start;
    std::string list;
    std::vector<m::Dot> before, after;
    m::Mask mask_before, mask_after;
    std::vector<float> dist_before, dist_after;
    long previous = -2;
    for (long f : frames) {
        after = load_dots(numbered(dir, "dots", f, "csv"));
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
                m::frame_pair(before, mask_before, dist_before, after, mask_after, dist_after);
            pairs.push_back(p);
            pair_start.push_back(previous);
            list += (list.empty() ? "" : ", ") +
                    pair_json(previous, f, before.size(), after.size(), p);
        }
        before.swap(after);
        mask_before = std::move(mask_after);
        dist_before.swap(dist_after);
        previous = f;
    }
    return {"[" + list + "]", summary_json(m::summarize(pairs), pair_start)};
}

int coherence(stipple::cli::Args& args) {
    std::string dir, contours, a;
    long from = -1, to = -1;
    while (args.next(&a)) {
        if (a == "--contours") {
            contours = args.value(a);
        } else if (a == "--from") {
            from = frame_number(args, a);
        } else if (a == "--to") {
            to = frame_number(args, a);
        } else if (!a.empty() && a[0] == '-') {
            die("coherence: unknown option '" + a + "' (see coherence --help)");
        } else if (dir.empty()) {
            dir = a;
        } else {
            die("coherence: more than one directory given ('" + dir + "', '" + a + "')");
        }
    }
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
    if (frames.size() < 2) die("coherence needs at least two consecutive dots files in '" + dir + "'");
    if (!contours.empty()) check_dir(contours);
    const CoherenceJson c = coherence_json(dir, frames, contours);
    std::printf("{\"dir\": %s, \"from\": %ld, \"to\": %ld, \"pairs\": %s, \"summary\": %s}\n",
                json_string(dir).c_str(), frames.front(), frames.back(), c.pairs.c_str(),
                c.summary.c_str());
    return 0;
}

int frames_command(stipple::cli::Args& args) {
    std::string dir, a;
    while (args.next(&a)) {
        if (!a.empty() && a[0] == '-') {
            die("frames: unknown option '" + a + "' (see frames --help)");
        } else if (dir.empty()) {
            dir = a;
        } else {
            die("frames: more than one directory given ('" + dir + "', '" + a + "')");
        }
    }
    if (dir.empty()) die("frames: no directory given (see frames --help)");
    check_dir(dir);
    std::string list;
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
        Object o;
        o.add("frame", json_int(f)).add("tone", json_number(t)).add("mask_pixels",
                                                                    json_size(pixels));
        const std::string dots_path = numbered(dir, "dots", f, "csv");
        if (file_exists(dots_path)) {
            Object e;
            o.add("evenness", evenness_fields(m::evenness(load_dots(dots_path), mask), &e));
            with_dots.push_back(f);
        }
        list += (list.empty() ? "" : ", ") + o.str();
    }
    if (measured == 0) die("no frame_NNNN.png with a mask_NNNN.png in '" + dir + "'");
    Object summary;
    summary.add("frames", json_size(measured))
        .add("mean_tone", json_number(tone_sum / double(measured)))
        .add("min_tone", json_number(tone_min))
        .add("max_tone", json_number(tone_max));
    // Coherence over runs of consecutive frames with dots (pairs never span a gap).
    bool has_pair = false;
    for (size_t i = 1; i < with_dots.size(); ++i) has_pair |= with_dots[i] == with_dots[i - 1] + 1;
    summary.add("coherence", has_pair ? coherence_json(dir, with_dots).summary : "null");
    std::printf("{\"dir\": %s, \"frames\": [%s], \"summary\": %s}\n", json_string(dir).c_str(),
                list.c_str(), summary.str().c_str());
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    stipple::cli::Args args{"stipple-measure", argc, argv};
    g_args = &args;
    if (argc < 2) die("no command given (see --help)");
    const std::string command = argv[1];
    if (command == "-h" || command == "--help") {
        std::fputs(kUsage, stdout);
        return 0;
    }
    struct Command {
        const char* name;
        const char* usage;
        int (*run)(stipple::cli::Args&);
    };
    const Command commands[] = {{"tone", kToneUsage, tone},
                                {"evenness", kEvennessUsage, evenness},
                                {"coherence", kCoherenceUsage, coherence},
                                {"frames", kFramesUsage, frames_command}};
    for (const Command& c : commands) {
        if (command != c.name) continue;
        if (wants_help(argc, argv)) {
            std::fputs(c.usage, stdout);
            return 0;
        }
        args.at = 1;
        return c.run(args);
    }
    die("unknown command '" + command + "' (see --help)");
}
