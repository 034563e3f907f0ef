// Static mesh importer (OBJ, PLY, STL through OpenMesh's readers) and the extension
// dispatcher. Vertex normals come from bake/vertex_normals.h, as for every importer.
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <algorithm>
#include <cassert>
#include <cctype>
#include <cmath>
#include <fstream>
#include <iostream>
#include <iterator>
#include <limits>
#include <map>
#include <new>
#include <sstream>
#include <string>
#include <vector>

#include "anim/finite.h"
#include "bake/input_file.h"
#include "bake/scene_import.h"
#include "bake/vertex_normals.h"
#include "runtime/asset_limits.h"

namespace stipple::bake {

namespace {

// OpenMesh reports through its global streams: omerr writes to std::cerr, omlog and omout
// are informational. While a capture is alive, std::cerr's buffer is swapped for a string
// (omerr's messages become warnings or the error) and omlog/omout are muted; everything is
// restored afterwards. OpenMesh's own stream wiring is left alone: mostream::disconnect
// does not free the target it removes, so rewiring it per read would leak. Not thread-safe
// with other users of std::cerr or OpenMesh I/O.
class OpenMeshLogCapture {
  public:
    OpenMeshLogCapture()
        : previous_(std::cerr.rdbuf(captured_.rdbuf())),
          err_enabled_(omerr().is_enabled()),
          log_enabled_(omlog().is_enabled()),
          out_enabled_(omout().is_enabled()) {
        omerr().enable();
        omlog().disable();
        omout().disable();
    }
    ~OpenMeshLogCapture() {
        omerr().flush();
        std::cerr.rdbuf(previous_);
        if (!err_enabled_) omerr().disable();
        if (log_enabled_) omlog().enable();
        if (out_enabled_) omout().enable();
    }
    OpenMeshLogCapture(const OpenMeshLogCapture&) = delete;
    OpenMeshLogCapture& operator=(const OpenMeshLogCapture&) = delete;

    // Captured lines, trimmed, empty ones dropped.
    std::vector<std::string> lines() {
        omerr().flush();
        std::vector<std::string> out;
        std::istringstream in(captured_.str());
        std::string line;
        while (std::getline(in, line)) {
            const size_t a = line.find_first_not_of(" \t\r");
            if (a == std::string::npos) continue;
            out.push_back(line.substr(a, line.find_last_not_of(" \t\r") - a + 1));
        }
        return out;
    }

  private:
    std::ostringstream captured_;
    std::streambuf* previous_;
    bool err_enabled_;
    bool log_enabled_;
    bool out_enabled_;
};

// One warning per distinct reader message, with its count.
void add_reader_warnings(const std::vector<std::string>& messages, RawScene* scene) {
    std::map<std::string, size_t> counts;
    std::vector<std::string> distinct;
    for (const std::string& m : messages) {
        if (counts[m]++ == 0) distinct.push_back(m);
    }
    for (const std::string& m : distinct) {
        const size_t n = counts[m];
        const bool vertex = m.find("add_face: complex vertex") != std::string::npos;
        if (vertex || m.find("add_face: complex edge") != std::string::npos) {
            // The reader re-adds such a face on copies of its corners (OpenMesh ImporterT).
            scene->warnings.push_back("OpenMesh reader: " + std::to_string(n) +
                                      (n == 1 ? " face hit a complex " : " faces hit a complex ") +
                                      (vertex ? "vertex" : "edge") +
                                      "; kept on duplicated vertices");
            continue;
        }
        scene->warnings.push_back("OpenMesh reader: " + m +
                                  (n > 1 ? " (" + std::to_string(n) + " times)" : ""));
    }
}

std::string lowercase_extension(const std::string& path);

bool ply_type(const std::string& t) {
    static const char* const kTypes[] = {"char",  "uchar",  "short",   "ushort", "int",   "uint",
                                         "float", "double", "int8",    "uint8",  "int16", "uint16",
                                         "int32", "uint32", "float32", "float64"};
    return std::find(std::begin(kTypes), std::end(kTypes), t) != std::end(kTypes);
}

// OpenMesh 9's PLY header reader loops forever (its string stream growing) on a header it
// cannot tokenise (no end_header, or a keyword or count its stream fails on) and crashes on
// a property line before any element line (both found by tests/fuzz/fuzz_mesh_import.cpp). So a
// .ply reaches it only with a header of the PLY grammar: "ply", then format (version 1.0) / comment
// / obj_info / element NAME COUNT / property TYPE NAME / property list TYPE TYPE NAME lines, then
// end_header, within the first 64 KiB.
BakeError check_ply_header(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::string line;
    size_t read = 0;
    bool element = false;  // a property line belongs to the element before it
    for (int n = 1; read < (64u << 10) && std::getline(in, line); ++n) {
        read += line.size() + 1;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        std::istringstream words(line);
        std::string key, a, b, c, d;
        words >> key >> a >> b >> c >> d;
        bool ok = false;
        if (n == 1) {
            ok = key == "ply" && a.empty();
        } else if (key == "end_header") {
            return BakeError();
        } else if (key == "comment" || key == "obj_info") {
            ok = true;
        } else if (key == "format") {
            ok = (a == "ascii" || a == "binary_little_endian" || a == "binary_big_endian") &&
                 b == "1.0" && c.empty();
        } else if (key == "element") {
            ok = element =
                !a.empty() && !b.empty() && b.size() <= 10 && c.empty() &&
                std::all_of(b.begin(), b.end(), [](char ch) { return ch >= '0' && ch <= '9'; });
        } else if (key == "property") {
            ok = element && (a == "list" ? ply_type(b) && ply_type(c) && !d.empty()
                                         : ply_type(a) && !b.empty() && c.empty());
        }
        if (!ok) return malformed_input("PLY header line " + std::to_string(n) + " is not valid");
    }
    return malformed_input("PLY header has no end_header line");
}

// OpenMesh 9's OBJ reader asserts (aborting the bake) on a face corner without a vertex
// index ("f /1 ..."; found by tests/fuzz/fuzz_mesh_import.cpp): refuse those first.
BakeError check_obj_faces(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::string line;
    for (uint64_t n = 1; std::getline(in, line); ++n) {
        if (line.size() < 2 || line[0] != 'f' || !std::isspace(static_cast<unsigned char>(line[1])))
            continue;
        std::istringstream words(line.substr(1));
        std::string corner;
        while (words >> corner) {
            if (corner[0] == '/')
                return malformed_input("OBJ line " + std::to_string(n) +
                                       ": a face corner has no vertex index");
        }
    }
    return BakeError();
}

BakeError read_static_mesh(const std::string& path, RawScene* scene) {
    // Only a regular file under the cap reaches OpenMesh's readers (a directory or
    // /dev/zero would otherwise be read until memory runs out).
    uint64_t size = 0;
    const BakeError checked = check_input_file(path, kMaxModelFileBytes, &size);
    if (!checked.ok()) return checked;
    const std::string ext = lowercase_extension(path);
    const BakeError syntax = ext == ".ply"   ? check_ply_header(path)
                             : ext == ".obj" ? check_obj_faces(path)
                                             : BakeError();
    if (!syntax.ok()) return syntax;
    OpenMesh::TriMesh_ArrayKernelT<> mesh;
    bool ok = false;
    std::vector<std::string> messages;
    {
        OpenMeshLogCapture capture;
        // Polygons are split into triangle fans by TriMesh::add_face. Faces OpenMesh cannot
        // connect manifoldly ("complex edge") are kept on duplicated vertices by its readers.
        ok = OpenMesh::IO::read_mesh(mesh, path);
        messages = capture.lines();
    }
    if (!ok) {
        return malformed_input("cannot read mesh" +
                               (messages.empty() ? std::string() : ": " + messages.front()));
    }
    add_reader_warnings(messages, scene);
    if (mesh.n_vertices() > limits::kMaxVertices) {
        return bake_error(BakeErrorCode::unsupported, "too many vertices");
    }
    // Triangles as fans over each face's vertex loop (a TriMesh already holds triangles;
    // the fan keeps this correct for any face size).
    std::vector<uint32_t> triangles;
    std::vector<uint32_t> loop;
    for (auto f : mesh.faces()) {
        loop.clear();
        for (auto v : mesh.fv_range(f)) loop.push_back(uint32_t(v.idx()));
        for (size_t i = 1; i + 1 < loop.size(); ++i) {
            triangles.insert(triangles.end(), {loop[0], loop[i], loop[i + 1]});
        }
    }
    if (triangles.empty()) return malformed_input("no triangles found");
    // Keep only the vertices the triangles use: isolated vertices, and the spare copies
    // OpenMesh makes when it repairs non-manifold faces, are dropped silently.
    constexpr uint32_t kUnused = std::numeric_limits<uint32_t>::max();
    std::vector<uint32_t> remap(mesh.n_vertices(), kUnused);
    for (uint32_t& index : triangles) {
        uint32_t& slot = remap[index];
        if (slot == kUnused) {
            slot = uint32_t(scene->positions.size() / 3);
            const auto p = mesh.point(OpenMesh::VertexHandle(int(index)));
            if (!all_finite(p.data(), 3)) {
                return malformed_input("vertex " + std::to_string(index) +
                                       " has a non-finite position");
            }
            for (int c = 0; c < 3; ++c) scene->positions.push_back(p[c]);
        }
        index = slot;
    }
    scene->indices = std::move(triangles);
    compute_vertex_normals(scene->positions, scene->indices, &scene->normals);
    return BakeError();
}

std::string lowercase_extension(const std::string& path) {
    const size_t slash = path.find_last_of("/\\");
    const size_t dot = path.find_last_of('.');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
    std::string ext = path.substr(dot);
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

}  // namespace

BakeError import_static_mesh(const std::string& path, RawScene* out) {
    assert(out != nullptr);
    RawScene scene;
    BakeError error;
    try {
        error = read_static_mesh(path, &scene);
    } catch (const std::bad_alloc&) {
        error = bake_error(BakeErrorCode::out_of_memory, "out of memory");
    } catch (const std::exception& e) {
        error = bake_error(BakeErrorCode::internal, std::string("mesh reader failed: ") + e.what());
        std::replace(error.message.begin(), error.message.end(), '\n', ' ');
    } catch (...) {
        error = bake_error(BakeErrorCode::internal, "mesh reader failed");
    }
    if (!error.ok()) {
        *out = RawScene();
        return prefixed(path + ": ", std::move(error));
    }
    *out = std::move(scene);
    return BakeError();
}

BakeError import_scene(const std::string& path, RawScene* out) {
    assert(out != nullptr);
    const std::string ext = lowercase_extension(path);
    if (ext == ".gltf" || ext == ".glb") return import_gltf(path, out);
    if (ext == ".obj" || ext == ".ply" || ext == ".stl") return import_static_mesh(path, out);
    *out = RawScene();
    return bake_error(BakeErrorCode::unsupported,
                      path + ": unsupported file extension '" + ext +
                          "' (expected .gltf, .glb, .obj, .ply or .stl)");
}

}  // namespace stipple::bake
