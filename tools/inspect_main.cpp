// stipple-inspect: what is in a .stip asset, and how evenly its point hierarchy is spread.
// Prints one JSON object. With --quality, for prefixes of 1k, 4k, 16k and 64k points (the
// hierarchy's coarser levels, thesis §3.1.1), the nearest-neighbour distance of every point
// of the prefix to the rest of it, in bind pose, normalised by sqrt(area / n) — the spacing
// of an even distribution: mean, coefficient of variation and min / mean. Two bakes (methods,
// seeds) compare by these numbers instead of by eye (tools/inspect_quality.h).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "runtime/asset.h"
#include "runtime/asset_format.h"
#include "runtime/point_placement.h"
#include "tools/cli_options.h"
#include "tools/inspect_quality.h"
#include "tools/json_line.h"

namespace {

using stipple::cli::fixed;
using stipple::cli::Json;
using stipple::cli::significant;

const char* kUsage =
    "usage: stipple-inspect ASSET.stip [--quality] [--prefixes N,N,...]\n"
    "  --quality       nearest-neighbour spacing of the 1k/4k/16k/64k-point prefixes (levels)\n"
    "                  and the tone calibration (area per point / radius^2) there (default off)\n"
    "  --prefixes L    other prefix sizes for --quality, comma-separated, each in\n"
    "                  [2, 100000000] (default 1000,4000,16000,64000)\n"
    "  -h, --help      this text\n";

struct Options {
    std::string path;
    bool quality = false;
    std::vector<uint32_t> prefixes = {1000, 4000, 16000, 64000};
};

Options parse(int argc, char** argv) {
    Options o;
    stipple::cli::Parser p("stipple-inspect", kUsage);
    p.positional("asset", &o.path)
        .flag("--quality", &o.quality)
        .custom("--prefixes", [&](const std::string& name, const std::string& v) {
            o.prefixes.clear();
            size_t at = 0;
            while (at <= v.size()) {
                const size_t comma = std::min(v.find(',', at), v.size());
                o.prefixes.push_back(uint32_t(
                    p.integer_value(name + " size", v.substr(at, comma - at), 2, 100000000)));
                at = comma + 1;
            }
        });
    p.parse(argc, argv);
    if (o.path.empty()) p.fail("no asset given (see --help)");
    return o;
}

Json box(const float* x) {
    Json b;
    b["min"] = {significant(x[0], 6), significant(x[1], 6), significant(x[2], 6)};
    b["max"] = {significant(x[3], 6), significant(x[4], 6), significant(x[5], 6)};
    return b;
}

// Orientation and framing (BNDS), format version 3.
Json bounds(const stipple::Asset& a) {
    const stipple::BoundsView& b = a.bounds;
    Json clips = Json::array();
    for (uint32_t c = 0; c < a.clip_count; ++c) {
        Json clip;
        clip["name"] = a.clips[c].name;
        clip["duration"] = significant(a.clips[c].duration, 6);
        clip["box"] = box(b.clips + size_t(c) * 6);
        clips.push_back(clip);
    }
    Json out;
    out["rest"] = box(b.rest);
    out["clips"] = clips;
    return out;
}

// Paintstrokes (STRK): counts, anchors, how many sit on a hierarchy point (fur).
Json strokes(const stipple::Asset& a) {
    const stipple::StrokesView& v = a.strokes;
    uint32_t anchors[3] = {}, rooted = 0;
    for (uint32_t i = 0; i < v.stroke_count; ++i) {
        if (v.strokes[i].anchor < 3) ++anchors[v.strokes[i].anchor];
        rooted += v.strokes[i].root_point != stipple::format::kNoRootPoint;
    }
    Json j;
    j["strokes"] = v.stroke_count;
    j["control_points"] = v.point_count;
    j["max_points_per_stroke"] = v.max_points_per_stroke;
    j["surface"] = anchors[stipple::format::kAnchorSurface];
    j["object"] = anchors[stipple::format::kAnchorObject];
    j["joint"] = anchors[stipple::format::kAnchorJoint];
    j["rooted"] = rooted;
    j["bytes"] = a.section_size[stipple::kSectionStrokes];
    return j;
}

// Looks (LOOK): parts, transparent parts, coloured points, crease edges.
Json looks(const stipple::Asset& a) {
    const stipple::LooksView& v = a.looks;
    uint32_t transparent = 0;
    for (uint32_t i = 0; i < v.part_count; ++i)
        transparent += (v.part_flags[i] & stipple::kPartTransparent) ? 1 : 0;
    Json j;
    j["parts"] = v.part_count;
    j["transparent_parts"] = transparent;
    j["coloured_points"] = v.point_colour ? a.points.point_count : 0u;
    j["creases"] = v.crease_count;
    j["bytes"] = a.section_size[stipple::kSectionLooks];
    return j;
}

// Counts and sizes of the asset's sections.
Json contents(const std::string& path, const stipple::Asset& a) {
    const stipple::PointsView& p = a.points;
    size_t mesh_side = 0;
    for (int s : {stipple::kSectionMesh, stipple::kSectionSkin, stipple::kSectionClips,
                  stipple::kSectionEdges, stipple::kSectionMorph, stipple::kSectionBounds,
                  stipple::kSectionSides, stipple::kSectionStrokes, stipple::kSectionLooks})
        mesh_side += a.section_size[s];
    Json j;
    j["asset"] = path;
    j["version"] = a.version;
    j["bytes"] = a.file_size;
    Json sections = Json::object();
    for (int s = 0; s < stipple::kSectionCount; ++s)
        sections[stipple::section_name(s)] = a.section_size[s];
    j["sections"] = sections;
    j["vertices"] = a.mesh.vertex_count;
    j["triangles"] = a.mesh.triangle_count;
    j["joints"] = a.skinned ? a.skin.skeleton.joint_count : 0;
    j["clips"] = a.clip_count;
    j["morph_targets"] = a.morph.target_count;
    j["points"] = p.point_count;
    const double n = p.point_count;
    j["neighbours_per_point"] = fixed(p.point_count ? p.neighbour_count / n : 0.0, 2);
    j["bytes_per_point"] = fixed(p.point_count ? double(a.file_size - mesh_side) / n : 0.0, 2);
    j["radius_first"] = significant(p.point_count ? p.radius[0] : 0.0, 6);
    j["radius_last"] = significant(p.point_count ? p.radius[p.point_count - 1] : 0.0, 6);
    j["up"] = !a.bounds.present ? "unknown" : a.bounds.up_axis == stipple::format::kUpZ ? "z" : "y";
    j["double_sided_triangles"] = a.sides.triangle_count;
    if (a.bounds.present) j["bounds"] = bounds(a);
    if (a.strokes.stroke_count > 0) j["strokes"] = strokes(a);
    if (a.section_size[stipple::kSectionLooks] > 0) j["looks"] = looks(a);
    return j;
}

// --quality: spacing and calibration of each prefix the asset has.
void add_quality(const stipple::Asset& a, const std::vector<uint32_t>& prefixes, Json* j) {
    const stipple::PointsView& p = a.points;
    std::vector<float> pos(size_t(p.point_count) * 3), nrm(size_t(p.point_count) * 3);
    stipple::place_points(p, a.mesh.indices, a.mesh.positions, a.mesh.normals, pos.data(),
                          nrm.data());
    const double area = stipple::tools::surface_area(a.mesh);
    Json quality = Json::array();
    for (uint32_t n : prefixes) {
        if (n > p.point_count) continue;
        const stipple::tools::Spacing s = stipple::tools::nearest_neighbour_spacing(pos, n, area);
        Json q;
        q["points"] = n;
        q["nn_mean"] = fixed(s.mean, 4);
        q["nn_cv"] = fixed(s.cv, 4);
        q["nn_min_over_mean"] = fixed(s.min_over_mean, 4);
        q["density_cv"] = fixed(s.density_cv, 4);
        q["region_per_r2"] = fixed(stipple::tools::region_per_radius2(p, n, area), 3);
        quality.push_back(q);
    }
    (*j)["surface_area"] = significant(area, 6);
    (*j)["quality"] = quality;
}

}  // namespace

int main(int argc, char** argv) {
    const Options o = parse(argc, argv);
    stipple::Asset a;
    stipple::Status st = stipple::load_asset_file(o.path.c_str(), &a);
    if (!st.ok()) {
        std::fprintf(stderr, "stipple-inspect: %s: %s\n", o.path.c_str(), st.message);
        return 1;
    }
    Json j = contents(o.path, a);
    if (o.quality && a.points.point_count > 1) add_quality(a, o.prefixes, &j);
    stipple::cli::print_json(j);
    return 0;
}
