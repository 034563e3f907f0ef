// Malformed input to the command-line tools ends with a one-line error and a non-zero exit,
// never a crash, a hang or a partial output file.
#include <gtest/gtest.h>

#include <fstream>

#include "tests/common/fixtures.h"

namespace {

using namespace stipple::test;

std::string temp(const char* name) {
    return scratch_path(std::string("cli_") + name);
}

void write_file(const std::string& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
}

bool exists(const std::string& path) {
    return std::ifstream(path).good();
}

// One line, prefixed with the tool's name, exit status 1 (not a signal).
void expect_one_line_error(int rc, const std::string& log, const char* tool, const char* words) {
    EXPECT_EQ(rc, 1) << log;
    EXPECT_EQ(log.rfind(std::string(tool) + ": ", 0), 0u) << log;
    EXPECT_EQ(log.find('\n'), log.size() - 1) << log;
    EXPECT_NE(log.find(words), std::string::npos) << log;
}

TEST(CliErrors, BakeRejectsAFileThatIsNotGltf) {
    std::string in = temp("not_gltf.gltf"), out = temp("not_gltf.stip");
    write_file(in, "this is not json at all\n");
    std::string log;
    int rc = run(bin("stipple-bake") + " " + in + " -o " + out, &log);
    expect_one_line_error(rc, log, "stipple-bake", "glTF");
    EXPECT_FALSE(exists(out));
}

TEST(CliErrors, BakeRejectsOutOfRangeIndices) {
    std::string in = temp("bad_indices.gltf"), out = temp("bad_indices.stip");
    // One triangle whose third index (7) points past the 3 vertices.
    write_file(in, R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],
"nodes":[{"mesh":0}],"meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],
"buffers":[{"byteLength":44,"uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAcAAAA="}],
"bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":6}],
"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},
{"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}]})");
    std::string log;
    int rc = run(bin("stipple-bake") + " " + in + " -o " + out, &log);
    expect_one_line_error(rc, log, "stipple-bake", "out of range");
    EXPECT_FALSE(exists(out));
}

TEST(CliErrors, BakeRejectsUnknownOptionsAndBadValues) {
    std::string log;
    int rc = run(bin("stipple-bake") + " x.glb -o y.stip --frobnicate", &log);
    expect_one_line_error(rc, log, "stipple-bake", "unknown option '--frobnicate'");
    rc = run(bin("stipple-bake") + " x.glb -o y.stip --points -5", &log);
    expect_one_line_error(rc, log, "stipple-bake", "--points");
    rc = run(bin("stipple-bake") + " " + temp("missing.glb") + " -o " + temp("y.stip"), &log);
    expect_one_line_error(rc, log, "stipple-bake", "missing.glb");
}

TEST(CliErrors, PlayRejectsTruncatedAndCorruptedAssets) {
    std::string asset = temp("cli_tri.stip");
    std::string obj = temp("cli_tri.obj");
    write_file(obj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
    ASSERT_EQ(run(bin("stipple-bake") + " " + obj + " -o " + asset + " --points 200 --quiet"), 0);
    std::ifstream f(asset, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    ASSERT_GT(bytes.size(), 1000u);

    std::string cut = temp("cli_cut.stip"), bad = temp("cli_bad.stip"), out = temp("cli_out");
    write_file(cut, bytes.substr(0, bytes.size() / 2));
    std::string log;
    int rc = run(bin("stipple-play") + " " + cut + " --out " + out, &log);
    expect_one_line_error(rc, log, "stipple-play", "header says");

    std::string flipped = bytes;
    flipped[flipped.size() - 5] ^= 0x10;  // inside the last section (NBRS)
    write_file(bad, flipped);
    rc = run(bin("stipple-play") + " " + bad + " --out " + out, &log);
    expect_one_line_error(rc, log, "stipple-play", "checksum mismatch");
    EXPECT_FALSE(exists(out + "/frame_0000.png"));
}

TEST(CliErrors, PlayRejectsUnknownOptionsAndOutOfRangeValues) {
    std::string log;
    int rc = run(bin("stipple-play") + " a.stip --out d --wobble", &log);
    expect_one_line_error(rc, log, "stipple-play", "unknown option '--wobble'");
    rc = run(bin("stipple-play") + " a.stip --out d --tone 1.5", &log);
    expect_one_line_error(rc, log, "stipple-play", "--tone");
    rc = run(bin("stipple-play") + " a.stip --out d --size 10x99999", &log);
    expect_one_line_error(rc, log, "stipple-play", "--size");
    rc = run(bin("stipple-play") + " a.stip --out d --zoom 0", &log);
    expect_one_line_error(rc, log, "stipple-play", "--zoom");
    rc = run(bin("stipple-play") + " " + temp("nope.stip") + " --out d", &log);
    expect_one_line_error(rc, log, "stipple-play", "cannot open");
}

TEST(CliErrors, HelpDescribesEveryTool) {
    std::string log;
    EXPECT_EQ(run(bin("stipple-bake") + " --help", &log), 0);
    EXPECT_NE(log.find("--points"), std::string::npos);
    EXPECT_EQ(run(bin("stipple-play") + " --help", &log), 0);
    EXPECT_NE(log.find("--dots-out"), std::string::npos);
}

}  // namespace
