// The halfedge collapse of simplification (thesis Alg. 4.1, bake/point_hierarchy.cpp) without
// its O(valence) step. OpenMesh's PolyConnectivity::collapse (collapse_edge, then
// collapse_loop for each of the two faces that became loops) calls adjust_outgoing_halfedge
// on the kept vertex and on the apices of the removed faces; it walks the vertex's whole
// one-ring looking for a boundary halfedge. Around the hub of a closed fan every rim collapse
// walked the hub's ring: O(T) per collapse, O(T^2) in all (70,000 triangles: 15 s, 90 % of it
// there; docs/hierarchy.md, "Complexity"). The walk finds nothing and changes nothing at a
// vertex that was interior before the collapse (a collapse leaves it interior), and OpenMesh
// keeps a boundary vertex's outgoing halfedge on the boundary, so is_boundary() tells in O(1)
// which vertices need it. Otherwise this is OpenMesh 9's collapse step for step, so the mesh,
// and the bake, are the same.
#pragma once
#include <algorithm>
#include <iterator>

namespace stipple::bake {

template <class Mesh>
void collapse_halfedge(Mesh& m, typename Mesh::HalfedgeHandle h0) {
    using HalfedgeHandle = typename Mesh::HalfedgeHandle;
    using VertexHandle = typename Mesh::VertexHandle;
    using FaceHandle = typename Mesh::FaceHandle;
    const HalfedgeHandle h1 = m.next_halfedge_handle(h0);
    const HalfedgeHandle o0 = m.opposite_halfedge_handle(h0);
    const HalfedgeHandle o1 = m.next_halfedge_handle(o0);
    // The vertices whose outgoing halfedge may need the walk: boundary ones before the
    // collapse, and the kept vertex if the removed one was on the boundary.
    const VertexHandle kept = m.to_vertex_handle(h0), removed = m.from_vertex_handle(h0);
    const VertexHandle touched[4] = {kept, removed, m.to_vertex_handle(h1), m.to_vertex_handle(o1)};
    bool walk[4];
    for (int i = 0; i < 4; ++i) walk[i] = m.is_boundary(touched[i]);
    walk[0] = walk[0] || walk[1];
    auto adjust = [&](VertexHandle v) {
        const auto at = std::find(std::begin(touched), std::end(touched), v);
        if (at == std::end(touched) || walk[at - std::begin(touched)])
            m.adjust_outgoing_halfedge(v);
    };

    // collapse_edge(h0)
    {
        const HalfedgeHandle h = h0, hn = m.next_halfedge_handle(h), hp = m.prev_halfedge_handle(h);
        const HalfedgeHandle o = o0, on = m.next_halfedge_handle(o), op = m.prev_halfedge_handle(o);
        const FaceHandle fh = m.face_handle(h), fo = m.face_handle(o);
        const VertexHandle vh = m.to_vertex_handle(h), vo = m.to_vertex_handle(o);
        for (auto it = m.vih_iter(vo); it.is_valid(); ++it) m.set_vertex_handle(*it, vh);
        m.set_next_halfedge_handle(hp, hn);
        m.set_next_halfedge_handle(op, on);
        if (fh.is_valid()) m.set_halfedge_handle(fh, hn);
        if (fo.is_valid()) m.set_halfedge_handle(fo, on);
        if (m.halfedge_handle(vh) == o) m.set_halfedge_handle(vh, hn);
        adjust(vh);
        m.set_isolated(vo);
        m.status(m.edge_handle(h)).set_deleted(true);
        m.status(vo).set_deleted(true);
        m.status(h).set_deleted(true);
        m.status(o).set_deleted(true);
    }
    // collapse_loop for each face that became a loop
    auto collapse_loop = [&](HalfedgeHandle l0) {
        const HalfedgeHandle l1 = m.next_halfedge_handle(l0);
        const HalfedgeHandle lo0 = m.opposite_halfedge_handle(l0);
        const HalfedgeHandle lo1 = m.opposite_halfedge_handle(l1);
        const VertexHandle v0 = m.to_vertex_handle(l0), v1 = m.to_vertex_handle(l1);
        const FaceHandle fh = m.face_handle(l0), fo = m.face_handle(lo0);
        m.set_next_halfedge_handle(l1, m.next_halfedge_handle(lo0));
        m.set_next_halfedge_handle(m.prev_halfedge_handle(lo0), l1);
        m.set_face_handle(l1, fo);
        m.set_halfedge_handle(v0, l1);
        adjust(v0);
        m.set_halfedge_handle(v1, lo1);
        adjust(v1);
        if (fo.is_valid() && m.halfedge_handle(fo) == lo0) m.set_halfedge_handle(fo, l1);
        if (fh.is_valid()) {
            m.set_halfedge_handle(fh, HalfedgeHandle());
            m.status(fh).set_deleted(true);
        }
        m.status(m.edge_handle(l0)).set_deleted(true);
        m.status(l0).set_deleted(true);
        m.status(lo0).set_deleted(true);
    };
    if (m.next_halfedge_handle(m.next_halfedge_handle(h1)) == h1)
        collapse_loop(m.next_halfedge_handle(h1));
    if (m.next_halfedge_handle(m.next_halfedge_handle(o1)) == o1) collapse_loop(o1);
}

}  // namespace stipple::bake
