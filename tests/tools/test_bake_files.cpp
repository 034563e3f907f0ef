// stipple-bake's file handling against hostile input: glTF URIs confined to the model's
// folder, only regular files read, the output written through a unique temp file that no
// failure or signal leaves behind, and an output never written over the input.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/common/fixtures.h"

namespace {

using namespace stipple::test;
namespace fs = std::filesystem;

std::string read_text(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

void write_text(const std::string& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
}

// One triangle whose buffer 0 is the external file `uri` (36 bytes: three float positions).
void write_uri_gltf(const std::string& path, const std::string& uri,
                    const std::string& extra = "") {
    write_text(path, R"({"asset": {"version": "2.0"}, )" + extra + R"(
        "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 0]}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}],
        "buffers": [{"uri": ")" +
                         uri + R"(", "byteLength": 36}]})");
}

// The 36 bytes of a valid triangle: a refused URI naming it would otherwise bake fine.
void write_triangle_bin(const std::string& path) {
    const float p[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(p), sizeof(p));
}

const char* kTetrahedron =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

std::string bake(const std::string& args, std::string* log) {
    return std::to_string(run(bin("stipple-bake") + " " + args, log));
}

// Names in `dir` other than `keep`.
std::vector<std::string> other_files(const std::string& dir, const std::vector<std::string>& keep) {
    std::vector<std::string> out;
    for (const auto& e : fs::directory_iterator(dir)) {
        const std::string name = e.path().filename().string();
        if (std::find(keep.begin(), keep.end(), name) == keep.end()) out.push_back(name);
    }
    return out;
}

TEST(BakeFiles, GltfUrisStayInTheModelFolder) {
    ScratchDir dir;
    fs::create_directories(dir.file("model"));
    write_triangle_bin(dir.file("secret.bin"));  // outside the model's folder
    write_triangle_bin(dir.file("model/inside.bin"));
    fs::create_symlink(dir.file("secret.bin"), dir.file("model/link.bin"));
    const std::string out = dir.file("out.stip");
    const struct {
        const char* name;
        std::string uri;
        const char* words;
    } cases[] = {
        {"climb.gltf", "../secret.bin", "climbs out of the model's folder"},
        {"passwd.gltf", "../../../../etc/passwd", "climbs out of the model's folder"},
        {"hidden_climb.gltf", "sub/../../secret.bin", "climbs out of the model's folder"},
        {"absolute.gltf", dir.file("secret.bin"), "is an absolute path"},
        {"symlink.gltf", "link.bin", "resolves outside the model's folder"},
    };
    for (const auto& c : cases) {
        const std::string model = dir.file(std::string("model/") + c.name);
        write_uri_gltf(model, c.uri);
        std::string log;
        EXPECT_EQ(bake(model + " -o " + out + " --points 10", &log), "1") << c.name << log;
        EXPECT_NE(log.find(c.words), std::string::npos) << c.name << ": " << log;
        EXPECT_EQ(log.find('\n'), log.size() - 1) << log;  // one line
        EXPECT_FALSE(fs::exists(out)) << c.name;
    }
    // The same triangle inside the folder bakes: the refusals above are about the URI.
    write_uri_gltf(dir.file("model/good.gltf"), "inside.bin");
    std::string log;
    EXPECT_EQ(bake(dir.file("model/good.gltf") + " -o " + out + " --points 10 --quiet", &log), "0")
        << log;
}

TEST(BakeFiles, UnknownRequiredExtensionFails) {
    ScratchDir dir;
    write_triangle_bin(dir.file("t.bin"));
    write_uri_gltf(dir.file("ext.gltf"), "t.bin",
                   R"("extensionsUsed": ["VENDOR_teleport"], "extensionsRequired":
                      ["VENDOR_teleport"],)");
    std::string log;
    EXPECT_EQ(bake(dir.file("ext.gltf") + " -o " + dir.file("o.stip"), &log), "1") << log;
    EXPECT_NE(log.find("required extension VENDOR_teleport is not supported"), std::string::npos)
        << log;
    EXPECT_FALSE(fs::exists(dir.file("o.stip")));
}

TEST(BakeFiles, OnlyRegularFilesAreRead) {
    ScratchDir dir;
    fs::create_directories(dir.file("folder.obj"));
    fs::create_symlink("/dev/zero", dir.file("zero.obj"));
    fs::create_symlink("/dev/zero", dir.file("zero.glb"));
    const struct {
        const char* name;
        const char* words;
    } cases[] = {{"folder.obj", "is a directory"},
                 {"zero.obj", "is not a regular file"},
                 {"zero.glb", "is not a regular file"}};
    for (const auto& c : cases) {
        const auto t0 = std::chrono::steady_clock::now();
        std::string log;
        EXPECT_EQ(bake(dir.file(c.name) + " -o " + dir.file("o.stip"), &log), "1") << log;
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        EXPECT_LT(seconds, 5.0) << c.name;  // refused up front, not read until memory runs out
        EXPECT_NE(log.find(c.words), std::string::npos) << c.name << ": " << log;
    }
}

// ASCII PLY bodies OpenMesh would misread (fuzz finding: 12 GB from an "end_header 0" line
// and a face index past int) are refused before it reads them, each with a one-line error.
TEST(BakeFiles, PlyBodiesOpenMeshWouldMisreadAreRefused) {
    ScratchDir dir;
    const std::string head =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property float z\nelement face 1\nproperty list uchar int vertex_indices\n";
    const std::string body = "0 0 0\n1 0 0\n0 1 0\n";
    const std::pair<const char*, std::string> cases[] = {
        {"end_header line has more", head + "end_header 0\n" + body + "3 0 1 2\n"},
        {"not a number of its type", head + "end_header\n" + body + "3 0 1 11111111110\n"},
        {"not a number of its type", head + "end_header\n" + body + "300 0 1 2\n"}};
    for (const auto& c : cases) {
        write_text(dir.file("bad.ply"), c.second);
        std::string log;
        EXPECT_EQ(bake(dir.file("bad.ply") + " -o " + dir.file("bad.stip"), &log), "1") << log;
        EXPECT_NE(log.find(c.first), std::string::npos) << log;
        EXPECT_EQ(std::count(log.begin(), log.end(), '\n'), 1) << log;
    }
    write_text(dir.file("good.ply"), head + "end_header\n" + body + "3 0 1 2\n");
    std::string log;
    EXPECT_EQ(bake(dir.file("good.ply") + " -o " + dir.file("good.stip") + " --points 50", &log),
              "0")
        << log;
}

TEST(BakeFiles, OutputNamingTheInputIsRefused) {
    ScratchDir dir;
    const std::string in = dir.file("in.obj");
    write_text(in, kTetrahedron);
    fs::create_symlink(in, dir.file("alias.obj"));
    for (const std::string& out : {in, dir.path() + "/./in.obj", dir.file("alias.obj")}) {
        std::string log;
        EXPECT_EQ(bake(in + " -o " + out, &log), "1") << out << log;
        EXPECT_NE(log.find("is the input file"), std::string::npos) << log;
        EXPECT_EQ(read_text(in), kTetrahedron);
        EXPECT_TRUE(fs::is_symlink(dir.file("alias.obj")));
    }
}

// A symlink planted at the output, or at the old fixed temp name OUT.tmp, never has its
// target written: the asset replaces the output's link itself.
TEST(BakeFiles, PlantedSymlinksAreNotFollowed) {
    ScratchDir dir;
    write_text(dir.file("in.obj"), kTetrahedron);
    write_text(dir.file("victim_tmp"), "precious tmp");
    write_text(dir.file("victim_out"), "precious out");
    fs::create_symlink(dir.file("victim_tmp"), dir.file("out.stip.tmp"));
    fs::create_symlink(dir.file("victim_out"), dir.file("out.stip"));
    std::string log;
    EXPECT_EQ(
        bake(dir.file("in.obj") + " -o " + dir.file("out.stip") + " --points 50 --quiet", &log),
        "0")
        << log;
    EXPECT_EQ(read_text(dir.file("victim_tmp")), "precious tmp");
    EXPECT_EQ(read_text(dir.file("victim_out")), "precious out");
    EXPECT_FALSE(fs::is_symlink(dir.file("out.stip")));
    EXPECT_EQ(read_text(dir.file("out.stip")).substr(0, 4), "STIP");
    EXPECT_TRUE(fs::is_symlink(dir.file("out.stip.tmp")));
    EXPECT_EQ(
        other_files(dir.path(), {"in.obj", "victim_tmp", "victim_out", "out.stip", "out.stip.tmp"}),
        std::vector<std::string>());
}

// Writes that fail (the output is a folder; a file size limit) say why and leave no temp.
TEST(BakeFiles, FailedWritesLeaveNoTempFile) {
    ScratchDir dir;
    write_text(dir.file("in.obj"), kTetrahedron);
    fs::create_directories(dir.file("out.stip/inner"));
    std::string log;
    EXPECT_EQ(bake(dir.file("in.obj") + " -o " + dir.file("out.stip") + " --points 50", &log), "1")
        << log;
    EXPECT_NE(log.find("Is a directory"), std::string::npos) << log;
    EXPECT_EQ(other_files(dir.path(), {"in.obj", "out.stip"}), std::vector<std::string>());

    // ulimit -f 1: at most 1 KiB per file; a 2000-point asset is bigger.
    const std::string out = dir.file("big.stip");
    const int rc = run("ulimit -f 1 && " + bin("stipple-bake") + " " + dir.file("in.obj") + " -o " +
                           out + " --points 2000",
                       &log);
    EXPECT_EQ(rc, 1) << log;  // an error, not a SIGXFSZ kill
    EXPECT_NE(log.find("File too large"), std::string::npos) << log;
    EXPECT_EQ(other_files(dir.path(), {"in.obj", "out.stip"}), std::vector<std::string>());
}

// SIGTERM in the middle of a long bake: no temp file and no partial asset remain. If the
// bake happened to finish first (a very fast machine), the asset must be whole instead.
TEST(BakeFiles, SigtermLeavesNoTempFile) {
    ScratchDir dir;
    const std::string out = dir.file("bunny.stip");
    std::string log;
    const int rc = run("sh -c '" + bin("stipple-bake") + " " +
                           source("assets/StanfordBunny/stanford-bunny.obj") + " -o " + out +
                           " --points 400000 --quiet & pid=$!; sleep 0.3; kill -TERM $pid; "
                           "wait $pid; echo status=$?'",
                       &log);
    EXPECT_EQ(rc, 0) << log;
    if (log.find("status=0") != std::string::npos) {
        EXPECT_TRUE(fs::exists(out));  // finished before the signal
        EXPECT_EQ(other_files(dir.path(), {"bunny.stip"}), std::vector<std::string>());
    } else {
        EXPECT_NE(log.find("status=143"), std::string::npos) << log;  // 128 + SIGTERM
        EXPECT_EQ(other_files(dir.path(), {"bunny.stip"}), std::vector<std::string>());
        // A signal after the rename (before the process ended) leaves the asset, whole.
        if (fs::exists(out)) {
            EXPECT_EQ(run(bin("stipple-inspect") + " " + out, &log), 0) << log;
        }
    }
}

// SIGTERM while the asset is being written (the signal is sent once the temp file next to
// the output appears): the temp file is removed and no output remains; if the write won the
// race, the asset is whole and alone. What the test times is the write of a large asset
// (6 MB: one write(2) of about 0.1 s against a poll every few ms), not the hierarchy before it,
// so the points are placed by --method random (the default elimination took 20 s of CPU
// against 8 s under ASan, 10 s against 3 s in Release; both runs end by the signal).
TEST(BakeFiles, SigtermDuringTheWriteLeavesNoTempFile) {
    ScratchDir dir;
    const std::string out = dir.file("bunny.stip");
    std::string log;
    const int rc = run("sh -c '" + bin("stipple-bake") + " " +
                           source("assets/StanfordBunny/stanford-bunny.obj") + " -o " + out +
                           " --points 400000 --method random --quiet & pid=$!; "
                           "until ls " +
                           dir.path() +
                           " | grep -q bunny.stip.; do "
                           "kill -0 $pid 2>/dev/null || break; sleep 0.002; done; "
                           "kill -TERM $pid 2>/dev/null; wait $pid; echo status=$?'",
                       &log);
    EXPECT_EQ(rc, 0) << log;
    if (log.find("status=0") != std::string::npos) {
        EXPECT_TRUE(fs::exists(out));  // the write finished before the signal
        EXPECT_EQ(other_files(dir.path(), {"bunny.stip"}), std::vector<std::string>());
    } else {
        EXPECT_NE(log.find("status=143"), std::string::npos) << log;  // 128 + SIGTERM
        EXPECT_EQ(other_files(dir.path(), {"bunny.stip"}), std::vector<std::string>());
        // A signal after the rename (before the process ended) leaves the asset, whole.
        if (fs::exists(out)) {
            EXPECT_EQ(run(bin("stipple-inspect") + " " + out, &log), 0) << log;
        }
    }
}

}  // namespace
