#include "bake/point_hierarchy.h"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <new>
#include <numeric>
#include <queue>
#include <tuple>

#include "anim/finite.h"
#include "bake/bake_random.h"
#include "bake/base_mesh.h"
#include "bake/particle_parents.h"
#include "bake/point_hierarchy_collapse.h"
#include "bake/radius_calibration.h"
#include "bake/sample_elimination.h"
#include "bake/surface_projection.h"
#include "bake/token_relaxation.h"

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

Vec3 input_position(const RawScene& s, uint32_t vertex) {
    const float* p = &s.positions[size_t(vertex) * 3];
    return Vec3(p[0], p[1], p[2]);
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

// Randomization may not create angles below this (see move_is_valid).
constexpr double kSliverDegrees = 10;
const double kSliverCosine = std::cos(kSliverDegrees * M_PI / 180);

// Cosine of the smallest angle of triangle (p, a, b); 1 if degenerate.
double smallest_angle_cosine(const Vec3& p, const Vec3& a, const Vec3& b) {
    const Vec3 c[3] = {p, a, b};
    double worst = -1;
    for (int i = 0; i < 3; ++i) {
        const Vec3 u = c[(i + 1) % 3] - c[i], w = c[(i + 2) % 3] - c[i];
        const double den = u.norm() * w.norm();
        worst = std::max(worst, den > 0 ? (u | w) / den : 1.0);
    }
    return worst;
}

struct Builder {
    const RawScene& scene;
    const HierarchyConfig& config;
    HierarchyStats stats;
    Mesh mesh;
    OpenMesh::FPropHandleT<uint32_t> host_face;  // input triangle each face lies in
    std::vector<PointRecord> points;             // indexed like mesh vertices
    std::vector<uint32_t> welded;                // input vertex -> position class
    std::vector<uint32_t> merged_into;           // the merge record (bake/particle_parents.h)
    std::unique_ptr<InputSurface> surface;
    Rng rng;
    bool jitter_off = false;  // ch. 5 refines without randomizing
    const char* phase = "subdivide";

    Builder(const RawScene& s, const HierarchyConfig& c) : scene(s), config(c), rng{c.seed} {
        mesh.add_property(host_face);
    }

    double uniform() { return rng.uniform(); }

    // A random point of the triangle (p, a, b) within `jitter` of p: s, t uniform over the
    // corner triangle s + t <= 1, scaled (§4.4.1 "a small region between the input vertex and
    // the other vertices of the face").
    Vec3 jittered(const Vec3& p, const Vec3& a, const Vec3& b) {
        double s = uniform(), t = uniform();
        if (s + t > 1) {
            s = 1 - s;
            t = 1 - t;
        }
        const double j = double(config.jitter);
        return p + (a - p) * (s * j) + (b - p) * (t * j);
    }

    // A random move of boundary vertex v along the boundary: up to `jitter` of the way to
    // one of its two boundary neighbours. §4.4.1's move into a random incident face would
    // pull it off the boundary, and the randomized mesh, which subdivision fills, would no
    // longer cover the input: on a plane of 8 triangles (SimpleSkin) a sixth of the 16-px
    // blocks inside the plane drew no dot. A corner (the boundary turns by more than ~2.5
    // degrees) stays put: moving it along either edge would cut the corner off.
    Vec3 jittered_on_boundary(Mesh::VertexHandle v) {
        Vec3 ends[2];
        int count = 0;
        for (Mesh::VertexOHalfedgeIter h = mesh.voh_iter(v); h.is_valid() && count < 2; ++h) {
            const Mesh::HalfedgeHandle g = *h;
            if (mesh.is_boundary(g) || mesh.is_boundary(mesh.opposite_halfedge_handle(g)))
                ends[count++] = mesh.point(mesh.to_vertex_handle(g));
        }
        const Vec3 p = mesh.point(v);
        if (count < 2) return p;
        const Vec3 a = ends[0] - p, b = ends[1] - p;
        const double den = a.norm() * b.norm();
        if (!(den > 0) || (a | b) > -0.999 * den) return p;
        const Vec3 to = ends[rng.below(2)];
        return p + (to - p) * (uniform() * double(config.jitter));
    }

    // True if moving vertex v to q flips none of its faces (a fold, §4.4.2 "invalid
    // projection": each face normal keeps its side) and makes none of them a sliver (an
    // angle under kSliverDegrees that was not there before: §4.4.1 bounds the randomize
    // region because "we would generate thin polygons, which we want to avoid").
    bool move_is_valid(Mesh::VertexHandle v, const Vec3& q) const {
        const Vec3 p = mesh.point(v);
        for (Mesh::ConstVertexOHalfedgeIter h = mesh.cvoh_iter(v); h.is_valid(); ++h) {
            if (!mesh.face_handle(*h).is_valid()) continue;
            const Vec3 a = mesh.point(mesh.to_vertex_handle(*h));
            const Vec3 b = mesh.point(mesh.to_vertex_handle(mesh.next_halfedge_handle(*h)));
            const Vec3 before = (a - p) % (b - p);
            const Vec3 after = (a - q) % (b - q);
            if ((before | after) <= 0) return false;
            const double thin = smallest_angle_cosine(q, a, b);
            if (thin > kSliverCosine && thin > smallest_angle_cosine(p, a, b)) return false;
        }
        return true;
    }

    void set_surface_point(Mesh::VertexHandle v, const SurfacePoint& sp) {
        mesh.point(v) = sp.position;
        PointRecord& r = points[size_t(v.idx())];
        r.host = sp.host;
        r.u = sp.u;
        r.v = sp.v;
    }

    // Thesis Alg. 4.4: every input vertex moves inside a random incident face of the
    // randomized mesh Mr (whose earlier vertices have already moved, so the face need not
    // lie on the input surface), then is projected onto the input mesh Mi along the summed
    // normals of its neighbours (§4.4.2); a move that folds a face around it is discarded.
    void randomize_inputs() {
        if (config.jitter <= 0) return;
        std::vector<Mesh::HalfedgeHandle> out;
        std::vector<uint32_t> seeds;
        size_t done = 0;
        for (Mesh::VertexHandle v : mesh.vertices()) {
            if (++done % 8192 == 0) report("randomize", float(done) / float(mesh.n_vertices()));
            out.clear();
            seeds.assign(1, points[size_t(v.idx())].host);
            Vec3 direction = surface->normal(seeds[0]);
            for (Mesh::VertexOHalfedgeIter h = mesh.voh_iter(v); h.is_valid(); ++h) {
                if (mesh.face_handle(*h).is_valid()) out.push_back(*h);
                const uint32_t host = points[size_t(mesh.to_vertex_handle(*h).idx())].host;
                seeds.push_back(host);
                direction += surface->normal(host);
            }
            if (out.empty()) continue;
            Mesh::HalfedgeHandle h = out[rng.below(out.size())];
            const Vec3 a = mesh.point(mesh.to_vertex_handle(h));
            const Vec3 b = mesh.point(mesh.to_vertex_handle(mesh.next_halfedge_handle(h)));
            const Vec3 q =
                mesh.is_boundary(v) ? jittered_on_boundary(v) : jittered(mesh.point(v), a, b);
            const SurfacePoint sp = surface->project(q, direction, seeds.data(), int(seeds.size()));
            if (!move_is_valid(v, sp.position)) {
                ++stats.discarded_randomizations;
                continue;
            }
            set_surface_point(v, sp);
        }
    }

    void report(const char* name, float fraction) const { config.report(name, fraction); }

    Mesh::VertexHandle new_vertex(const Vec3& p, uint32_t triangle, int corner) {
        PointRecord r;
        r.host = triangle;
        r.u = corner == 0 ? 1 : 0;
        r.v = corner == 1 ? 1 : 0;
        points.push_back(r);
        return mesh.add_vertex(p);
    }

    // Connectivity graph (§4.1). Faces that would make the mesh non-manifold get copies of their
    // own vertices rather than being dropped, so every input triangle can host points.
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
        welded = remap;
        stats.welded_vertices = welded_count;
        std::vector<Mesh::VertexHandle> handle(welded_count);
        for (uint32_t t = 0; t < scene.triangle_count(); ++t) {
            const uint32_t* tri = &scene.indices[size_t(t) * 3];
            uint32_t w[3] = {remap[tri[0]], remap[tri[1]], remap[tri[2]]};
            Vec3 p[3] = {input_position(scene, tri[0]), input_position(scene, tri[1]),
                         input_position(scene, tri[2])};
            if (w[0] == w[1] || w[1] == w[2] || w[0] == w[2] ||
                ((p[1] - p[0]) % (p[2] - p[0])).norm() == 0) {
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
                Mesh::HalfedgeHandle h = m.halfedge_handle(e, int(rng.next() & 1));
                if (!m.is_collapse_ok(h)) h = m.opposite_halfedge_handle(h);
                if (!m.is_collapse_ok(h)) continue;
                Mesh::VertexHandle removed = m.from_vertex_handle(h), kept = m.to_vertex_handle(h);
                PointRecord& r = points[size_t(removed.idx())];
                r.neighbours = one_ring(m, removed);
                r.radius = mean_distance(uint32_t(removed.idx()), r.neighbours, m);
                collapse_halfedge(m, h);  // OpenMesh's collapse without its O(valence) walk
                record_merge(&merged_into, uint32_t(removed.idx()), uint32_t(kept.idx()));
                --remaining;
                for (Mesh::VertexEdgeIter it = m.ve_iter(kept); it.is_valid(); ++it)
                    heap.push({length(*it), it->idx()});
                if (remaining % 4096 == 0)
                    report("simplify", float(total - remaining) / float(total));
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

    using Heap = std::priority_queue<std::pair<double, int>>;  // (length, edge), longest first

    // Thesis Alg. 4.3, refineLocal: an edge is split only when it is the longest edge of the
    // faces on both its sides; otherwise that longer edge is refined first. This keeps
    // bisection from creating slivers even where randomization made edges uneven.
    void refine_local(Mesh::EdgeHandle e, Heap* heap, int depth) {
        for (int round = 0; round < 8; ++round) {
            const double len = mesh.calc_edge_length(e);
            Mesh::EdgeHandle longest = e;
            double longest_len = len;
            for (int side = 0; side < 2; ++side) {
                Mesh::HalfedgeHandle h = mesh.halfedge_handle(e, side);
                if (!mesh.face_handle(h).is_valid()) continue;
                for (Mesh::HalfedgeHandle g :
                     {mesh.next_halfedge_handle(h), mesh.prev_halfedge_handle(h)}) {
                    const double l = mesh.calc_edge_length(mesh.edge_handle(g));
                    if (l > longest_len * (1 + 1e-9)) {
                        longest = mesh.edge_handle(g);
                        longest_len = l;
                    }
                }
            }
            if (longest == e || depth > 16) break;
            refine_local(longest, heap, depth + 1);
            ++stats.legal_splits;
        }
        split(e, heap);
    }

    // Thesis Alg. 4.5 for one edge: split at the midpoint, project onto the input surface
    // along the summed normals of the neighbourhood, randomize inside a random incident face
    // and project again; a randomization that folds the mesh is discarded. The new vertex's
    // one-ring are its relevant neighbours (§4.5).
    void split(Mesh::EdgeHandle e, Heap* heap) {
        const Mesh::HalfedgeHandle h = mesh.halfedge_handle(e, 0);
        const Mesh::VertexHandle a = mesh.from_vertex_handle(h), b = mesh.to_vertex_handle(h);
        uint32_t seeds[4];
        int seed_count = 0;
        seeds[seed_count++] = points[size_t(a.idx())].host;
        seeds[seed_count++] = points[size_t(b.idx())].host;
        for (Mesh::HalfedgeHandle side : {h, mesh.opposite_halfedge_handle(h)})
            if (mesh.face_handle(side).is_valid())
                seeds[seed_count++] =
                    points[size_t(mesh.to_vertex_handle(mesh.next_halfedge_handle(side)).idx())]
                        .host;
        Vec3 direction(0, 0, 0);
        for (int i = 0; i < seed_count; ++i) direction += surface->normal(seeds[i]);
        const Vec3 mid = (mesh.point(a) + mesh.point(b)) * 0.5;
        const SurfacePoint projected = surface->project(mid, direction, seeds, seed_count);

        points.push_back(PointRecord());
        const Mesh::VertexHandle v = mesh.add_vertex(projected.position);
        mesh.split_copy(e, v);
        set_surface_point(v, projected);
        if (config.jitter > 0 && !jitter_off) {
            std::vector<Mesh::HalfedgeHandle> out;
            for (Mesh::VertexOHalfedgeIter o = mesh.voh_iter(v); o.is_valid(); ++o)
                if (mesh.face_handle(*o).is_valid()) out.push_back(*o);
            if (!out.empty()) {
                Mesh::HalfedgeHandle o = out[rng.below(out.size())];
                const Vec3 q =
                    mesh.is_boundary(v)
                        ? jittered_on_boundary(v)
                        : jittered(projected.position, mesh.point(mesh.to_vertex_handle(o)),
                                   mesh.point(mesh.to_vertex_handle(mesh.next_halfedge_handle(o))));
                seeds[0] = projected.host;
                const SurfacePoint moved = surface->project(q, direction, seeds, seed_count);
                if (move_is_valid(v, moved.position))
                    set_surface_point(v, moved);
                else
                    ++stats.discarded_randomizations;
            }
        }
        record_split(&merged_into, mesh, v, a, b);
        PointRecord& added = points.back();
        added.neighbours = one_ring(mesh, v);
        added.radius =
            kBisectionRadiusScale * mean_distance(uint32_t(v.idx()), added.neighbours, mesh);
        for (Mesh::VertexEdgeIter it = mesh.ve_iter(v); it.is_valid(); ++it)
            heap->push({mesh.calc_edge_length(*it), it->idx()});
    }

    // Ch. 5 needs at least one polygon per point: bisect (without randomization, so every
    // refined face stays inside its input face) to `faces` faces; as arrays (bake/base_mesh.h).
    BaseMesh base_mesh(size_t faces) {
        phase = "refine";
        while (mesh.n_faces() < faces) {
            const size_t before = mesh.n_faces();
            subdivide(mesh.n_vertices() + (faces - mesh.n_faces() + 1) / 2);
            if (mesh.n_faces() == before) break;
        }
        BaseMesh base;
        base.positions.reserve(mesh.n_vertices());
        for (Mesh::VertexHandle v : mesh.vertices()) base.positions.push_back(mesh.point(v));
        base.faces.reserve(mesh.n_faces() * 3);
        base.across.reserve(mesh.n_faces() * 3);
        base.host.reserve(mesh.n_faces());
        for (Mesh::FaceHandle f : mesh.faces()) {
            Mesh::HalfedgeHandle h = mesh.halfedge_handle(f);
            for (int k = 0; k < 3; ++k) {  // edge k = (from(h), to(h)) = (v[k], v[k + 1])
                base.faces.push_back(uint32_t(mesh.from_vertex_handle(h).idx()));
                const Mesh::FaceHandle g = mesh.opposite_face_handle(h);
                base.across.push_back(g.is_valid() ? uint32_t(g.idx()) : kNoFace);
                h = mesh.next_halfedge_handle(h);
            }
            base.host.push_back(mesh.property(host_face, f));
        }
        base.build_vertex_faces();
        return base;
    }

    // Thesis Alg. 4.2/4.5: split the longest edge until the point budget is met.
    // Faces with an angle under kSliverDegrees (slivers), for the stats.
    uint32_t sliver_faces() const {
        uint32_t thin = 0;
        for (Mesh::FaceHandle f : mesh.faces()) {
            Mesh::ConstFaceVertexIter v = mesh.cfv_iter(f);
            const Vec3 p = mesh.point(*v), a = mesh.point(*++v), b = mesh.point(*++v);
            thin += smallest_angle_cosine(p, a, b) > kSliverCosine;
        }
        return thin;
    }

    void subdivide(size_t target) {
        if (!jitter_off) stats.slivers_before_subdivision = sliver_faces();
        Heap heap;
        for (Mesh::EdgeHandle e : mesh.edges()) heap.push({mesh.calc_edge_length(e), e.idx()});
        const size_t start = mesh.n_vertices();
        size_t reported = 0;
        while (mesh.n_vertices() < target && !heap.empty()) {
            auto [len, idx] = heap.top();
            heap.pop();
            Mesh::EdgeHandle e(idx);
            if (mesh.calc_edge_length(e) != len) continue;  // stale entry
            refine_local(e, &heap, 0);
            const size_t done = mesh.n_vertices() - start;
            if (done - reported >= 4096) {
                reported = done;
                report(phase, float(done) / float(target - start));
            }
        }
        if (!jitter_off) stats.slivers_after_subdivision = sliver_faces();
    }
};

// Orders points coarse to fine (descending radius; ties by creation order, so the result
// is deterministic), keeps the first `count`, and rewrites neighbour indices.
void order_and_emit(const std::vector<PointRecord>& points, const std::vector<uint32_t>& merged,
                    size_t count, PointHierarchy* out) {
    std::vector<uint32_t> order(points.size());
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(),
                     [&](uint32_t a, uint32_t b) { return points[a].radius > points[b].radius; });
    order.resize(std::min(count, order.size()));
    std::vector<uint32_t> rank(points.size(), UINT32_MAX);
    for (uint32_t i = 0; i < order.size(); ++i) rank[order[i]] = i;
    *out = PointHierarchy();
    out->record_parent = record_parents(merged, order, rank);
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

// Keeps the first `count` points and drops neighbour references past them.
void truncate(size_t count, PointHierarchy* p) {
    if (p->size() <= count) return;
    PointHierarchy t;
    t.neighbour_offsets.push_back(0);
    for (size_t i = 0; i < count; ++i) {
        t.host_triangle.push_back(p->host_triangle[i]);
        t.bary_u.push_back(p->bary_u[i]);
        t.bary_v.push_back(p->bary_v[i]);
        t.radius.push_back(p->radius[i]);
        for (uint32_t k = p->neighbour_offsets[i]; k < p->neighbour_offsets[i + 1]; ++k)
            if (p->neighbours[k] < count) t.neighbours.push_back(p->neighbours[k]);
        t.neighbour_offsets.push_back(uint32_t(t.neighbours.size()));
    }
    *p = std::move(t);
}

// The input and the options, checked before any work.
BakeError check_input(const RawScene& scene, const HierarchyConfig& config) {
    if (scene.triangle_count() == 0) return malformed_input("mesh has no triangles");
    if (config.point_count == 0)
        return bake_error(BakeErrorCode::invalid_option, "point count must be positive");
    if (!all_finite(scene.positions))
        return malformed_input("mesh has a vertex position that is not finite");
    for (uint32_t i : scene.indices)
        if (i >= scene.vertex_count())
            return malformed_input("mesh has a triangle index out of range");
    return BakeError();
}

// Thesis ch. 5 (relax) or the random baseline: both start from a base mesh of about one
// polygon per point (more for relax, RelaxConfig::polygons_per_point).
void build_from_base_mesh(Builder& b, const HierarchyConfig& config, PointHierarchy* out,
                          HierarchyStats* stats) {
    b.jitter_off = true;
    const size_t input_faces = b.mesh.n_faces();
    const double per_point = config.method == HierarchyMethod::relax
                                 ? std::max(config.relax.polygons_per_point, 1.0)
                                 : 1.0;
    const BaseMesh base = b.base_mesh(size_t(std::ceil(double(config.point_count) * per_point)));
    b.mesh.clear();  // the arrays above are all ch. 5 needs
    b.mesh.garbage_collection();
    std::vector<PointRecord>().swap(b.points);
    HierarchyStats st = b.stats;
    if (config.method == HierarchyMethod::relax)
        relax_hierarchy(*b.surface, base, config, out, &st);
    else
        random_hierarchy(*b.surface, base, config, out);
    truncate(config.point_count, out);
    st.simplified_points = uint32_t(std::min<size_t>(input_faces, out->size()));
    st.subdivided_points = uint32_t(out->size() - st.simplified_points);
    if (stats) *stats = st;
}

// Thesis ch. 4: randomize the input vertices, simplify, subdivide, then order the points.
void build_by_simplification(Builder& b, const HierarchyConfig& config, PointHierarchy* out,
                             HierarchyStats* stats) {
    b.randomize_inputs();
    b.simplify();
    size_t input_points = b.points.size();
    b.subdivide(config.point_count);
    b.stats.simplified_points = uint32_t(input_points);
    b.stats.subdivided_points = uint32_t(b.points.size() - input_points);
    b.report("order", 0);
    order_and_emit(b.points, b.merged_into, config.point_count, out);
    calibrate_radii(b.surface->area(), out);
    b.report("order", 1);
    if (stats) *stats = b.stats;
}

BakeError build(const RawScene& scene, const HierarchyConfig& config, PointHierarchy* out,
                HierarchyStats* stats) {
    const BakeError checked = check_input(scene, config);
    if (!checked.ok()) return checked;
    // Sample elimination needs no connectivity: samples are drawn on the input triangles.
    if (config.method == HierarchyMethod::eliminate)
        return eliminate_hierarchy(scene, config, out, stats);
    Builder b(scene, config);
    b.build_graph();
    if (b.mesh.n_faces() == 0) return malformed_input("mesh has no non-degenerate triangles");
    b.surface = std::make_unique<InputSurface>(scene, b.welded);
    if (config.method != HierarchyMethod::simplify)
        build_from_base_mesh(b, config, out, stats);
    else
        build_by_simplification(b, config, out, stats);
    if (stats) stats->projection_candidates = b.surface->candidates_examined();
    return BakeError();
}

}  // namespace

BakeError build_point_hierarchy(const RawScene& scene, const HierarchyConfig& config,
                                PointHierarchy* out, HierarchyStats* stats) {
    try {
        return build(scene, config, out, stats);
    } catch (const std::bad_alloc&) {
        *out = PointHierarchy();
        return bake_error(BakeErrorCode::out_of_memory, "out of memory");
    }
}

}  // namespace stipple::bake
