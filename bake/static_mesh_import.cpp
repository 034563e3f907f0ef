// Static mesh importer (OBJ, PLY, STL through OpenMesh's readers) and the extension
// dispatcher. Also home of the vertex normal computation both importers share.
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <algorithm>
#include <cassert>
#include <cctype>
#include <cmath>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <new>
#include <sstream>
#include <string>
#include <vector>

#include "bake/scene_import.h"

namespace stipple::bake {

namespace detail {

// Area-weighted vertex normals: each vertex gets the sum of the cross products
// (p1 - p0) x (p2 - p0) of its triangles, whose length is twice the triangle area, then
// normalised (Max, "Weights for Computing Vertex Normals from Facet Normals", JGT 1999,
// the area-weighted variant). A vertex whose triangles all have zero area gets +z.
void compute_vertex_normals(const std::vector<float>& positions,
                            const std::vector<uint32_t>& indices, std::vector<float>* normals) {
    const size_t vertex_count = positions.size() / 3;
    std::vector<double> sum(vertex_count * 3, 0.0);
    for (size_t t = 0; t + 2 < indices.size(); t += 3) {
        const uint32_t v[3] = {indices[t], indices[t + 1], indices[t + 2]};
        assert(v[0] < vertex_count && v[1] < vertex_count && v[2] < vertex_count);
        double e1[3], e2[3];
        for (int c = 0; c < 3; ++c) {
            e1[c] = double(positions[v[1] * 3 + c]) - positions[v[0] * 3 + c];
            e2[c] = double(positions[v[2] * 3 + c]) - positions[v[0] * 3 + c];
        }
        const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                             e1[0] * e2[1] - e1[1] * e2[0]};
        for (uint32_t vi : v) {
            for (int c = 0; c < 3; ++c) sum[vi * 3 + c] += n[c];
        }
    }
    normals->assign(vertex_count * 3, 0.0f);
    for (size_t i = 0; i < vertex_count; ++i) {
        const double* s = &sum[i * 3];
        const double len = std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
        if (std::isfinite(len) && len > 0.0) {
            for (int c = 0; c < 3; ++c) (*normals)[i * 3 + c] = float(s[c] / len);
        } else {
            (*normals)[i * 3 + 2] = 1.0f;
        }
    }
}

}  // namespace detail

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

bool read_static_mesh(const std::string& path, RawScene* scene, std::string* err) {
    if (!std::ifstream(path, std::ios::binary)) {
        *err = "cannot open file";
        return false;
    }
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
        *err = "cannot read mesh" + (messages.empty() ? std::string() : ": " + messages.front());
        return false;
    }
    // One warning per distinct reader message, with its count.
    std::map<std::string, size_t> counts;
    std::vector<std::string> distinct;
    for (const std::string& m : messages) {
        if (counts[m]++ == 0) distinct.push_back(m);
    }
    for (const std::string& m : distinct) {
        const size_t n = counts[m];
        scene->warnings.push_back("OpenMesh reader: " + m +
                                  (n > 1 ? " (" + std::to_string(n) + " times)" : ""));
    }

    if (mesh.n_vertices() > std::numeric_limits<uint32_t>::max()) {
        *err = "too many vertices";
        return false;
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
    if (triangles.empty()) {
        *err = "no triangles found";
        return false;
    }
    // Keep only the vertices the triangles use: isolated vertices, and the spare copies
    // OpenMesh makes when it repairs non-manifold faces, are dropped silently.
    constexpr uint32_t kUnused = std::numeric_limits<uint32_t>::max();
    std::vector<uint32_t> remap(mesh.n_vertices(), kUnused);
    for (uint32_t& index : triangles) {
        uint32_t& slot = remap[index];
        if (slot == kUnused) {
            slot = uint32_t(scene->positions.size() / 3);
            const auto p = mesh.point(OpenMesh::VertexHandle(int(index)));
            for (int c = 0; c < 3; ++c) {
                if (!std::isfinite(p[c])) {
                    *err = "vertex " + std::to_string(index) + " has a non-finite position";
                    return false;
                }
                scene->positions.push_back(p[c]);
            }
        }
        index = slot;
    }
    scene->indices = std::move(triangles);
    detail::compute_vertex_normals(scene->positions, scene->indices, &scene->normals);
    return true;
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

bool import_static_mesh(const std::string& path, RawScene* out, std::string* error) {
    assert(out != nullptr);
    RawScene scene;
    std::string err;
    bool ok = false;
    try {
        ok = read_static_mesh(path, &scene, &err);
    } catch (const std::bad_alloc&) {
        err = "out of memory";
    } catch (const std::exception& e) {
        err = std::string("mesh reader failed: ") + e.what();
        std::replace(err.begin(), err.end(), '\n', ' ');
    } catch (...) {
        err = "mesh reader failed";
    }
    if (!ok) {
        *out = RawScene();
        if (error) *error = path + ": " + err;
        return false;
    }
    *out = std::move(scene);
    return true;
}

bool import_scene(const std::string& path, RawScene* out, std::string* error) {
    assert(out != nullptr);
    const std::string ext = lowercase_extension(path);
    if (ext == ".gltf" || ext == ".glb") return import_gltf(path, out, error);
    if (ext == ".obj" || ext == ".ply" || ext == ".stl")
        return import_static_mesh(path, out, error);
    *out = RawScene();
    if (error) {
        *error = path + ": unsupported file extension '" + ext +
                 "' (expected .gltf, .glb, .obj, .ply or .stl)";
    }
    return false;
}

}  // namespace stipple::bake
