// stipple-paintstroke-table: reruns GI'98 Table 1 (Neulander & van de Panne, §6) on the
// GLES 3 stroke renderer. The 27-tube cluster of bench/paintstroke_scene.h is rendered along
// its 50-frame orbit at three scales with paintstrokes of quality 2, 1, 0 and static n-gon
// extrusions (9, 5, 3 sides), each compared with a 64-gon reference render of the same frame.
// Writes the table (and a verdict per scale) into a markdown file between marker lines, and
// one cropped PNG per model and scale.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "bench/paintstroke_scene.h"
#include "platform/headless_context.h"
#include "runtime/stroke_renderer.h"
#include "tools/cli_options.h"
#include "tools/image_write.h"
#include "tools/paintstroke_oit.h"

namespace {

using namespace stipple;
using namespace stipple::bench;

const char* kUsage =
    "usage: stipple-paintstroke-table [options]\n"
    "  --out FILE      markdown file whose Table 1 section (between the lines\n"
    "                  '<!-- table1:begin -->' and '<!-- table1:end -->', appended when\n"
    "                  missing) is rewritten (default docs/paintstrokes.md)\n"
    "  --images DIR    where paintstrokes_SCALE_MODEL.png go (default docs/images;\n"
    "                  'none': no images)\n"
    "  --size WxH      image size (default 640x480)\n"
    "  --runs N        timed runs per model and scale, interleaved; the fastest is kept\n"
    "                  (default 3, 1..20)\n"
    "  --frames N      frames of the orbit drawn, 1..50 (default 50)\n"
    "  --max-mean E    reference threshold: mean absolute RGB difference from the 64-gon\n"
    "                  over pixels covered in either image, in 1/255 (default 5.0)\n"
    "  --max-bad P     reference threshold, too: percent of those pixels off by more than\n"
    "                  8/255 (default 100: no limit)\n"
    "  --oit-frames N  frames (spread over the orbit) of the compositing check: sorted\n"
    "                  segments against depth peeling, semi-transparent tubes, large and\n"
    "                  medium scale (default 10; 0: skip)\n"
    "  --tol-theta PX  paintstrokes' tol_theta (Position Constraint I; default 1)\n"
    "  --tol-z PX      paintstrokes' tol_z (Position Constraint II, radius; default 0.5)\n"
    "  -h, --help      this text\n";

struct Options {
    std::string out = "docs/paintstrokes.md", images = "docs/images";
    int width = kWidth, height = kHeight, runs = 3, frames = kFrames;
    double max_mean = 5.0, max_bad = 100.0;
    int oit_frames = 10;
    double tol_theta = 1.0, tol_z = 0.5;  // paintstroke tessellation tolerances, pixels
};

struct Model {
    std::string name;
    int quality = -1;  // paintstrokes: 0, 1, 2
    int sides = 0;     // static: the n-gon
    StaticModel mesh;
    std::unique_ptr<StrokeFrame> strokes;
};

struct Result {  // one model at one scale, summed over frames
    double total = 0, rendered = 0, vertices = 0, covered = 0;
    double abs_sum = 0, union_px = 0, bad_px = 0;
    double ms = 1e30, prep_ms = 1e30;
    double mean_error() const { return union_px > 0 ? abs_sum / union_px / 3.0 : 0.0; }
    double bad_percent() const { return union_px > 0 ? 100.0 * bad_px / union_px : 0.0; }
};

struct Runner {
    Options o;
    GlApi gl;
    StrokeRenderer renderer;
    Target target;
    Scene scene;
    std::vector<Model> models;  // the 64-gon reference last
    StaticFrame static_frame;
    const StrokeVertex* vertices = nullptr;
    const uint32_t* indices = nullptr;
    uint32_t vertex_count = 0, index_count = 0, total = 0, rendered = 0;
    View view;
};

Options parse(int argc, char** argv) {
    static stipple::cli::Parser parser("stipple-paintstroke-table", kUsage);
    Options o;
    parser.text("--out", &o.out)
        .text("--images", &o.images)
        .custom("--size",
                [&o](const std::string& name, const std::string& v) {
                    if (!stipple::cli::parse_size(v, 64, 4096, &o.width, &o.height))
                        parser.bad_value(name, "WxH with both in 64..4096", v);
                })
        .integer("--runs", 1, 20, &o.runs)
        .integer("--frames", 1, kFrames, &o.frames)
        .number("--max-mean", 0.0, 255.0, &o.max_mean)
        .number("--max-bad", 0.0, 100.0, &o.max_bad)
        .integer("--oit-frames", 0, kFrames, &o.oit_frames)
        .number("--tol-theta", 0.01, 100.0, &o.tol_theta)
        .number("--tol-z", 0.01, 100.0, &o.tol_z);
    parser.parse(argc, argv);
    return o;
}

void add_models(Runner* r) {
    for (int q = 2; q >= 0; --q) {
        Model m;
        m.name = "paintstroke-q" + std::to_string(q);
        m.quality = q;
        TessellationParams params;
        params.quality = q;
        params.tol_theta_px = float(r->o.tol_theta);
        params.tol_z_px = float(r->o.tol_z);
        m.strokes.reset(new StrokeFrame());
        stroke_frame_init(m.strokes.get(), params);
        r->models.push_back(std::move(m));
    }
    const int sides[4] = {9, 5, 3, 64};
    for (int n : sides) {
        Model m;
        m.name = n == 64 ? "reference-64gon" : "static-" + std::to_string(n) + "gon";
        m.sides = n;
        // 10 degrees between ring tangents for the static models; the reference 2.5.
        m.mesh = build_extrusion(r->scene, n, glm::radians(n == 64 ? 2.5f : 10.0f));
        r->models.push_back(std::move(m));
    }
}

bool init(Runner* r, platform::HeadlessContext* context) {
    platform::HeadlessConfig hc;
    hc.width = r->o.width;
    hc.height = r->o.height;
    const platform::ContextStatus cs = platform::create_headless_context(hc, context);
    if (!cs.ok()) {
        std::fprintf(stderr, "stipple-paintstroke-table: %s\n", cs.message.c_str());
        return false;
    }
    if (!load_gl_api(platform::proc_loader(*context), &r->gl).ok()) return false;
    r->scene = make_gi98_scene();
    add_models(r);
    uint64_t max_v = 0, max_i = 0;
    for (const Model& m : r->models) {
        max_v = std::max<uint64_t>(max_v,
                                   m.strokes ? m.strokes->bound.vertices : m.mesh.vertices.size());
        max_i =
            std::max<uint64_t>(max_i, m.strokes ? m.strokes->bound.indices : m.mesh.indices.size());
    }
    StrokeRendererConfig rc;
    rc.max_vertices = uint32_t(std::min<uint64_t>(max_v, 1u << 24));
    rc.max_indices = uint32_t(std::min<uint64_t>(max_i, 1u << 26));
    rc.check_errors = true;
    const Status st = stroke_renderer_init(&r->renderer, r->gl, rc);
    if (!st.ok()) {
        std::fprintf(stderr, "stipple-paintstroke-table: %s\n", st.message);
        return false;
    }
    return target_init(r->gl, r->o.width, r->o.height, &r->target);
}

// CPU half of a frame: tessellation and sorting, or the static model's eye-space transform
// and back-face culling.
void prepare(Runner* r, Model& m, int scale, int frame) {
    r->view = scene_view(scale, frame, r->o.width, r->o.height);
    if (m.strokes) {
        tessellate_scene(r->scene, r->view, m.strokes.get());
        const StrokeMesh& mesh = m.strokes->mesh;
        if (mesh.overflow)
            std::fprintf(stderr, "warning: %s overflowed its buffers\n", m.name.c_str());
        r->vertices = mesh.vertices;
        r->vertex_count = mesh.vertex_count;
        r->indices = m.strokes->sorted_indices.get();
        r->index_count = mesh.index_count;
        r->total = r->rendered = mesh.index_count / 3;
        return;
    }
    static_to_eye(m.mesh, r->view.view, &r->static_frame);
    r->vertices = r->static_frame.vertices.data();
    r->vertex_count = uint32_t(r->static_frame.vertices.size());
    r->indices = r->static_frame.indices.data();
    r->index_count = uint32_t(r->static_frame.indices.size());
    r->total = m.mesh.triangles;
    r->rendered = r->static_frame.rendered_triangles;
}

void draw(Runner* r) {
    target_clear(r->gl, r->target);
    StrokeLighting lighting;
    lighting.light_eye = r->view.light_eye;
    stroke_renderer_draw(&r->renderer, r->view.projection, lighting, r->vertices, r->vertex_count,
                         r->indices, r->index_count);
}

bool covered(const uint8_t* p) {
    return p[0] | p[1] | p[2];
}

void compare(const std::vector<uint8_t>& img, const std::vector<uint8_t>& ref, Result* res) {
    for (size_t i = 0; i < img.size(); i += 4) {
        const bool a = covered(&img[i]), b = covered(&ref[i]);
        res->covered += a;
        if (!a && !b) continue;
        res->union_px += 1;
        int worst = 0;
        for (int c = 0; c < 3; ++c) {
            const int d = std::abs(int(img[i + size_t(c)]) - int(ref[i + size_t(c)]));
            res->abs_sum += d;
            worst = std::max(worst, d);
        }
        res->bad_px += worst > 8;
    }
}

// The box around the covered pixels of `img` (bottom-up rows), with a margin.
void crop_box(const std::vector<uint8_t>& img, int w, int h, int box[4]) {
    int x0 = w, y0 = h, x1 = -1, y1 = -1;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (covered(&img[(size_t(y) * size_t(w) + size_t(x)) * 4])) {
                x0 = std::min(x0, x), x1 = std::max(x1, x);
                y0 = std::min(y0, y), y1 = std::max(y1, y);
            }
    if (x1 < 0) x0 = y0 = 0, x1 = w - 1, y1 = h - 1;
    box[0] = std::max(x0 - 6, 0), box[1] = std::max(y0 - 6, 0);
    box[2] = std::min(x1 + 6, w - 1), box[3] = std::min(y1 + 6, h - 1);
}

// Writes the crop of `img` (opaque), magnified `zoom` times (pixel replication).
void write_crop(const Runner& r, const std::vector<uint8_t>& img, const int box[4], int zoom,
                const std::string& path) {
    const int cw = (box[2] - box[0] + 1) * zoom, ch = (box[3] - box[1] + 1) * zoom;
    std::vector<uint8_t> out(size_t(cw) * size_t(ch) * 4);
    for (int y = 0; y < ch; ++y)
        for (int x = 0; x < cw; ++x) {
            const size_t src =
                (size_t(box[1] + y / zoom) * size_t(r.o.width) + size_t(box[0] + x / zoom)) * 4;
            uint8_t* dst = &out[(size_t(y) * size_t(cw) + size_t(x)) * 4];
            std::copy(&img[src], &img[src] + 3, dst);
            dst[3] = 255;  // the framebuffer's alpha is the blend's, not coverage
        }
    std::string error;
    if (!stipple::image::write_png(path.c_str(), cw, ch, out.data(), true, &error))
        std::fprintf(stderr, "stipple-paintstroke-table: %s\n", error.c_str());
}

// Counts and image errors of every model at `scale` (untimed); PNGs of frame 0.
void measure_scale(Runner* r, int scale, std::vector<Result>* results) {
    const size_t pixels = size_t(r->o.width) * size_t(r->o.height) * 4;
    std::vector<uint8_t> ref(pixels), img(pixels);
    Model& reference = r->models.back();
    for (int f = 0; f < r->o.frames; ++f) {
        prepare(r, reference, scale, f);
        draw(r);
        target_read(r->gl, r->target, ref.data());
        int box[4];
        if (f == 0) crop_box(ref, r->o.width, r->o.height, box);
        for (size_t m = 0; m < r->models.size(); ++m) {
            prepare(r, r->models[m], scale, f);
            draw(r);
            target_read(r->gl, r->target, img.data());
            Result& res = (*results)[m];
            res.total += r->total;
            res.rendered += r->rendered;
            res.vertices += r->vertex_count;
            compare(img, ref, &res);
            if (f == 0 && r->o.images != "none")
                write_crop(*r, img, box,
                           scale == 2   ? 3
                           : scale == 1 ? 2
                                        : 1,
                           r->o.images + "/paintstrokes_" + scale_name(scale) + "_" +
                               r->models[m].name + ".png");
        }
    }
}

double now_ms() {
    using namespace std::chrono;
    return duration<double, std::milli>(steady_clock::now().time_since_epoch()).count();
}

// One timed run of every model over the frames (models interleaved run by run); keeps the
// fastest run's ms per frame, and the CPU part (prepare) of that minimum separately.
void time_scale(Runner* r, int scale, std::vector<Result>* results) {
    for (size_t m = 0; m < r->models.size(); ++m) {  // warm-up: buffers, caches, shaders
        prepare(r, r->models[m], scale, 0);
        draw(r);
        r->gl.Finish();
    }
    for (int run = 0; run < r->o.runs; ++run) {
        for (size_t m = 0; m < r->models.size(); ++m) {
            double prep = 0;
            const double t0 = now_ms();
            for (int f = 0; f < r->o.frames; ++f) {
                const double p0 = now_ms();
                prepare(r, r->models[m], scale, f);
                prep += now_ms() - p0;
                draw(r);
                r->gl.Finish();
            }
            const double ms = (now_ms() - t0) / r->o.frames;
            Result& res = (*results)[m];
            res.ms = std::min(res.ms, ms);
            res.prep_ms = std::min(res.prep_ms, prep / r->o.frames);
        }
    }
}

std::string format(const char* f, double a = 0, double b = 0, double c = 0, double d = 0,
                   double e = 0, double g = 0, double h = 0, double i = 0) {
    char text[1024];
    std::snprintf(text, sizeof(text), f, a, b, c, d, e, g, h, i);
    return text;
}

bool acceptable(const Options& o, const Result& res) {
    return res.mean_error() <= o.max_mean && res.bad_percent() <= o.max_bad;
}

std::string table_rows(const Runner& r, const std::vector<std::vector<Result>>& results) {
    std::string t =
        "| Scale | Model | Total triangles | Rendered triangles | Vertices | Pixel area | ms / "
        "frame | "
        "CPU ms / frame | Mean error (1/255) | Pixels off > 8/255 | Within threshold |\n"
        "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---|\n";
    const double per_tube = 1.0 / (double(r.o.frames) * kTubeCount);
    for (int s = 0; s < kScales; ++s)
        for (size_t m = 0; m < r.models.size(); ++m) {
            const Result& res = results[size_t(s)][m];
            t += std::string("| ") + scale_name(s) + " | " + r.models[m].name + " | ";
            t += format("%.1f | %.1f | %.1f | %.1f | %.2f | %.2f | %.2f | %.2f%% | ",
                        res.total * per_tube, res.rendered * per_tube, res.vertices * per_tube,
                        res.covered * per_tube, res.ms, res.prep_ms, res.mean_error(),
                        res.bad_percent());
            t += m + 1 == r.models.size() ? "(reference) |\n"
                 : acceptable(r.o, res)   ? "yes |\n"
                                          : "no |\n";
        }
    return t;
}

// The cheapest paintstroke setting (quality 0, then 1, then 2) whose mean error is no worse
// than model `st`'s, or size_t(-1) when none is.
size_t matching_strokes(const std::vector<Result>& res, size_t st) {
    const size_t strokes[3] = {2, 1, 0};  // models[2] is quality 0
    for (size_t m : strokes)
        if (res[m].mean_error() <= res[st].mean_error()) return m;
    return size_t(-1);
}

// "q (error) uses Rx the triangles (Rx rendered) in A vs B ms: PASS/FAIL (why)".
std::string claim(const Runner& r, const std::vector<Result>& res, size_t m, size_t st) {
    const double tri = res[m].total / res[st].total;
    const double rend = res[m].rendered / res[st].rendered;
    const bool pass = tri <= 0.5 && res[m].ms < res[st].ms;
    std::string v = r.models[m].name +
                    format(
                        " (error %.2f) uses %.2fx its triangles (%.2fx of those rendered) in "
                        "%.2f vs %.2f ms per frame: ",
                        res[m].mean_error(), tri, rend, res[m].ms, res[st].ms);
    v += pass ? "**PASS**" : "**FAIL**";
    if (tri > 0.5) v += " (more than half the triangles)";
    if (res[m].ms >= res[st].ms) v += " (not faster)";
    return v;
}

// GI'98's claim at one scale: the paintstroke setting whose error is no worse than the best
// static model's (the coarsest within the threshold) uses at most half its triangles and is
// faster. Errors compare by the mean error.
std::string verdict(const Runner& r, int s, const std::vector<Result>& res) {
    const size_t statics[3] = {5, 4, 3};  // 3-, 5-, 9-gon: coarsest first
    size_t best = 3;
    bool found = false;
    for (size_t m : statics)
        if (!found && acceptable(r.o, res[m])) best = m, found = true;
    std::string v = std::string("- **") + scale_name(s) + "**: best static model " +
                    r.models[best].name +
                    (found ? "" : " (none is within the threshold; the finest is used)") +
                    format(" (error %.2f); ", res[best].mean_error());
    const size_t m = matching_strokes(res, best);
    if (m == size_t(-1))
        return v + "no paintstroke setting is as close to the reference: **FAIL**\n";
    return v + claim(r, res, m, best) + "\n";
}

// The same comparison against every static model, whether within the threshold or not.
std::string matrix(const Runner& r, const std::vector<std::vector<Result>>& results) {
    std::string t =
        "| Scale | Static model | Cheapest paintstroke no worse | Triangles | Rendered "
        "triangles | ms / frame | Claim |\n|---|---|---|---:|---:|---:|---|\n";
    for (int s = 0; s < kScales; ++s)
        for (size_t st = 3; st < 6; ++st) {
            const std::vector<Result>& res = results[size_t(s)];
            const size_t m = matching_strokes(res, st);
            t += std::string("| ") + scale_name(s) + " | " + r.models[st].name + " | ";
            if (m == size_t(-1)) {
                t += "none | | | | |\n";
                continue;
            }
            const double tri = res[m].total / res[st].total;
            const bool pass = tri <= 0.5 && res[m].ms < res[st].ms;
            t += r.models[m].name +
                 format(" | %.2fx | %.2fx | %.2f vs %.2f | ", tri,
                        res[m].rendered / res[st].rendered, res[m].ms, res[st].ms) +
                 (pass ? "holds" : "fails") + " |\n";
        }
    return t;
}

std::string report(const Runner& r, const std::vector<std::vector<Result>>& results) {
    std::string t = "<!-- table1:begin -->\n";
    t += format(
        "%.0f frames of the orbit at %.0fx%.0f; per tube averages (27 tubes). Rendered: "
        "static, the triangles facing the camera (culled on the CPU); paintstrokes "
        "emit only the viewer's side. Vertices: uploaded per tube. Pixel area: pixels "
        "covered / 27. ms / frame: CPU work + draw + glFinish, the fastest of %.0f "
        "interleaved runs; CPU ms: tessellation + back-to-front sort, or the static "
        "model's eye transform + cull. ",
        r.o.frames, r.o.width, r.o.height, r.o.runs);
    t += format(
        "Errors against the 64-gon reference of the same frame, over pixels covered in "
        "either image: mean absolute RGB difference (1/255) and pixels off by more "
        "than 8/255. Threshold: mean error <= %.2f (and <= %.1f%% of pixels off); 'no "
        "worse' compares mean errors. Paintstrokes: tol_theta %.2f px, tol_z %.2f px; "
        "static models: rings where the tangent turns by 10 degrees (reference: 2.5).\n\n",
        r.o.max_mean, r.o.max_bad, r.o.tol_theta, r.o.tol_z);
    t += table_rows(r, results) + "\n";
    for (int s = 0; s < kScales; ++s) t += verdict(r, s, results[size_t(s)]);
    t += "\nThe same check against each static model:\n\n" + matrix(r, results);
    return t + "<!-- table1:end -->\n";
}

// Replaces the section of `path` between the marker lines `name`:begin and `name`:end
// (which `section` holds too) with `section`; appends it when the file has no such markers.
bool splice(const std::string& path, const std::string& name, const std::string& section) {
    std::string text;
    {
        std::ifstream in(path);
        std::stringstream ss;
        ss << in.rdbuf();
        text = ss.str();
    }
    const size_t a = text.find("<!-- " + name + ":begin -->");
    const std::string end = "<!-- " + name + ":end -->\n";
    const size_t b = a == std::string::npos ? a : text.find(end, a);
    if (a != std::string::npos && b != std::string::npos)
        text.replace(a, b + end.size() - a, section);
    else
        text += (text.empty() ? "" : "\n") + section;
    std::ofstream out(path);
    out << text;
    if (!out) std::fprintf(stderr, "stipple-paintstroke-table: cannot write %s\n", path.c_str());
    return bool(out);
}

// The compositing check (tools/paintstroke_oit.h) at the large and medium scales, opacity 0.5
// (op_min; op_max 0.75), quality 2; PNGs of frame 0 of the large scale, both ways.
std::string oit_report(Runner* r) {
    std::string t = "<!-- oit:begin -->\n";
    t += format(
        "Semi-transparent tubes (op_min 0.5, op_max 0.75), paintstroke quality 2, %.0f "
        "frames per scale; differences over pixels covered in either image, in 1/255.\n\n",
        r->o.oit_frames);
    t += "| Scale | Peeled layers (mean / max) | Mean difference | Max difference | "
         "Pixels off > 8/255 | ms sorted / peeled | Without depth writes: mean / off > 8 "
         "|\n|---|---:|---:|---:|---:|---:|---:|\n";
    for (int s = 0; s < 2; ++s) {
        OitResult res;
        std::vector<uint8_t> sorted, peeled;
        if (!measure_oit(r->gl, &r->renderer, r->o.width, r->o.height, s, r->o.oit_frames, 2, 0.5f,
                         &res, &sorted, &peeled))
            return t + "(depth peeling could not be set up)\n<!-- oit:end -->\n";
        t += std::string("| ") + scale_name(s) + " | ";
        t += format("%.1f / %.0f | %.2f | %.0f | %.2f%% | %.2f / %.2f | ", res.mean_layers,
                    res.max_layers, res.abs_sum / std::max(res.covered_px, 1.0) / 3.0, res.max_diff,
                    100.0 * res.bad_px / std::max(res.covered_px, 1.0), res.sorted_ms,
                    res.peeled_ms);
        t += format("%.2f / %.2f%% |\n",
                    res.nowrite_abs_sum / std::max(res.nowrite_covered_px, 1.0) / 3.0,
                    100.0 * res.nowrite_bad_px / std::max(res.nowrite_covered_px, 1.0));
        if (s == 0 && r->o.images != "none") {
            int box[4];
            crop_box(peeled, r->o.width, r->o.height, box);
            write_crop(*r, sorted, box, 1, r->o.images + "/paintstrokes_oit_sorted.png");
            write_crop(*r, peeled, box, 1, r->o.images + "/paintstrokes_oit_peeled.png");
        }
    }
    return t + "<!-- oit:end -->\n";
}

}  // namespace

int main(int argc, char** argv) {
    Runner r;
    r.o = parse(argc, argv);
    platform::HeadlessContext context;
    if (!init(&r, &context)) return 1;
    std::vector<std::vector<Result>> results(kScales, std::vector<Result>(r.models.size()));
    for (int s = 0; s < kScales; ++s) {
        measure_scale(&r, s, &results[size_t(s)]);
        time_scale(&r, s, &results[size_t(s)]);
        std::fprintf(stderr, "scale %s done\n", scale_name(s));
    }
    const std::string table = report(r, results);
    std::fputs(table.c_str(), stdout);
    bool ok = splice(r.o.out, "table1", table);
    if (r.o.oit_frames > 0) {
        const std::string oit = oit_report(&r);
        std::fputs(oit.c_str(), stdout);
        ok = splice(r.o.out, "oit", oit) && ok;
    }
    if (r.renderer.gl_error_count)
        std::fprintf(stderr, "stipple-paintstroke-table: %u GL errors (first 0x%x)\n",
                     r.renderer.gl_error_count, r.renderer.first_gl_error);
    stroke_renderer_destroy(&r.renderer);
    target_destroy(r.gl, &r.target);
    platform::destroy_headless_context(&context);
    return ok && r.renderer.gl_error_count == 0 ? 0 : 1;
}
