// stipple-bake: glTF / OBJ / PLY / STL -> .stip asset (mesh, skin, clips, point hierarchy).
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "bake/asset_writer.h"
#include "bake/atomic_file.h"
#include "bake/fur.h"
#include "bake/particle_parents.h"
#include "bake/point_hierarchy.h"
#include "bake/scene_import.h"
#include "bake/scene_orientation.h"
#include "bake/stroke_json.h"
#include "bake/surface_looks.h"
#include "bake/vertex_normals.h"
#include "runtime/asset.h"
#include "runtime/asset_format.h"
#include "runtime/asset_limits.h"
#include "runtime/particle_transform.h"
#include "runtime/particle_tree.h"
#include "tools/bake_log.h"
#include "tools/cli_options.h"
#include "tools/json_line.h"

namespace {

using stipple::bake::HierarchyMethod;

const char* kUsage =
    "usage: stipple-bake INPUT -o OUT.stip [options]\n"
    "  INPUT            glTF 2.0 (.gltf/.glb), or a static .obj/.ply/.stl mesh\n"
    "  -o, --output F   asset to write\n"
    "  --points N       points in the hierarchy (default 20000, in [1, 20000000])\n"
    "  --seed S         random seed (default 1, in [0, 2^64 - 1]); same input+options+seed =\n"
    "                   same bytes\n"
    "  --jitter J       simplify: randomize range in [0, 0.75] (default 0.35, thesis §4.4.1)\n"
    "  --method M       eliminate (default: progressive sample elimination, even on any mesh)\n"
    "                   | simplify (thesis ch. 4) | relax (ch. 5 token relaxation)\n"
    "                   | random (naive baseline: one random point per polygon)\n"
    "  --normals M      flat | smooth | auto (split at sharp edges) | input (default auto)\n"
    "  --crease DEG     auto normals: dihedral angle that makes an edge sharp, an integer in\n"
    "                   [0, 180] (default 40)\n"
    "  --double-sided M auto (glTF material.doubleSided; OBJ/PLY/STL single-sided) | on | off:\n"
    "                   points on double-sided triangles draw from both sides (default auto)\n"
    "  --up A           y | z: the input's up axis; z turns a Z-up mesh upright (+Z becomes\n"
    "                   +Y). Default y (glTF is Y-up by its spec; pass z for Z-up PLY/STL)\n"
    "  --fur N          paintstroke fur: one hair on each of the hierarchy's first N points\n"
    "                   (coarse to fine, so a prefix is a level of detail), N in\n"
    "                   [0, 4194304]; more than --points gives one per point (default 0)\n"
    "  --fur-length L   hair length, object units, in (0, 250000] (default 3% of the\n"
    "                   bounding-box diagonal, each hair 0.85-1.15 times that)\n"
    "  --fur-radius R   hair radius at the root, in (0, 250000]; the tip is 0.2 R\n"
    "                   (default L / 25)\n"
    "  --fur-comb X,Y,Z object-space direction the hair bends toward (its projection on the\n"
    "                   surface; the tip turns by that projection's length in radians, at\n"
    "                   most 1.5), each in [-1000, 1000] (default 0,-1,0: gravity)\n"
    "  --fur-curl C     twist of the bend around the normal, radians per object unit, in\n"
    "                   [-1000000, 1000000] (default 0)\n"
    "  --strokes F      paintstrokes from a JSON file (docs/strokes.md), after any fur\n"
    "  --looks          write the LOOK section (docs/format.md): each point's material colour\n"
    "                   (glTF base colour factor times its texture and COLOR_0; PLY/OBJ\n"
    "                   vertex colours), the parts (one per material) with their\n"
    "                   transparency, and crease edges (faces meeting at more than --crease\n"
    "                   degrees). Default off: the asset has no LOOK section\n"
    "  --transparent N[,N...]  glTF materials or meshes drawn by stipples only (no fill),\n"
    "                   besides alphaMode BLEND materials; implies --looks. An unknown name\n"
    "                   is an error\n"
    "  --particles      write the PTRE section: the particle tree of view-dependent particles.\n"
    "                   With --method simplify a point's parent is the point it merged into\n"
    "                   (simplify's own merge record); otherwise the nearest point of the\n"
    "                   level above (docs/particles.md, \"Parents\"). Without it the runtime\n"
    "                   builds the nearest-point tree at load\n"
    "  --curvature      write the CURV section: each point's principal curvature direction,\n"
    "                   the orientation field of ink and two-tone strokes (docs/particles.md)\n"
    "  --occluder R     write the OCCL section: the mesh decimated to R of its triangles, in\n"
    "                   [0.001, 0.999], that the depth pass draws instead (docs/format.md)\n"
    "  --quiet          no warnings and no summary; the progress bar (on stderr, for bakes over\n"
    "                   a second) shows only when stderr is a terminal (default off)\n"
    "  -h, --help       this text\n";

struct Options {
    std::string input, output;
    long points = 20000;
    uint64_t seed = 1;
    stipple::bake::NormalConfig normals;
    double jitter = 0.35;
    HierarchyMethod method = HierarchyMethod::eliminate;
    bool quiet = false;
    enum class Sides { automatic, on, off } double_sided = Sides::automatic;
    uint32_t up_axis = stipple::format::kUpY;
    stipple::bake::FurConfig fur;
    bool fur_options = false;  // any --fur-* given
    std::string strokes;
    bool looks = false;
    bool particles = false;  // --particles: a PTRE section
    bool curvature = false;  // --curvature: a CURV section
    double occluder = 0.0;   // --occluder R: an OCCL section (0: none)
    std::vector<std::string> transparent;
};

stipple::cli::Parser g_parser("stipple-bake", kUsage);

[[noreturn]] void die(const std::string& message) {
    g_parser.fail(message);
}

// A number in (0, 250000]: fur length and radius.
float positive_length(stipple::cli::Parser& p, const std::string& name, const std::string& v) {
    const double x = p.number_value(name, v, 0, 250000);
    if (!(x > 0)) p.bad_value(name, "a number in (0, 250000]", v);
    return float(x);
}

// --fur, --fur-length, --fur-radius, --fur-comb, --fur-curl, --strokes.
void add_stroke_options(stipple::cli::Parser& p, Options* o) {
    p.integer("--fur", 0, stipple::limits::kMaxStrokes, &o->fur.count)
        .custom("--fur-length",
                [&p, o](const std::string& name, const std::string& v) {
                    o->fur.length = positive_length(p, name, v);
                    o->fur_options = true;
                })
        .custom("--fur-radius",
                [&p, o](const std::string& name, const std::string& v) {
                    o->fur.radius = positive_length(p, name, v);
                    o->fur_options = true;
                })
        .custom("--fur-comb",
                [&p, o](const std::string& name, const std::string& v) {
                    size_t at = 0;
                    for (int k = 0; k < 3; ++k) {
                        const size_t comma = k < 2 ? v.find(',', at) : v.size();
                        if (comma == std::string::npos || (k == 2 && v.find(',', at) != v.npos))
                            p.bad_value(name, "three numbers X,Y,Z", v);
                        o->fur.comb[k] = float(p.number_value(
                            name + " component", v.substr(at, comma - at), -1000, 1000));
                        at = comma + 1;
                    }
                    o->fur_options = true;
                })
        .custom("--fur-curl",
                [&p, o](const std::string& name, const std::string& v) {
                    o->fur.curl = float(p.number_value(name, v, -1e6, 1e6));
                    o->fur_options = true;
                })
        .text("--strokes", &o->strokes);
}

// The particle tree (--particles): simplify's own merge record (bake/particle_parents.h), else
// the runtime's own rule (runtime/particle_tree.h) over the points' bind-pose positions, so a
// stored tree is the one the runtime would build.
std::vector<uint32_t> particle_tree(const stipple::bake::RawScene& scene,
                                    const stipple::bake::PointHierarchy& points) {
    const size_t n = points.size();
    std::vector<float> bind(n * 3);
    for (size_t i = 0; i < n; ++i) {
        const uint32_t* t = &scene.indices[size_t(points.host_triangle[i]) * 3];
        const float u = points.bary_u[i], v = points.bary_v[i], w = 1.0f - u - v;
        for (int k = 0; k < 3; ++k)
            bind[i * 3 + k] = u * scene.positions[size_t(t[0]) * 3 + k] +
                              v * scene.positions[size_t(t[1]) * 3 + k] +
                              w * scene.positions[size_t(t[2]) * 3 + k];
    }
    if (!points.record_parent.empty())
        return stipple::bake::merge_tree_parents(points.record_parent, bind);
    std::vector<uint32_t> parent(n);
    if (!stipple::particle_parents(uint32_t(n), bind.data(), INFINITY, parent.data()).ok())
        die("out of memory for the particle tree");
    return parent;
}

// --looks, --transparent NAME[,NAME...].
void add_look_options(stipple::cli::Parser& p, Options* o) {
    p.flag("--looks", &o->looks)
        .flag("--particles", &o->particles)
        .flag("--curvature", &o->curvature)
        .number("--occluder", 0.001, 0.999, &o->occluder)
        .custom("--transparent", [&p, o](const std::string& name, const std::string& v) {
            size_t at = 0;
            while (at <= v.size()) {
                const size_t comma = std::min(v.find(',', at), v.size());
                if (comma == at) p.bad_value(name, "material or mesh names, comma-separated", v);
                o->transparent.push_back(v.substr(at, comma - at));
                at = comma + 1;
            }
        });
}

Options parse(int argc, char** argv) {
    using Sides = Options::Sides;
    Options o;
    stipple::cli::Parser& p = g_parser;
    p.positional("input", &o.input)
        .text("-o,--output", &o.output)
        .integer("--points", 1, 20000000, &o.points)
        .seed("--seed", &o.seed)
        .number("--jitter", 0, 0.75, &o.jitter)
        .choice("--method",
                {std::pair<const char*, HierarchyMethod>{"eliminate", HierarchyMethod::eliminate},
                 {"simplify", HierarchyMethod::simplify},
                 {"relax", HierarchyMethod::relax},
                 {"random", HierarchyMethod::random}},
                &o.method)
        .custom("--normals",
                [&](const std::string& name, const std::string& v) {
                    if (!stipple::bake::parse_normal_mode(v, &o.normals.mode))
                        p.bad_value(name, "flat, smooth, auto or input", v);
                })
        .custom("--crease",
                [&](const std::string& name, const std::string& v) {
                    o.normals.crease_degrees = float(p.integer_value(name, v, 0, 180));
                })
        .choice("--double-sided",
                {std::pair<const char*, Sides>{"auto", Sides::automatic},
                 {"on", Sides::on},
                 {"off", Sides::off}},
                &o.double_sided)
        .custom("--up",
                [&](const std::string& name, const std::string& v) {
                    if (!stipple::bake::parse_up_axis(v, &o.up_axis))
                        p.bad_value(name, "y or z", v);
                })
        .flag("--quiet", &o.quiet);
    add_stroke_options(p, &o);
    add_look_options(p, &o);
    p.parse(argc, argv);
    if (!o.transparent.empty()) o.looks = true;
    if (o.fur_options && o.fur.count == 0)
        die("--fur-length, --fur-radius, --fur-comb and --fur-curl need --fur N");
    if (o.input.empty()) die("no input file (see --help)");
    if (o.output.empty()) die("no output file: pass -o OUT.stip");
    return o;
}

// -o naming the input (the same path, or another name for the same file: a hard link, a
// symlink, "./x") would replace the model with the asset: refused before anything is read
// or written.
void refuse_output_over_input(const Options& o) {
    struct stat in = {}, out = {};
    const bool same = o.output == o.input ||
                      (::stat(o.input.c_str(), &in) == 0 && ::stat(o.output.c_str(), &out) == 0 &&
                       in.st_dev == out.st_dev && in.st_ino == out.st_ino);
    if (same) die("output '" + o.output + "' is the input file; pass another -o");
}

// SIGINT/SIGTERM remove the temp file an asset write holds, then end the process as the
// signal would have. SIGXFSZ (a write past `ulimit -f`) is ignored, so the write fails with
// EFBIG, the error is reported and the temp file removed.
void on_fatal_signal(int sig) {
    stipple::bake::remove_pending_temp_file();
    std::signal(sig, SIG_DFL);
    std::raise(sig);
}

void install_signal_handlers() {
    std::signal(SIGINT, on_fatal_signal);
    std::signal(SIGTERM, on_fatal_signal);
    std::signal(SIGXFSZ, SIG_IGN);
}

// Progress bar on stderr, only when stderr is a terminal (a redirected log gets no '\r'
// frames) and not --quiet: silent for the first second (most bakes end sooner), then one
// line rewritten in place with the phase, a bar, the phase's percentage and the time.
// STIPPLE_PROGRESS_DELAY (seconds, default 1) changes the silent start (tests set 0).
struct Progress {
    std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
    bool enabled = false;
    bool shown = false;
    double delay = 1.0;
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
    if (!p->enabled || seconds < p->delay || (p->phase == phase && percent == p->last)) return;
    p->phase = phase;
    p->last = percent;
    p->shown = true;
    char bar[25];
    for (int i = 0; i < 24; ++i) bar[i] = i < percent * 24 / 100 ? '#' : '.';
    bar[24] = '\0';
    std::fprintf(stderr, "\r%-16s [%s] %3d%%  %6.1f s", phase, bar, percent, seconds);
    std::fflush(stderr);
}

// The summary line on stdout (the keys scripts and tests read).
void print_summary(const Options& o, const stipple::bake::RawScene& scene,
                   const stipple::bake::PointHierarchy& points,
                   const stipple::bake::HierarchyStats& stats, const stipple::Asset& check,
                   size_t bytes, double seconds) {
    using stipple::cli::fixed;
    // Point data only: the coded point stream.
    const size_t point_bytes = check.section_size[stipple::kSectionPoints];
    const double n = double(points.size());
    stipple::cli::Json j;
    j["input"] = o.input;
    j["output"] = o.output;
    j["vertices"] = scene.vertex_count();
    j["triangles"] = scene.triangle_count();
    j["joints"] = scene.joint_nodes.size();
    j["clips"] = scene.clips.size();
    j["points"] = points.size();
    j["input_points"] = stats.simplified_points;
    j["subdivided_points"] = stats.subdivided_points;
    j["discarded_randomizations"] = stats.discarded_randomizations;
    j["legal_splits"] = stats.legal_splits;
    j["slivers"] = {stats.slivers_before_subdivision, stats.slivers_after_subdivision};
    j["levels"] = stats.levels;
    j["relax_iterations"] = stats.relax_iterations;
    j["neighbours_per_point"] = fixed(double(points.neighbours.size()) / n, 2);
    j["bytes"] = bytes;
    j["up"] = o.up_axis == stipple::format::kUpZ ? "z" : "y";
    j["double_sided_triangles"] = check.sides.triangle_count;
    j["bytes_per_point"] = fixed(double(point_bytes) / n, 2);
    if (check.section_size[stipple::kSectionLooks] > 0) {
        const stipple::LooksView& l = check.looks;
        uint32_t transparent = 0;
        for (uint32_t i = 0; i < l.part_count; ++i)
            transparent += (l.part_flags[i] & stipple::kPartTransparent) ? 1 : 0;
        j["parts"] = l.part_count;
        j["transparent_parts"] = transparent;
        j["coloured_points"] = l.point_colour ? check.points.point_count : 0u;
        j["creases"] = l.crease_count;
        j["look_bytes"] = check.section_size[stipple::kSectionLooks];
    }
    if (check.strokes.stroke_count > 0) {
        j["strokes"] = check.strokes.stroke_count;
        j["stroke_points"] = check.strokes.point_count;
        j["stroke_bytes"] = check.section_size[stipple::kSectionStrokes];
    }
    if (check.points.curvature_angle) {  // CURV: its bytes and the confident share
        uint32_t confident = 0;
        for (uint32_t i = 0; i < check.points.point_count; ++i)
            confident += check.points.curvature_confidence[i] >= stipple::kCurvatureConfident;
        j["curvature_bytes"] = check.section_size[stipple::kSectionCurvature];
        j["curvature_confident"] = fixed(confident / n, 3);
    }
    if (check.occluder_indices) {  // OCCL: triangles and the measured deviation
        j["occluder_triangles"] = check.occluder_triangle_count;
        j["occluder_deviation"] = check.occluder_deviation;
    }
    j["seconds"] = fixed(seconds, 3);
    stipple::cli::print_json(j);
}

// Imports, orients and prepares the input's normals; warnings unless --quiet.
stipple::bake::RawScene import(const Options& o) {
    using namespace stipple::bake;
    RawScene scene;
    ImportOptions options;
    options.looks = o.looks;
    options.transparent = o.transparent;
    const BakeError imported = import_scene(o.input, &scene, options);
    if (!imported.ok()) die(imported.message);
    apply_up_axis(o.up_axis, &scene);
    if (o.double_sided == Options::Sides::on) scene.double_sided.assign(scene.triangle_count(), 1);
    if (o.double_sided == Options::Sides::off) scene.double_sided.clear();
    if (!scene.animated()) orient_outward(&scene);  // glTF's winding is fixed by the spec
    assign_normals(o.normals, &scene);
    if (!o.quiet)
        for (const std::string& w : scene.warnings)
            std::fprintf(stderr, "warning: %s\n", w.c_str());
    return scene;
}

// The asset's paintstrokes: fur first (its roots follow the hierarchy), then --strokes.
stipple::bake::BakedStrokes all_strokes(const Options& o, const stipple::bake::RawScene& scene,
                                        const stipple::bake::PointHierarchy& points,
                                        const stipple::bake::BakedStrokes& explicit_strokes) {
    using namespace stipple::bake;
    BakedStrokes strokes;
    if (o.fur.count > 0) {
        const BakeError fur = bake_fur(scene, points, o.fur, &strokes);
        if (!fur.ok()) die(o.input + ": " + fur.message);
    }
    append_strokes(explicit_strokes, &strokes);
    if (strokes.points.size() > stipple::limits::kMaxStrokePoints ||
        strokes.strokes.size() > stipple::limits::kMaxStrokes)
        die("fur and --strokes together have " + std::to_string(strokes.strokes.size()) +
            " strokes and " + std::to_string(strokes.points.size()) +
            " control points, over the limits of " + std::to_string(stipple::limits::kMaxStrokes) +
            " and " + std::to_string(stipple::limits::kMaxStrokePoints));

    return strokes;
}

}  // namespace

int main(int argc, char** argv) {
    using namespace stipple::bake;
    const uint16_t probe = 1;
    if (*reinterpret_cast<const uint8_t*>(&probe) != 1) die("big-endian hosts are not supported");
    const Options o = parse(argc, argv);
    refuse_output_over_input(o);
    install_signal_handlers();
    const auto t0 = std::chrono::steady_clock::now();

    Progress progress;
    progress.enabled = !o.quiet && isatty(fileno(stderr));
    if (const char* delay = std::getenv("STIPPLE_PROGRESS_DELAY"))
        progress.delay = std::atof(delay);
    // What libraries print on std::cerr during the whole bake (OpenMesh's add_face lines),
    // summarized below, one line per distinct message.
    stipple::tools::LibraryLog log;
    const RawScene scene = import(o);
    BakedStrokes explicit_strokes;  // read before the hierarchy is built: errors come early
    if (!o.strokes.empty()) {
        const BakeError read = load_strokes_json(o.strokes, scene, &explicit_strokes);
        if (!read.ok()) die(read.message);
    }
    on_progress("import", 1, &progress);

    HierarchyConfig config;
    config.point_count = uint32_t(o.points);
    config.seed = o.seed;
    config.jitter = float(o.jitter);
    config.method = o.method;
    config.progress = on_progress;
    config.progress_user = &progress;
    PointHierarchy points;
    HierarchyStats stats;
    const BakeError built = build_point_hierarchy(scene, config, &points, &stats);
    log.stop();
    progress.finish();
    if (!built.ok()) die(o.input + ": " + built.message);
    if (!o.quiet) {
        for (const std::string& line : log.summary())
            std::fprintf(stderr, "warning: %s\n", line.c_str());
        if (points.size() < size_t(o.points))
            std::fprintf(stderr, "warning: only %zu points could be built\n", points.size());
    }

    const BakedStrokes strokes = all_strokes(o, scene, points, explicit_strokes);

    on_progress("encode", 0, &progress);
    BakedLooks looks;
    if (o.looks) looks = bake_looks(scene, points, LooksConfig{true, o.normals.crease_degrees});
    const std::vector<uint8_t> bytes =
        encode_asset(scene, points, strokes, looks,
                     o.particles ? particle_tree(scene, points) : std::vector<uint32_t>(),
                     o.curvature ? bake_curvature(scene, points) : BakedCurvature(),
                     o.occluder > 0.0 ? stipple::bake::bake_occluder(scene, o.occluder)
                                      : stipple::bake::BakedOccluder());
    on_progress("verify", 0, &progress);
    // Read the asset back with the runtime's validating loader before writing it, so a
    // bake never leaves an asset the runtime would refuse.
    stipple::Asset check;
    stipple::Status loaded = stipple::load_asset_memory(bytes.data(), bytes.size(), &check);
    if (!loaded.ok()) {
        progress.finish();
        die(std::string("internal error: baked asset does not load: ") + loaded.message);
    }
    on_progress("write", 0, &progress);
    const BakeError written = write_asset(o.output, bytes);
    if (!written.ok()) {
        progress.finish();
        die(written.message);
    }
    on_progress("write", 1, &progress);
    progress.finish();
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (!o.quiet) print_summary(o, scene, points, stats, check, bytes.size(), seconds);
    return 0;
}
