// The polygons point relaxation works on (thesis §5.1): the welded input, bisected until
// there is at least one polygon per point wanted. Every face lies inside one input triangle
// (its host), so a point on a face is a point of the input surface. Plain arrays, built once
// from the connectivity graph.
#pragma once
#include <OpenMesh/Core/Geometry/VectorT.hh>
#include <cstdint>
#include <vector>

namespace stipple::bake {

using Vec3d = OpenMesh::Vec3d;

constexpr uint32_t kNoFace = 0xFFFFFFFFu;

struct BaseMesh {
    std::vector<Vec3d> positions;          // per vertex
    std::vector<uint32_t> faces;           // 3 vertex indices per face
    std::vector<uint32_t> host;            // input triangle each face lies in
    std::vector<uint32_t> across;          // 3 per face: the face across edge (v[k], v[k+1])
    std::vector<uint32_t> vf_offsets, vf;  // faces around each vertex (CSR)

    uint32_t face_count() const { return uint32_t(host.size()); }
    const Vec3d& corner(uint32_t f, int k) const {
        return positions[faces[size_t(f) * 3 + size_t(k)]];
    }
    double area(uint32_t f) const;
    Vec3d unit_normal(uint32_t f) const;
    // Faces sharing a vertex with f, f included, sorted (Alg. 5.2's neighbouring polygons).
    void faces_around(uint32_t f, std::vector<uint32_t>* out) const;
    // Fills vf_offsets/vf from faces (call after faces are set).
    void build_vertex_faces();
};

// Moves the point p of face *face by `step` along the surface (Alg. 5.1, "displace Pt on the
// surface of the model"): the step is taken in the face's plane; where it leaves the face,
// the point "jumps" to the face across that edge (§5.2) and the rest of the step is turned
// into that face's plane about the shared edge. It stops at a boundary edge. The result
// stays on the surface exactly (up to rounding), with *face its new host polygon.
void walk_on_surface(const BaseMesh& mesh, uint32_t* face, Vec3d* p, Vec3d step);

}  // namespace stipple::bake
