// stipple-make-bend-rig: rigs a static mesh with a generated chain of joints along its longest
// axis and one looping clip, "bend" (tools/bend_rig.h), written as glTF for stipple-bake.
// The horse of issue 9, animated:
//   stipple-make-bend-rig assets/Horse/horse.ply horse_bend.gltf --up z
//   stipple-bake horse_bend.gltf -o horse_bend.stip --points 96966
//   stipple-play horse_bend.stip --out out/horse --clip bend
#include <string>

#include "bake/scene_orientation.h"
#include "tools/bend_rig.h"
#include "tools/cli_options.h"
#include "tools/json_line.h"

namespace {

const char* kUsage =
    "usage: stipple-make-bend-rig IN.ply|obj|stl OUT.gltf [--up y|z] [--bones N]\n"
    "    [--bend DEG] [--sway DEG] [--period S]\n"
    "  Rigs a static mesh with a chain of N joints along its longest axis (each vertex\n"
    "  weighted linearly between its two neighbouring joints) and writes it as glTF with one\n"
    "  looping clip, \"bend\": a wave down the chain that arches and sways it.\n"
    "  --up y|z       the input's up axis; z stands a Z-up mesh upright (default y)\n"
    "  --bones N      joints in the chain, 2..64 (default 8)\n"
    "  --bend DEG     per-joint arch amplitude, 0..45 degrees (default 7)\n"
    "  --sway DEG     per-joint sway amplitude, 0..45 degrees (default 5)\n"
    "  --period S     the clip's length in seconds, 0.1..60 (default 2)\n"
    "  -h, --help     this text\n";

}  // namespace

int main(int argc, char** argv) {
    std::string in, out;
    stipple::tools::BendRigOptions o;
    stipple::cli::Parser p("stipple-make-bend-rig", kUsage);
    p.positional("input mesh", &in)
        .positional("output path", &out)
        .custom("--up",
                [&](const std::string& name, const std::string& v) {
                    if (!stipple::bake::parse_up_axis(v, &o.up_axis))
                        p.fail(name + " must be y or z, got '" + v + "'");
                })
        .integer("--bones", 2, 64, &o.bones)
        .number("--bend", 0.0, 45.0, &o.bend_degrees)
        .number("--sway", 0.0, 45.0, &o.sway_degrees)
        .number("--period", 0.1, 60.0, &o.period_seconds);
    p.parse(argc, argv);
    if (in.empty() || out.empty()) p.fail("needs an input mesh and an output path (see --help)");
    stipple::tools::BendRigSummary s;
    std::string error;
    if (!stipple::tools::write_bend_rig(in, out, o, &s, &error)) {
        std::fprintf(stderr, "stipple-make-bend-rig: %s\n", error.c_str());
        return 1;
    }
    stipple::cli::Json j;
    j["output"] = out;
    j["vertices"] = s.vertices;
    j["triangles"] = s.triangles;
    j["bones"] = o.bones;
    j["chain_axis"] = std::string(1, "xyz"[s.chain_axis]);
    j["chain_length"] = stipple::cli::significant(s.chain_length, 4);
    j["clip"] = "bend";
    j["seconds"] = o.period_seconds;
    stipple::cli::print_json(j);
    return 0;
}
