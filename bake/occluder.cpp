#include "bake/occluder.h"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalFlippingT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>
#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>
#include <unordered_map>

#include "bake/position_weld.h"

namespace stipple::bake {

namespace {

using Mesh = OpenMesh::TriMesh_ArrayKernelT<>;

bool single_sided(const RawScene& s, size_t t) {
    return s.double_sided.empty() || s.double_sided[t] == 0;
}

glm::vec3 position(const RawScene& s, uint32_t v) {
    return glm::vec3(s.positions[size_t(v) * 3], s.positions[size_t(v) * 3 + 1],
                     s.positions[size_t(v) * 3 + 2]);
}

// The point of triangle abc nearest to p (Ericson, Real-Time Collision Detection §5.1.5).
glm::vec3 closest_on_triangle(glm::vec3 p, glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    const glm::vec3 ab = b - a, ac = c - a, ap = p - a;
    const float d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) return a;
    const glm::vec3 bp = p - b;
    const float d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) return b;
    const float vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
    const glm::vec3 cp = p - c;
    const float d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) return c;
    const float vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
    const float va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    const float denom = 1.0f / (va + vb + vc);
    return a + ab * (vb * denom) + ac * (vc * denom);
}

// A uniform grid of the occluder's triangles (each in every cell its bounding box touches).
struct TriangleGrid {
    glm::vec3 origin{0.0f};
    float cell = 1.0f;
    std::unordered_map<uint64_t, std::vector<uint32_t>> cells;
    static uint64_t key(glm::ivec3 c) {
        return (uint64_t(uint32_t(c.x) & 0x1FFFFF) << 42) |
               (uint64_t(uint32_t(c.y) & 0x1FFFFF) << 21) | uint64_t(uint32_t(c.z) & 0x1FFFFF);
    }
    glm::ivec3 at(glm::vec3 p) const { return glm::ivec3(glm::floor((p - origin) / cell)); }
};

TriangleGrid build_grid(const RawScene& s, const std::vector<uint32_t>& tris) {
    TriangleGrid g;
    double edge = 0.0;
    for (size_t t = 0; t < tris.size() / 3; ++t)
        edge += glm::length(position(s, tris[t * 3]) - position(s, tris[t * 3 + 1]));
    g.cell = std::max(float(2.0 * edge / double(std::max<size_t>(tris.size() / 3, 1))), 1e-6f);
    g.origin = position(s, tris.empty() ? 0 : tris[0]);
    for (size_t t = 0; t < tris.size() / 3; ++t) {
        const glm::vec3 a = position(s, tris[t * 3]), b = position(s, tris[t * 3 + 1]),
                        c = position(s, tris[t * 3 + 2]);
        const glm::ivec3 lo = g.at(glm::min(a, glm::min(b, c)));
        const glm::ivec3 hi = g.at(glm::max(a, glm::max(b, c)));
        for (int x = lo.x; x <= hi.x; ++x)
            for (int y = lo.y; y <= hi.y; ++y)
                for (int z = lo.z; z <= hi.z; ++z)
                    g.cells[TriangleGrid::key({x, y, z})].push_back(uint32_t(t));
    }
    return g;
}

// How far p lies behind (inside) the occluder triangle nearest to it; 0 when in front.
float behind(const RawScene& s, const std::vector<uint32_t>& tris, const TriangleGrid& g,
             glm::vec3 p, float outward) {
    const glm::ivec3 c = g.at(p);
    float best = INFINITY, depth = 0.0f;
    for (int ring = 0; ring <= 6; ++ring) {
        for (int x = -ring; x <= ring; ++x)
            for (int y = -ring; y <= ring; ++y)
                for (int z = -ring; z <= ring; ++z) {
                    if (std::max(std::abs(x), std::max(std::abs(y), std::abs(z))) != ring)
                        continue;  // the shell of this ring only
                    auto it = g.cells.find(TriangleGrid::key(c + glm::ivec3(x, y, z)));
                    if (it == g.cells.end()) continue;
                    for (uint32_t t : it->second) {
                        const glm::vec3 a = position(s, tris[t * 3]),
                                        b = position(s, tris[t * 3 + 1]),
                                        d = position(s, tris[t * 3 + 2]);
                        const glm::vec3 q = closest_on_triangle(p, a, b, d);
                        const float dist = glm::length(p - q);
                        if (dist >= best) continue;
                        best = dist;
                        const glm::vec3 n = glm::cross(b - a, d - a);
                        depth = outward * glm::dot(p - q, n) < 0.0f ? dist : 0.0f;
                    }
                }
        if (best <= float(ring) * g.cell) break;  // nothing nearer in the rings beyond
    }
    return std::isfinite(best) ? depth : 0.0f;
}

}  // namespace

float occluder_deviation(const RawScene& scene, const std::vector<uint32_t>& occluder) {
    if (occluder.empty()) return 0.0f;
    const TriangleGrid grid = build_grid(scene, occluder);
    // Outward is the side the winding's normals point to unless the mesh encloses a negative
    // volume (faces pointing inwards, e.g. a Z-up PLY that no importer flipped).
    double volume = 0.0;
    for (size_t t = 0; t < occluder.size() / 3; ++t) {
        const glm::vec3 a = position(scene, occluder[t * 3]),
                        b = position(scene, occluder[t * 3 + 1]),
                        c = position(scene, occluder[t * 3 + 2]);
        volume += double(glm::dot(a, glm::cross(b, c)));
    }
    const float outward = volume < 0.0 ? -1.0f : 1.0f;
    float deviation = 0.0f;
    for (size_t v = 0; v < scene.vertex_count(); ++v)
        deviation = std::max(deviation,
                             behind(scene, occluder, grid, position(scene, uint32_t(v)), outward));
    for (size_t t = 0; t < scene.triangle_count(); ++t) {
        if (!single_sided(scene, t)) continue;
        const glm::vec3 centre =
            (position(scene, scene.indices[t * 3]) + position(scene, scene.indices[t * 3 + 1]) +
             position(scene, scene.indices[t * 3 + 2])) /
            3.0f;
        deviation = std::max(deviation, behind(scene, occluder, grid, centre, outward));
    }
    return deviation;
}

BakedOccluder bake_occluder(const RawScene& scene, double ratio) {
    BakedOccluder out;
    const std::vector<uint32_t> weld = weld_by_position(scene);
    uint32_t classes = 0;
    for (uint32_t w : weld) classes = std::max(classes, w + 1);
    std::vector<uint32_t> representative(classes, UINT32_MAX);
    for (size_t v = 0; v < weld.size(); ++v)
        if (representative[weld[v]] == UINT32_MAX) representative[weld[v]] = uint32_t(v);

    Mesh mesh;
    mesh.request_vertex_status();
    mesh.request_edge_status();
    mesh.request_halfedge_status();
    mesh.request_face_status();
    mesh.request_face_normals();
    for (uint32_t c = 0; c < classes; ++c) {
        const glm::vec3 p = position(scene, representative[c]);
        mesh.add_vertex(Mesh::Point(p.x, p.y, p.z));
    }
    std::vector<uint32_t> kept_as_is;  // triangles OpenMesh refuses (non-manifold): copied
    size_t single = 0;
    for (size_t t = 0; t < scene.triangle_count(); ++t) {
        if (!single_sided(scene, t)) continue;
        ++single;
        const uint32_t w[3] = {weld[scene.indices[t * 3]], weld[scene.indices[t * 3 + 1]],
                               weld[scene.indices[t * 3 + 2]]};
        if (w[0] == w[1] || w[1] == w[2] || w[0] == w[2]) continue;  // degenerate
        const Mesh::FaceHandle f =
            mesh.add_face(Mesh::VertexHandle(int(w[0])), Mesh::VertexHandle(int(w[1])),
                          Mesh::VertexHandle(int(w[2])));
        if (!f.is_valid()) kept_as_is.insert(kept_as_is.end(), w, w + 3);
    }
    if (single == 0) return out;
    mesh.update_face_normals();

    using Decimater = OpenMesh::Decimater::DecimaterT<Mesh>;
    Decimater decimater(mesh);
    OpenMesh::Decimater::ModQuadricT<Mesh>::Handle quadric;
    OpenMesh::Decimater::ModNormalFlippingT<Mesh>::Handle flipping;
    decimater.add(quadric);
    decimater.add(flipping);
    decimater.module(quadric).unset_max_err();
    decimater.module(flipping).set_max_normal_deviation(60.0);
    decimater.initialize();
    const size_t target = std::max<size_t>(size_t(double(mesh.n_faces()) * ratio), 4);
    decimater.decimate_to_faces(0, target);

    for (Mesh::FaceHandle f : mesh.faces()) {
        if (mesh.status(f).deleted()) continue;
        for (Mesh::VertexHandle v : mesh.fv_range(f))
            out.indices.push_back(representative[uint32_t(v.idx())]);
    }
    for (uint32_t w : kept_as_is) out.indices.push_back(representative[w]);
    out.deviation = occluder_deviation(scene, out.indices);
    return out;
}

}  // namespace stipple::bake
