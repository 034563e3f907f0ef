#include "bake/point_hierarchy.h"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <queue>
#include <tuple>

namespace stipple::bake {

namespace {

struct MeshTraits : OpenMesh::DefaultTraits {
    using Point = OpenMesh::Vec3d;
    using Normal = OpenMesh::Vec3d;
    VertexAttributes(OpenMesh::Attributes::Status);
    EdgeAttributes(OpenMesh::Attributes::Status);
    HalfedgeAttributes(OpenMesh::Attributes::Status);
    FaceAttributes(OpenMesh::Attributes::Status);
};
using Mesh = OpenMesh::TriMesh_ArrayKernelT<MeshTraits>;
using Vec3 = OpenMesh::Vec3d;

// A point of the hierarchy before ordering: host face + barycentrics (§4.5.1),
// and the relevant neighbours saved when it was removed or created (§4.5).
struct PointRecord {
    uint32_t host = 0;
    double u = 0, v = 0;
    double radius = 0;
    std::vector<uint32_t> neighbours;
};

uint64_t splitmix64(uint64_t* state) {
    uint64_t z = (*state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

Vec3 input_position(const RawScene& s, uint32_t vertex) {
    const float* p = &s.positions[size_t(vertex) * 3];
    return Vec3(p[0], p[1], p[2]);
}

// Barycentric weights (u, v) of `p` in input triangle `t`, for a point known to lie in it
// up to rounding: least-squares solve in the triangle's plane, then clamp into the
// triangle so the runtime always gets valid coordinates.
void barycentric_in(const RawScene& s, uint32_t t, const Vec3& p, double* u, double* v) {
    const uint32_t* tri = &s.indices[size_t(t) * 3];
    Vec3 a = input_position(s, tri[0]), b = input_position(s, tri[1]), c = input_position(s, tri[2]);
    Vec3 e0 = a - c, e1 = b - c, d = p - c;
    double d00 = e0 | e0, d01 = e0 | e1, d11 = e1 | e1, d20 = d | e0, d21 = d | e1;
    double den = d00 * d11 - d01 * d01;
    double bu = den > 0 ? (d11 * d20 - d01 * d21) / den : 1.0 / 3;
    double bv = den > 0 ? (d00 * d21 - d01 * d20) / den : 1.0 / 3;
    bu = std::max(bu, 0.0);
    bv = std::max(bv, 0.0);
    double sum = bu + bv;
    if (sum > 1) {
        bu /= sum;
        bv /= sum;
    }
    *u = bu;
    *v = bv;
}

// Welds vertices at the same position (within eps) so that seams split for UVs or normals
// do not cut the connectivity graph (thesis §4.1).
std::vector<uint32_t> weld(const RawScene& s, double eps, uint32_t* welded_count) {
    std::map<std::tuple<int64_t, int64_t, int64_t>, uint32_t> cells;
    std::vector<uint32_t> remap(s.vertex_count());
    for (uint32_t i = 0; i < s.vertex_count(); ++i) {
        Vec3 p = input_position(s, i);
        auto key = std::make_tuple(std::llround(p[0] / eps), std::llround(p[1] / eps),
                                   std::llround(p[2] / eps));
        auto it = cells.emplace(key, uint32_t(cells.size())).first;
        remap[i] = it->second;
    }
    *welded_count = uint32_t(cells.size());
    return remap;
}

// A bisection vertex's one-ring lies at about half the split edge L, but while one
// generation of splits sweeps the mesh, the area per point falls from L^2/2 to L^2/4; its mean
// over the generation, 2 ln 2 (L/2)^2, is what the point's region of influence should be.
// Scaling the radius by sqrt(2 ln 2) makes bisection levels carry the same region per r^2 as
// simplification levels, so tone does not jump where the two parts of the hierarchy meet.
// (The runtime re-scales this radius with its neighbours' distances, Alg. 6.4.)
const double kBisectionRadiusScale = std::sqrt(2.0 * std::log(2.0));

struct Builder {
    const RawScene& scene;
    const HierarchyConfig& config;
    HierarchyStats stats;
    Mesh mesh;
    OpenMesh::FPropHandleT<uint32_t> host_face;  // input triangle each face lies in
    std::vector<PointRecord> points;             // indexed like mesh vertices

    Builder(const RawScene& s, const HierarchyConfig& c) : scene(s), config(c) {
        mesh.add_property(host_face);
    }

    void report(float fraction) {
        if (config.progress) config.progress(fraction, config.progress_user);
    }

    Mesh::VertexHandle new_vertex(const Vec3& p, uint32_t triangle, int corner) {
        PointRecord r;
        r.host = triangle;
        r.u = corner == 0 ? 1 : 0;
        r.v = corner == 1 ? 1 : 0;
        points.push_back(r);
        return mesh.add_vertex(p);
    }

    // Connectivity graph (§4.1). Faces that would make the mesh non-manifold get their own
    // copies of their vertices rather than being dropped, so every input triangle can host
    // points.
    void build_graph() {
        double diag = 0;
        {
            Vec3 lo(1e300, 1e300, 1e300), hi(-1e300, -1e300, -1e300);
            for (uint32_t i = 0; i < scene.vertex_count(); ++i) {
                lo.minimize(input_position(scene, i));
                hi.maximize(input_position(scene, i));
            }
            diag = (hi - lo).norm();
        }
        uint32_t welded_count = 0;
        std::vector<uint32_t> remap =
            weld(scene, std::max(diag * config.weld_epsilon, 1e-12), &welded_count);
        stats.welded_vertices = welded_count;
        std::vector<Mesh::VertexHandle> handle(welded_count);
        for (uint32_t t = 0; t < scene.triangle_count(); ++t) {
            const uint32_t* tri = &scene.indices[size_t(t) * 3];
            uint32_t w[3] = {remap[tri[0]], remap[tri[1]], remap[tri[2]]};
            Vec3 p[3] = {input_position(scene, tri[0]), input_position(scene, tri[1]),
                         input_position(scene, tri[2])};
            if (w[0] == w[1] || w[1] == w[2] || w[0] == w[2] || ((p[1] - p[0]) % (p[2] - p[0])).norm() == 0) {
                ++stats.skipped_faces;
                continue;
            }
            Mesh::VertexHandle vh[3];
            for (int k = 0; k < 3; ++k) {
                if (!handle[w[k]].is_valid()) handle[w[k]] = new_vertex(p[k], t, k);
                vh[k] = handle[w[k]];
            }
            Mesh::FaceHandle f = mesh.add_face(vh[0], vh[1], vh[2]);
            if (!f.is_valid()) {
                for (int k = 0; k < 3; ++k) vh[k] = new_vertex(p[k], t, k);
                stats.split_vertices += 3;
                f = mesh.add_face(vh[0], vh[1], vh[2]);
            }
            mesh.property(host_face, f) = t;
        }
    }

    double mean_distance(uint32_t point, const std::vector<uint32_t>& neighbours,
                         const Mesh& m) const {
        if (neighbours.empty()) return 0;
        double sum = 0;
        Vec3 p = m.point(Mesh::VertexHandle(int(point)));
        for (uint32_t n : neighbours) sum += (m.point(Mesh::VertexHandle(int(n))) - p).norm();
        return sum / double(neighbours.size());
    }

    std::vector<uint32_t> one_ring(const Mesh& m, Mesh::VertexHandle v) const {
        std::vector<uint32_t> ring;
        for (Mesh::ConstVertexVertexIter it = m.cvv_iter(v); it.is_valid(); ++it)
            ring.push_back(uint32_t(it->idx()));
        return ring;
    }

    // Thesis Alg. 4.1 on a copy of the input graph: repeatedly collapse an edge, saving the
    // removed vertex's one-ring as its relevant neighbours. We collapse the *shortest* edge
    // first: §4.5 states that "closest vertices in object space are removed first", which is
    // what makes relevance radii grow as the hierarchy coarsens (Alg. 4.1's listing says
    // "longest", which would remove the best-spaced vertices first).
    void simplify() {
        Mesh m = mesh;
        using Entry = std::pair<double, int>;  // (length, edge), smallest first
        std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> heap;
        auto length = [&](Mesh::EdgeHandle e) { return m.calc_edge_length(e); };
        uint64_t rng = config.seed;
        size_t remaining = m.n_vertices(), total = remaining;
        for (int pass = 0; pass < 4; ++pass) {
            size_t before = remaining;
            for (Mesh::EdgeHandle e : m.edges())
                if (!m.status(e).deleted()) heap.push({length(e), e.idx()});
            while (!heap.empty()) {
                auto [len, idx] = heap.top();
                heap.pop();
                Mesh::EdgeHandle e(idx);
                if (m.status(e).deleted() || length(e) != len) continue;  // stale entry
                Mesh::HalfedgeHandle h = m.halfedge_handle(e, int(splitmix64(&rng) & 1));
                if (!m.is_collapse_ok(h)) h = m.opposite_halfedge_handle(h);
                if (!m.is_collapse_ok(h)) continue;
                Mesh::VertexHandle removed = m.from_vertex_handle(h), kept = m.to_vertex_handle(h);
                PointRecord& r = points[size_t(removed.idx())];
                r.neighbours = one_ring(m, removed);
                r.radius = mean_distance(uint32_t(removed.idx()), r.neighbours, m);
                m.collapse(h);
                --remaining;
                for (Mesh::VertexEdgeIter it = m.ve_iter(kept); it.is_valid(); ++it)
                    heap.push({length(*it), it->idx()});
                if (remaining % 4096 == 0) report(0.5f * float(total - remaining) / float(total));
            }
            if (remaining == before) break;
        }
        // The base mesh that can no longer be simplified: its vertices are the coarsest
        // points; their neighbours are what is left around them.
        for (Mesh::VertexHandle v : m.vertices()) {
            if (m.status(v).deleted()) continue;
            PointRecord& r = points[size_t(v.idx())];
            r.neighbours = one_ring(m, v);
            r.radius = r.neighbours.empty() ? 0 : mean_distance(uint32_t(v.idx()), r.neighbours, m);
        }
    }

    // Thesis Alg. 4.2: split the longest edge at its midpoint until the point budget is met;
    // the new vertex's one-ring are its relevant neighbours. Every face of the refined
    // mesh lies inside one input triangle (its host face property), so the midpoint's
    // barycentrics in that triangle are exact.
    void subdivide(size_t target) {
        using Entry = std::pair<double, int>;  // (length, edge), longest first
        std::priority_queue<Entry> heap;
        for (Mesh::EdgeHandle e : mesh.edges()) heap.push({mesh.calc_edge_length(e), e.idx()});
        size_t start = mesh.n_vertices();
        while (mesh.n_vertices() < target && !heap.empty()) {
            auto [len, idx] = heap.top();
            heap.pop();
            Mesh::EdgeHandle e(idx);
            if (mesh.calc_edge_length(e) != len) continue;  // stale entry
            Mesh::HalfedgeHandle h = mesh.halfedge_handle(e, 0);
            Mesh::FaceHandle f = mesh.face_handle(h);
            if (!f.is_valid()) f = mesh.face_handle(mesh.opposite_halfedge_handle(h));
            Vec3 mid = (mesh.point(mesh.from_vertex_handle(h)) + mesh.point(mesh.to_vertex_handle(h))) * 0.5;
            PointRecord r;
            r.host = mesh.property(host_face, f);
            barycentric_in(scene, r.host, mid, &r.u, &r.v);
            points.push_back(r);
            Mesh::VertexHandle v = mesh.add_vertex(mid);
            mesh.split_copy(e, v);
            PointRecord& added = points.back();
            added.neighbours = one_ring(mesh, v);
            added.radius = kBisectionRadiusScale *
                           mean_distance(uint32_t(v.idx()), added.neighbours, mesh);
            for (Mesh::VertexEdgeIter it = mesh.ve_iter(v); it.is_valid(); ++it)
                heap.push({mesh.calc_edge_length(*it), it->idx()});
            size_t done = mesh.n_vertices() - start;
            if (done % 4096 == 0) report(0.5f + 0.5f * float(done) / float(target - start));
        }
    }
};

// Orders points coarse to fine (descending radius; ties by creation order, so the result
// is deterministic), keeps the first `count`, and rewrites neighbour indices.
void order_and_emit(const std::vector<PointRecord>& points, size_t count, PointHierarchy* out) {
    std::vector<uint32_t> order(points.size());
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
        return points[a].radius > points[b].radius;
    });
    order.resize(std::min(count, order.size()));
    std::vector<uint32_t> rank(points.size(), UINT32_MAX);
    for (uint32_t i = 0; i < order.size(); ++i) rank[order[i]] = i;
    *out = PointHierarchy();
    out->neighbour_offsets.push_back(0);
    for (uint32_t id : order) {
        const PointRecord& r = points[id];
        out->host_triangle.push_back(r.host);
        out->bary_u.push_back(float(r.u));
        out->bary_v.push_back(float(r.v));
        out->radius.push_back(float(r.radius));
        for (uint32_t n : r.neighbours)
            if (rank[n] != UINT32_MAX) out->neighbours.push_back(rank[n]);
        out->neighbour_offsets.push_back(uint32_t(out->neighbours.size()));
    }
}

}  // namespace

bool build_point_hierarchy(const RawScene& scene, const HierarchyConfig& config,
                           PointHierarchy* out, HierarchyStats* stats, std::string* error) {
    if (scene.triangle_count() == 0) {
        *error = "mesh has no triangles";
        return false;
    }
    if (config.point_count == 0) {
        *error = "point count must be positive";
        return false;
    }
    Builder b(scene, config);
    b.build_graph();
    if (b.mesh.n_faces() == 0) {
        *error = "mesh has no non-degenerate triangles";
        return false;
    }
    b.simplify();
    size_t input_points = b.points.size();
    b.subdivide(config.point_count);
    b.report(1.0f);
    b.stats.simplified_points = uint32_t(input_points);
    b.stats.subdivided_points = uint32_t(b.points.size() - input_points);
    order_and_emit(b.points, config.point_count, out);
    if (stats) *stats = b.stats;
    return true;
}

}  // namespace stipple::bake
