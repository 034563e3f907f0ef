// A generated skeleton for a static mesh (issue 9, "What it must show": the horse animated
// "through a generated skeleton"): a chain of joints along the mesh's longest axis, every
// vertex weighted linearly between its two neighbouring joints, and one looping clip, "bend",
// that sends a wave down the chain (an arch in the vertical plane and a sideways sway), so a
// scan such as assets/Horse/horse.ply moves like a swimming body. Written as glTF 2.0 with an
// embedded buffer (tools/make_bend_rig.cpp, `stipple-make-bend-rig`); bench/bench_frame_floor
// writes the same file to bake the animated horse.
#pragma once
#include <cstdint>
#include <string>

namespace stipple::tools {

struct BendRigOptions {
    uint32_t up_axis = 1;         // format::kUpY or kUpZ: the input's up axis (stood upright)
    int bones = 8;                // joints along the chain, 2..64
    float bend_degrees = 7.0f;    // per-joint amplitude of the arch (about the side axis)
    float sway_degrees = 5.0f;    // per-joint amplitude of the sway (about the up axis)
    float period_seconds = 2.0f;  // the clip's length; it loops seamlessly
    int keys = 41;                // rotation keys per joint over one period (LINEAR)
};

struct BendRigSummary {
    size_t vertices = 0, triangles = 0;
    int chain_axis = 0;  // 0 x, 1 y, 2 z (after standing upright)
    float chain_length = 0.0f;
};

// Reads `in` (any static mesh the bake reads: .obj, .ply, .stl), stands it upright, rigs it
// and writes `out` (.gltf). False with a one-line reason in *error on any failure.
bool write_bend_rig(const std::string& in, const std::string& out, const BendRigOptions& options,
                    BendRigSummary* summary, std::string* error);

}  // namespace stipple::tools
