#include "bake/occluder.h"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalFlippingT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>
#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>

#include "bake/position_weld.h"
#include "bake/scene_poser.h"
#include "bake/triangle_grid.h"

namespace stipple::bake {

namespace {

using Mesh = OpenMesh::TriMesh_ArrayKernelT<>;

bool single_sided(const RawScene& s, size_t t) {
    return s.double_sided.empty() || s.double_sided[t] == 0;
}

glm::vec3 position(const float* p, uint32_t v) {
    return glm::vec3(p[size_t(v) * 3], p[size_t(v) * 3 + 1], p[size_t(v) * 3 + 2]);
}

// +1 when the triangles' winding makes their normals point out of the volume they enclose,
// -1 when it encloses a negative volume (faces pointing inwards, e.g. a Z-up PLY that no
// importer flipped).
float outward_sign(const float* pos, const std::vector<uint32_t>& tris) {
    double volume = 0.0;
    for (size_t t = 0; t < tris.size() / 3; ++t)
        volume += double(
            glm::dot(position(pos, tris[t * 3]),
                     glm::cross(position(pos, tris[t * 3 + 1]), position(pos, tris[t * 3 + 2]))));
    return volume < 0.0 ? -1.0f : 1.0f;
}

// The single-sided triangles of the render mesh.
std::vector<uint32_t> single_sided_triangles(const RawScene& s) {
    std::vector<uint32_t> tris;
    for (size_t t = 0; t < s.triangle_count(); ++t)
        if (single_sided(s, t)) tris.insert(tris.end(), &s.indices[t * 3], &s.indices[t * 3 + 3]);
    return tris;
}

// Both one-sided gaps in one pose: how far the surface (vertices, triangle centres) lies
// behind the occluder, and how far the occluder (7 points per triangle) lies in front of the
// surface. Either is a place where the occluder's depth would hide a dot on the surface.
float pose_deviation(const float* pos, const std::vector<uint32_t>& surface,
                     const std::vector<uint32_t>& vertices, const std::vector<uint32_t>& occluder,
                     float outward) {
    float deviation = 0.0f;
    const TriangleGrid on_occluder = build_triangle_grid(pos, occluder);
    for (uint32_t v : vertices)
        deviation = std::max(deviation, one_sided_gap(on_occluder, position(pos, v), -outward));
    for (size_t t = 0; t < surface.size() / 3; ++t) {
        const glm::vec3 centre =
            (position(pos, surface[t * 3]) + position(pos, surface[t * 3 + 1]) +
             position(pos, surface[t * 3 + 2])) /
            3.0f;
        deviation = std::max(deviation, one_sided_gap(on_occluder, centre, -outward));
    }
    const TriangleGrid on_surface = build_triangle_grid(pos, surface);
    for (size_t t = 0; t < occluder.size() / 3; ++t) {
        const glm::vec3 a = position(pos, occluder[t * 3]), b = position(pos, occluder[t * 3 + 1]),
                        c = position(pos, occluder[t * 3 + 2]);
        const glm::vec3 m = (a + b + c) / 3.0f;
        for (const glm::vec3& p : {m, (a + b) * 0.5f, (b + c) * 0.5f, (c + a) * 0.5f,
                                   (a + m) * 0.5f, (b + m) * 0.5f, (c + m) * 0.5f})
            deviation = std::max(deviation, one_sided_gap(on_surface, p, outward));
    }
    return deviation;
}

}  // namespace

float occluder_deviation(const RawScene& scene, const std::vector<uint32_t>& occluder) {
    if (occluder.empty()) return 0.0f;
    const std::vector<uint32_t> surface = single_sided_triangles(scene);
    std::vector<uint32_t> vertices(surface);  // the surface's vertices, each once
    std::sort(vertices.begin(), vertices.end());
    vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
    const float outward = outward_sign(scene.positions.data(), occluder);
    float deviation = 0.0f;
    // Every clip's poses too: skinning bends the surface between the occluder's vertices
    // (an arm against the body). 8 poses a second, at most 16 a clip, fewer on meshes past
    // 100k triangles (each pose costs a query per vertex, triangle and occluder sample).
    PoseSampling sampling;
    sampling.samples_per_second = 8.0f;
    sampling.max_samples_per_clip =
        std::clamp<size_t>(size_t(1.6e6 / double(std::max<size_t>(surface.size() / 3, 1))), 2, 16);
    for_each_pose(scene, sampling, [&](int, const float* positions) {
        deviation =
            std::max(deviation, pose_deviation(positions, surface, vertices, occluder, outward));
    });
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
        const glm::vec3 p = position(scene.positions.data(), representative[c]);
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
