// stipple-bake: glTF / OBJ / PLY / STL -> .stip asset (mesh, skin, clips, point hierarchy).
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "bake/asset_writer.h"
#include "bake/point_hierarchy.h"
#include "bake/scene_import.h"
#include "bake/scene_orientation.h"
#include "bake/vertex_normals.h"
#include "runtime/asset.h"
#include "runtime/asset_format.h"
#include "tools/cli_args.h"

namespace {

const char* kUsage =
    "usage: stipple-bake INPUT -o OUT.stip [options]\n"
    "  INPUT            glTF 2.0 (.gltf/.glb), or a static .obj/.ply/.stl mesh\n"
    "  -o, --output F   asset to write\n"
    "  --points N       points in the hierarchy (default 20000, max 20000000)\n"
    "  --seed S         random seed (default 1); same input+options+seed = same bytes\n"
    "  --jitter J       simplify: randomize range in [0, 0.75] (default 0.35, thesis §4.4.1)\n"
    "  --method M       eliminate (default: progressive sample elimination, even on any mesh)\n"
    "                   | simplify (thesis ch. 4) | relax (ch. 5 token relaxation)\n"
    "                   | random (naive baseline: one random point per polygon)\n"
    "  --normals M      flat | smooth | auto (split at sharp edges) | input (default auto)\n"
    "  --crease DEG     auto normals: dihedral angle that makes an edge sharp (default 40)\n"
    "  --double-sided M auto (glTF material.doubleSided; OBJ/PLY/STL single-sided) | on | off:\n"
    "                   points on double-sided triangles draw from both sides (default auto)\n"
    "  --up A           y | z: the input's up axis; z turns a Z-up mesh upright (+Z becomes\n"
    "                   +Y). Default y (glTF is Y-up by its spec; pass z for Z-up PLY/STL)\n"
    "  --quiet          no progress bar (shown on stderr for bakes over a second) or summary\n"
    "  -h, --help       this text\n";

struct Options {
    std::string input, output;
    long points = 20000;
    unsigned long long seed = 1;
    stipple::bake::NormalConfig normals;
    double jitter = 0.35;
    stipple::bake::HierarchyMethod method = stipple::bake::HierarchyMethod::eliminate;
    bool quiet = false;
    enum class Sides { automatic, on, off } double_sided = Sides::automatic;
    uint32_t up_axis = stipple::format::kUpY;
};

stipple::cli::Args* g_args = nullptr;  // for die() outside parse()

[[noreturn]] void die(const std::string& message) {
    g_args->die(message);
}

bool parse_long(const char* s, long lo, long hi, long* out) {
    char* end = nullptr;
    long v = std::strtol(s, &end, 10);
    if (end == s || *end != '\0' || v < lo || v > hi) return false;
    *out = v;
    return true;
}

Options parse(stipple::cli::Args& args) {
    Options o;
    std::string a;
    while (args.next(&a)) {
        auto value = [&]() { return args.value(a); };
        if (a == "-h" || a == "--help") {
            std::fputs(kUsage, stdout);
            std::exit(0);
        } else if (a == "-o" || a == "--output") {
            o.output = value();
        } else if (a == "--points") {
            if (!parse_long(value(), 1, 20000000, &o.points))
                die("--points must be an integer in [1, 20000000]");
        } else if (a == "--seed") {
            const char* s = value();
            char* end = nullptr;
            o.seed = std::strtoull(s, &end, 10);
            if (end == s || *end != '\0') die("--seed must be a non-negative integer");
        } else if (a == "--jitter") {
            o.jitter = args.number(a, value(), 0, 0.75);
        } else if (a == "--method") {
            std::string m = value();
            if (m == "simplify")
                o.method = stipple::bake::HierarchyMethod::simplify;
            else if (m == "random")
                o.method = stipple::bake::HierarchyMethod::random;
            else if (m == "relax")
                o.method = stipple::bake::HierarchyMethod::relax;
            else if (m == "eliminate")
                o.method = stipple::bake::HierarchyMethod::eliminate;
            else
                die("--method must be eliminate, simplify, relax or random, got '" + m + "'");
        } else if (a == "--normals") {
            if (!stipple::bake::parse_normal_mode(value(), &o.normals.mode))
                die("--normals must be flat, smooth, auto or input");
        } else if (a == "--crease") {
            long degrees = 0;
            if (!parse_long(value(), 0, 180, &degrees))
                die("--crease must be an integer in [0, 180]");
            o.normals.crease_degrees = float(degrees);
        } else if (a == "--double-sided") {
            std::string m = value();
            if (m == "auto")
                o.double_sided = Options::Sides::automatic;
            else if (m == "on")
                o.double_sided = Options::Sides::on;
            else if (m == "off")
                o.double_sided = Options::Sides::off;
            else
                die("--double-sided must be auto, on or off, got '" + m + "'");
        } else if (a == "--up") {
            std::string m = value();
            if (!stipple::bake::parse_up_axis(m, &o.up_axis))
                die("--up must be y or z, got '" + m + "'");
        } else if (a == "--quiet") {
            o.quiet = true;
        } else if (!a.empty() && a[0] == '-') {
            die("unknown option '" + a + "' (see --help)");
        } else if (o.input.empty()) {
            o.input = a;
        } else {
            die("more than one input given ('" + o.input + "', '" + a + "')");
        }
    }
    if (o.input.empty()) die("no input file (see --help)");
    if (o.output.empty()) die("no output file: pass -o OUT.stip");
    return o;
}

// Progress bar on stderr: silent for the first second (most bakes end sooner), then one
// line rewritten in place with the phase, a bar, the phase's percentage and the time.
struct Progress {
    std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
    bool quiet = false;
    bool shown = false;
    std::string phase;
    int last = -1;

    double seconds() const {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    void finish() {
        if (shown) std::fputc('\n', stderr);
        shown = false;
    }
};

void on_progress(const char* phase, float fraction, void* user) {
    Progress* p = static_cast<Progress*>(user);
    const double seconds = p->seconds();
    const int percent = fraction <= 0 ? 0 : (fraction >= 1 ? 100 : int(fraction * 100));
    if (p->quiet || seconds < 1.0 || (p->phase == phase && percent == p->last)) return;
    p->phase = phase;
    p->last = percent;
    p->shown = true;
    char bar[25];
    for (int i = 0; i < 24; ++i) bar[i] = i < percent * 24 / 100 ? '#' : '.';
    bar[24] = '\0';
    std::fprintf(stderr, "\r%-16s [%s] %3d%%  %6.1f s", phase, bar, percent, seconds);
    std::fflush(stderr);
}

}  // namespace

int main(int argc, char** argv) {
    using namespace stipple::bake;
    const uint16_t probe = 1;
    if (*reinterpret_cast<const uint8_t*>(&probe) != 1) die("big-endian hosts are not supported");
    stipple::cli::Args args{"stipple-bake", argc, argv};
    g_args = &args;
    Options o = parse(args);
    auto t0 = std::chrono::steady_clock::now();

    Progress progress;
    progress.quiet = o.quiet;
    RawScene scene;
    std::string error;
    if (!import_scene(o.input, &scene, &error)) die(error);
    on_progress("import", 1, &progress);
    apply_up_axis(o.up_axis, &scene);
    if (o.double_sided == Options::Sides::on) scene.double_sided.assign(scene.triangle_count(), 1);
    if (o.double_sided == Options::Sides::off) scene.double_sided.clear();
    if (!scene.animated()) orient_outward(&scene);  // glTF's winding is fixed by the spec
    assign_normals(o.normals, &scene);
    if (!o.quiet)
        for (const std::string& w : scene.warnings)
            std::fprintf(stderr, "warning: %s\n", w.c_str());

    HierarchyConfig config;
    config.point_count = uint32_t(o.points);
    config.seed = o.seed;
    config.jitter = float(o.jitter);
    config.method = o.method;
    config.progress = on_progress;
    config.progress_user = &progress;
    PointHierarchy points;
    HierarchyStats stats;
    if (!build_point_hierarchy(scene, config, &points, &stats, &error)) {
        progress.finish();
        die(o.input + ": " + error);
    }
    if (points.size() < size_t(o.points) && !o.quiet) {
        progress.finish();
        std::fprintf(stderr, "warning: only %zu points could be built\n", points.size());
    }

    on_progress("encode", 0, &progress);
    std::vector<uint8_t> bytes = encode_asset(scene, points);
    on_progress("verify", 0, &progress);
    // Read the asset back with the runtime's validating loader before writing it, so a
    // bake never leaves an asset the runtime would refuse.
    stipple::Asset check;
    stipple::LoadStatus loaded = stipple::load_asset_memory(bytes.data(), bytes.size(), &check);
    if (!loaded.ok()) {
        progress.finish();
        die(std::string("internal error: baked asset does not load: ") + loaded.message);
    }
    on_progress("write", 0, &progress);
    if (!write_asset(o.output, bytes, &error)) die(error);
    on_progress("write", 1, &progress);
    progress.finish();
    double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (!o.quiet) {
        // Point data only: the coded point stream.
        size_t point_bytes = check.section_size[stipple::kSectionPoints];
        std::printf(
            "{\"input\": \"%s\", \"output\": \"%s\", \"vertices\": %zu, \"triangles\": %zu, "
            "\"joints\": %zu, \"clips\": %zu, \"points\": %zu, \"input_points\": %u, "
            "\"subdivided_points\": %u, \"discarded_randomizations\": %u, \"legal_splits\": %u, "
            "\"slivers\": [%u, %u], "
            "\"levels\": %u, \"relax_iterations\": %u, \"neighbours_per_point\": %.2f, "
            "\"bytes\": %zu, \"up\": \"%s\", \"double_sided_triangles\": %u, "
            "\"bytes_per_point\": %.2f, \"seconds\": %.3f}\n",
            o.input.c_str(), o.output.c_str(), scene.vertex_count(), scene.triangle_count(),
            scene.joint_nodes.size(), scene.clips.size(), points.size(), stats.simplified_points,
            stats.subdivided_points, stats.discarded_randomizations, stats.legal_splits,
            stats.slivers_before_subdivision, stats.slivers_after_subdivision,
            stats.levels, stats.relax_iterations, double(points.neighbours.size()) / double(points.size()),
            bytes.size(), o.up_axis == stipple::format::kUpZ ? "z" : "y",
            check.sides.triangle_count, double(point_bytes) / double(points.size()), seconds);
    }
    return 0;
}
