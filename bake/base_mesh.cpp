#include "bake/base_mesh.h"

#include <algorithm>
#include <cmath>

namespace stipple::bake {

double BaseMesh::area(uint32_t f) const {
    return 0.5 * ((corner(f, 1) - corner(f, 0)) % (corner(f, 2) - corner(f, 0))).norm();
}

Vec3d BaseMesh::unit_normal(uint32_t f) const {
    const Vec3d n = (corner(f, 1) - corner(f, 0)) % (corner(f, 2) - corner(f, 0));
    const double len = n.norm();
    return len > 0 ? n / len : Vec3d(0, 0, 0);
}

void BaseMesh::faces_around(uint32_t f, std::vector<uint32_t>* out) const {
    out->clear();
    for (int k = 0; k < 3; ++k) {
        const uint32_t v = faces[size_t(f) * 3 + size_t(k)];
        out->insert(out->end(), vf.begin() + vf_offsets[v], vf.begin() + vf_offsets[v + 1]);
    }
    std::sort(out->begin(), out->end());
    out->erase(std::unique(out->begin(), out->end()), out->end());
}

void BaseMesh::build_vertex_faces() {
    vf_offsets.assign(positions.size() + 1, 0);
    for (uint32_t v : faces) ++vf_offsets[v + 1];
    for (size_t v = 0; v < positions.size(); ++v) vf_offsets[v + 1] += vf_offsets[v];
    vf.resize(faces.size());
    std::vector<uint32_t> fill(vf_offsets.begin(), vf_offsets.end() - 1);
    for (uint32_t f = 0; f < face_count(); ++f)
        for (int k = 0; k < 3; ++k) vf[fill[faces[size_t(f) * 3 + size_t(k)]]++] = f;
}

namespace {

// Barycentric weights of x (a point of the face's plane) for the face's 3 corners.
bool barycentric(const BaseMesh& m, uint32_t f, const Vec3d& x, double l[3]) {
    const Vec3d a = m.corner(f, 0), e1 = m.corner(f, 1) - a, e2 = m.corner(f, 2) - a, d = x - a;
    const double d11 = e1 | e1, d12 = e1 | e2, d22 = e2 | e2, x1 = d | e1, x2 = d | e2;
    const double den = d11 * d22 - d12 * d12;
    if (!(den > 0)) return false;
    l[1] = (d22 * x1 - d12 * x2) / den;
    l[2] = (d11 * x2 - d12 * x1) / den;
    l[0] = 1 - l[1] - l[2];
    return true;
}

}  // namespace

void walk_on_surface(const BaseMesh& mesh, uint32_t* face, Vec3d* p, Vec3d step) {
    uint32_t f = *face;
    Vec3d at = *p;
    // A step crosses a few faces at most; the bound only guards against rounding ping-pong.
    for (int crossing = 0; crossing < 64; ++crossing) {
        const Vec3d n = mesh.unit_normal(f);
        step -= n * (step | n);
        double l[3], m[3];
        if (step.sqrnorm() == 0 || !barycentric(mesh, f, at, l) ||
            !barycentric(mesh, f, at + step, m))
            break;
        // The first edge the segment at -> at + step crosses: where a weight reaches 0.
        int exit = -1;
        double s_exit = 1;
        for (int i = 0; i < 3; ++i) {
            if (m[i] >= 0) continue;
            const double s = std::max(l[i], 0.0) / (std::max(l[i], 0.0) - m[i]);
            if (s < s_exit) {
                s_exit = s;
                exit = i;
            }
        }
        if (exit < 0) {
            at += step;
            break;
        }
        const int k = (exit + 1) % 3;  // edge (v[k], v[k+1]) lies opposite corner `exit`
        const uint32_t i0 = mesh.faces[size_t(f) * 3 + size_t(k)];
        const uint32_t i1 = mesh.faces[size_t(f) * 3 + size_t((k + 1) % 3)];
        const Vec3d v0 = mesh.positions[i0], v1 = mesh.positions[i1];
        const Vec3d edge = v1 - v0;
        const double t = std::clamp(((at + step * s_exit - v0) | edge) / edge.sqrnorm(), 0.0, 1.0);
        at = v0 + edge * t;
        const uint32_t g = mesh.across[size_t(f) * 3 + size_t(k)];
        if (g == kNoFace) break;  // boundary: stop on the edge
        // Turn the rest of the step about the shared edge into g's plane.
        const Vec3d rest = step * (1 - s_exit), dir = edge / edge.norm();
        const double along = rest | dir, off = (rest - dir * along).norm();
        Vec3d inward(0, 0, 0);
        for (int c = 0; c < 3; ++c) {
            const uint32_t v = mesh.faces[size_t(g) * 3 + size_t(c)];
            if (v == i0 || v == i1) continue;
            inward = mesh.positions[v] - at;
        }
        inward -= dir * (inward | dir);
        const double inward_len = inward.norm();
        if (inward_len == 0) break;
        step = dir * along + inward * (off / inward_len);
        f = g;
    }
    *face = f;
    *p = at;
}

}  // namespace stipple::bake
