// Static mesh importer (OBJ, PLY, STL through OpenMesh's readers) and the extension
// dispatcher. Vertex normals come from bake/vertex_normals.h, as for every importer.
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <algorithm>
#include <cassert>
#include <cctype>
#include <cmath>
#include <cstdlib>
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

struct PlyProperty {
    bool list = false;
    std::string count_type, type;  // count_type: list properties only
};
struct PlyElement {
    uint64_t count = 0;
    std::vector<PlyProperty> properties;
};
struct PlyHeader {
    std::string format;
    std::vector<PlyElement> elements;
    uint64_t body_offset = 0;  // first byte after the end_header line
};

// OpenMesh 9's PLY header reader loops forever (its string stream growing) on a header it
// cannot tokenise (no end_header, or a keyword or count its stream fails on) and crashes on
// a property line before any element line (both found by tests/fuzz/fuzz_mesh_import.cpp). So a
// .ply reaches it only with a header of the PLY grammar: "ply", then format (version 1.0) / comment
// / obj_info / element NAME COUNT / property TYPE NAME / property list TYPE TYPE NAME lines, then
// end_header, within the first 64 KiB.
BakeError check_ply_header(std::istream& in, PlyHeader* header) {
    std::string line;
    uint64_t read = 0;
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
            // Nothing may follow it on its line: OpenMesh and this check would then disagree
            // on where the body starts (a fuzzed "end_header 0" took 12 GB).
            if (!a.empty()) break;
            header->body_offset = read;
            return BakeError();
        } else if (key == "comment" || key == "obj_info") {
            ok = true;
        } else if (key == "format") {
            ok = (a == "ascii" || a == "binary_little_endian" || a == "binary_big_endian") &&
                 b == "1.0" && c.empty();
            header->format = a;
        } else if (key == "element") {
            ok = !a.empty() && !b.empty() && b.size() <= 10 && c.empty() &&
                 std::all_of(b.begin(), b.end(), [](char ch) { return ch >= '0' && ch <= '9'; });
            if (ok) header->elements.push_back({std::stoull(b), {}});
        } else if (key == "property") {
            const bool list = a == "list";
            ok = !header->elements.empty() && (list ? ply_type(b) && ply_type(c) && !d.empty()
                                                    : ply_type(a) && !b.empty() && c.empty());
            if (ok)
                header->elements.back().properties.push_back({list, list ? b : "", list ? c : a});
        }
        if (!ok) return malformed_input("PLY header line " + std::to_string(n) + " is not valid");
    }
    if (!line.empty() && line.rfind("end_header", 0) == 0)
        return malformed_input("PLY end_header line has more after it");
    return malformed_input("PLY header has no end_header line");
}

// Bytes of one value of a PLY type (ply_type() names only).
uint64_t ply_type_bytes(const std::string& t) {
    if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
    if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
    return t == "double" || t == "float64" ? 8 : 4;
}

// One ASCII value of type t as OpenMesh's stream reads it: an integer ([+-]digits) for the
// integer types, a decimal number (strtod, no nan/inf/hex) for float and double.
bool ply_ascii_value(const std::string& token, const std::string& t) {
    const bool real = t == "float" || t == "double" || t == "float32" || t == "float64";
    const size_t digits = token[0] == '+' || token[0] == '-' ? 1 : 0;
    if (!real) {  // digits, and a value in the type's range (an int of 11111111110 overflows)
        if (token.size() <= digits || token.size() > digits + 10 ||
            !std::all_of(token.begin() + long(digits), token.end(),
                         [](char ch) { return ch >= '0' && ch <= '9'; }))
            return false;
        const long long v = std::strtoll(token.c_str(), nullptr, 10);
        const int bytes = ply_type_bytes(t);
        const bool is_unsigned = t[0] == 'u';
        const long long lo = is_unsigned ? 0 : -(1LL << (8 * bytes - 1));
        const long long hi = is_unsigned ? (1LL << (8 * bytes)) - 1 : (1LL << (8 * bytes - 1)) - 1;
        return v >= lo && v <= hi;
    }
    if (token.find_first_not_of("0123456789+-.eE") != std::string::npos) return false;
    char* end = nullptr;
    (void)std::strtod(token.c_str(), &end);
    return end == token.c_str() + token.size();
}

// OpenMesh 9's ASCII PLY body reader does not stop when its stream fails inside the element
// data: a body that stops being numbers grows a vector of face vertex handles until memory
// runs out (found by tests/fuzz/fuzz_mesh_import.cpp). So every element row the header
// promises must be there first: in an ASCII body, one number of its type per scalar property
// and a count then that many numbers per list; in a binary body, at least the bytes of the
// rows' scalars and list counts.
BakeError check_ply_body(std::istream& in, const PlyHeader& h, uint64_t file_size) {
    const uint64_t body = file_size > h.body_offset ? file_size - h.body_offset : 0;
    for (size_t e = 0; e < h.elements.size(); ++e) {
        uint64_t row = 0;  // least bytes (binary) or tokens (ASCII) of one row
        for (const PlyProperty& p : h.elements[e].properties)
            row += h.format == "ascii" ? 1 : ply_type_bytes(p.list ? p.count_type : p.type);
        if (h.elements[e].count > body / std::max<uint64_t>(row, 1))
            return malformed_input("PLY element " + std::to_string(e) + " has " +
                                   std::to_string(h.elements[e].count) +
                                   " rows, more than the file holds");
    }
    if (h.format != "ascii") return BakeError();
    std::string token;
    for (size_t e = 0; e < h.elements.size(); ++e) {
        const PlyElement& element = h.elements[e];
        if (element.properties.empty()) continue;
        for (uint64_t r = 0; r < element.count; ++r) {
            for (const PlyProperty& p : element.properties) {
                bool ok =
                    bool(in >> token) && ply_ascii_value(token, p.list ? p.count_type : p.type);
                uint64_t n = ok && p.list ? std::strtoull(token.c_str(), nullptr, 10) : 0;
                if (ok && p.list && token[0] == '-') ok = false;
                for (; ok && n > 0; --n) ok = bool(in >> token) && ply_ascii_value(token, p.type);
                if (!ok)
                    return malformed_input("PLY element " + std::to_string(e) + " row " +
                                           std::to_string(r) + ": not a number of its type");
            }
        }
    }
    return BakeError();
}

BakeError check_ply(const std::string& path, uint64_t file_size) {
    std::ifstream in(path, std::ios::binary);
    PlyHeader header;
    const BakeError e = check_ply_header(in, &header);
    return e.ok() ? check_ply_body(in, header, file_size) : e;
}

// OBJ's "v x y z r g b" and "vc r g b": OpenMesh 9's reader casts each colour value times 255
// to a byte, undefined outside [0, 1], and writes "vc" colours past the colour array (UBSan
// and ASan, tests/fuzz/fuzz_mesh_import.cpp: before any vertex, with more "vc" than "v"
// lines, after a malformed "v" line, and in a case with k vertices before the k-th "vc").
// Where a "vc" colour goes is not known, so "vc" lines, an extension no bundled model uses,
// are refused. Empty unless the line is such a colour (values read as the reader reads
// them: floats from a stream).
std::string obj_colour_error(const std::string& line) {
    std::istringstream words(line);
    std::string key;
    words >> key;
    if (key == "vc") return "vertex colour lines (vc) are not supported";
    if (key != "v") return std::string();
    float value[6];
    int count = 0;
    while (count < 6 && words >> value[count]) ++count;
    if (count < 6) return std::string();
    for (int k = 3; k < 6; ++k)
        if (!(value[k] >= 0.0f && value[k] <= 1.0f)) return "a vertex colour is outside [0, 1]";
    return std::string();
}

// OpenMesh 9's OBJ reader asserts (aborting the bake) on a face corner without a vertex
// index ("f /1 ..."; found by tests/fuzz/fuzz_mesh_import.cpp), and casts vertex colours
// unchecked (obj_colour_error): refuse those first.
BakeError check_obj(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::string line;
    for (uint64_t n = 1; std::getline(in, line); ++n) {
        const std::string colour = obj_colour_error(line);
        if (!colour.empty())
            return malformed_input("OBJ line " + std::to_string(n) + ": " + colour);
        std::istringstream words(line);  // keywords as the reader reads them: after blanks
        std::string corner;
        if (!(words >> corner) || corner != "f") continue;
        while (words >> corner) {
            if (corner[0] == '/')
                return malformed_input("OBJ line " + std::to_string(n) +
                                       ": a face corner has no vertex index");
        }
    }
    return BakeError();
}

// A file's vertex colour (8-bit sRGB, as PLY and OBJ colours are meant) as linear RGBA.
void append_colour(const OpenMesh::Vec3uc& c, RawScene* scene) {
    for (int k = 0; k < 3; ++k) {
        const float x = float(c[k]) / 255.0f;
        scene->colours.push_back(x <= 0.04045f ? x / 12.92f
                                               : std::pow((x + 0.055f) / 1.055f, 2.4f));
    }
    scene->colours.push_back(1.0f);
}

BakeError read_static_mesh(const std::string& path, RawScene* scene) {
    // Only a regular file under the cap reaches OpenMesh's readers (a directory or
    // /dev/zero would otherwise be read until memory runs out).
    uint64_t size = 0;
    const BakeError checked = check_input_file(path, kMaxModelFileBytes, &size);
    if (!checked.ok()) return checked;
    const std::string ext = lowercase_extension(path);
    const BakeError syntax = ext == ".ply"   ? check_ply(path, size)
                             : ext == ".obj" ? check_obj(path)
                                             : BakeError();
    if (!syntax.ok()) return syntax;
    OpenMesh::TriMesh_ArrayKernelT<> mesh;
    bool ok = false;
    std::vector<std::string> messages;
    // Vertex colours where the file has them (PLY red/green/blue[/alpha], OBJ "v x y z r g b").
    mesh.request_vertex_colors();
    OpenMesh::IO::Options options = OpenMesh::IO::Options::VertexColor;
    {
        OpenMeshLogCapture capture;
        // Polygons are split into triangle fans by TriMesh::add_face. Faces OpenMesh cannot
        // connect manifoldly ("complex edge") are kept on duplicated vertices by its readers.
        ok = OpenMesh::IO::read_mesh(mesh, path, options);
        messages = capture.lines();
    }
    // STL has no vertex colours (OpenMesh's STL reader reports some anyway).
    const bool coloured = ext != ".stl" && options.check(OpenMesh::IO::Options::VertexColor);
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
            if (coloured) append_colour(mesh.color(OpenMesh::VertexHandle(int(index))), scene);
        }
        index = slot;
    }
    scene->indices = std::move(triangles);
    if (std::all_of(scene->colours.begin(), scene->colours.end(),
                    [](float c) { return c == 1.0f; }))
        scene->colours.clear();
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

BakeError import_scene(const std::string& path, RawScene* out, const ImportOptions& options) {
    assert(out != nullptr);
    const std::string ext = lowercase_extension(path);
    BakeError error;
    if (ext == ".gltf" || ext == ".glb") {
        error = import_gltf(path, out, options);
    } else if (ext == ".obj" || ext == ".ply" || ext == ".stl") {
        error = import_static_mesh(path, out);
    } else {
        *out = RawScene();
        return bake_error(BakeErrorCode::unsupported,
                          path + ": unsupported file extension '" + ext +
                              "' (expected .gltf, .glb, .obj, .ply or .stl)");
    }
    if (error.ok()) error = check_transparent_names(options, *out);
    if (!error.ok()) *out = RawScene();
    return error;
}

}  // namespace stipple::bake
