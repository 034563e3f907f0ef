#include "bake/principal_curvature.h"

#include <algorithm>
#include <cmath>

#include "bake/position_weld.h"
#include "runtime/asset_format.h"
#include "runtime/stroke_anchor.h"

namespace stipple::bake {

namespace {

glm::vec3 at(const std::vector<float>& v, size_t i) {
    return glm::vec3(v[i * 3], v[i * 3 + 1], v[i * 3 + 2]);
}

// The host triangle's tangent frame at (u, v): the runtime's (runtime/stroke_anchor.h).
SurfaceFrame frame_at(const RawScene& scene, uint32_t triangle, float u, float v) {
    const uint32_t* t = &scene.indices[size_t(triangle) * 3];
    return surface_frame(at(scene.positions, t[0]), at(scene.positions, t[1]),
                         at(scene.positions, t[2]), at(scene.normals, t[0]),
                         at(scene.normals, t[1]), at(scene.normals, t[2]), u, v);
}

// The welded mesh: one position and one area-weighted normal per welded vertex, and the
// faces that are not degenerate after welding.
struct WeldedMesh {
    std::vector<glm::vec3> position, normal;
    std::vector<uint32_t> faces;  // 3 per face
};

WeldedMesh weld_mesh(const RawScene& scene, const std::vector<uint32_t>& weld) {
    WeldedMesh m;
    const uint32_t count = weld.empty() ? 0 : *std::max_element(weld.begin(), weld.end()) + 1;
    m.position.resize(count);
    m.normal.assign(count, glm::vec3(0.0f));
    for (size_t i = 0; i < weld.size(); ++i) m.position[weld[i]] = at(scene.positions, i);
    for (size_t t = 0; t + 2 < scene.indices.size(); t += 3) {
        const uint32_t a = weld[scene.indices[t]], b = weld[scene.indices[t + 1]],
                       c = weld[scene.indices[t + 2]];
        if (a == b || b == c || a == c) continue;
        const glm::vec3 n =
            glm::cross(m.position[b] - m.position[a], m.position[c] - m.position[a]);
        m.normal[a] += n;
        m.normal[b] += n;
        m.normal[c] += n;
        m.faces.insert(m.faces.end(), {a, b, c});
    }
    for (glm::vec3& n : m.normal) {
        const float len = glm::length(n);
        n = len > 1e-30f ? n / len : glm::vec3(0.0f);
    }
    return m;
}

// The face's second fundamental form from its edges and the change of the normal along them
// (Rusinkiewicz 2004, §3: least squares over the three edges), as a 3x3 tensor in object
// space; zero for a degenerate face. *area gets the face's area.
glm::mat3 face_tensor(const WeldedMesh& m, const uint32_t* f, float* area) {
    const glm::vec3 p[3] = {m.position[f[0]], m.position[f[1]], m.position[f[2]]};
    const glm::vec3 n[3] = {m.normal[f[0]], m.normal[f[1]], m.normal[f[2]]};
    const glm::vec3 cross = glm::cross(p[1] - p[0], p[2] - p[0]);
    *area = 0.5f * glm::length(cross);
    const float edge = glm::length(p[2] - p[1]);
    if (!(*area > 0.0f) || !(edge > 0.0f)) return glm::mat3(0.0f);
    const glm::vec3 t = (p[2] - p[1]) / edge, nf = cross / (2.0f * *area);
    const glm::vec3 b = glm::cross(nf, t);
    double m00 = 0, m01 = 0, m11 = 0, m12 = 0, m22 = 0, r0 = 0, r1 = 0, r2 = 0;
    for (int i = 0; i < 3; ++i) {
        const glm::vec3 e = p[(i + 2) % 3] - p[(i + 1) % 3];
        const glm::vec3 dn = n[(i + 2) % 3] - n[(i + 1) % 3];
        const double u = glm::dot(e, t), v = glm::dot(e, b);
        const double du = glm::dot(dn, t), dv = glm::dot(dn, b);
        m00 += u * u, m01 += u * v, m11 += u * u + v * v, m12 += u * v, m22 += v * v;
        r0 += u * du, r1 += v * du + u * dv, r2 += v * dv;
    }
    // Solve [m00 m01 0; m01 m11 m12; 0 m12 m22] (e f g) = (r0 r1 r2) by Cramer's rule.
    const double det = m00 * (m11 * m22 - m12 * m12) - m01 * (m01 * m22);
    if (!(std::abs(det) > 1e-300)) return glm::mat3(0.0f);
    const double e = (r0 * (m11 * m22 - m12 * m12) - m01 * (r1 * m22 - m12 * r2)) / det;
    const double fv = (m00 * (r1 * m22 - m12 * r2) - r0 * (m01 * m22)) / det;
    const double g = (m00 * (m11 * r2 - r1 * m12) - m01 * (m01 * r2) + r0 * (m01 * m12)) / det;
    return float(e) * glm::outerProduct(t, t) +
           float(fv) * (glm::outerProduct(t, b) + glm::outerProduct(b, t)) +
           float(g) * glm::outerProduct(b, b);
}

// The tensor restricted to the plane with normal n: P T P, P = I - n n^T.
glm::mat3 project(const glm::mat3& t, const glm::vec3& n) {
    const glm::mat3 p = glm::mat3(1.0f) - glm::outerProduct(n, n);
    return p * t * p;
}

float bounding_diagonal(const std::vector<glm::vec3>& points) {
    if (points.empty()) return 0.0f;
    glm::vec3 lo = points[0], hi = points[0];
    for (const glm::vec3& p : points) lo = glm::min(lo, p), hi = glm::max(hi, p);
    return glm::length(hi - lo);
}

// The vertices' tensors interpolated at barycentric (u, v) of `triangle`.
glm::mat3 interpolated(const RawScene& scene, const VertexCurvature& vertices, uint32_t triangle,
                       float u, float v) {
    const uint32_t* t = &scene.indices[size_t(triangle) * 3];
    return u * vertices.tensor[vertices.weld[t[0]]] + v * vertices.tensor[vertices.weld[t[1]]] +
           (1.0f - u - v) * vertices.tensor[vertices.weld[t[2]]];
}

}  // namespace

VertexCurvature vertex_curvature(const RawScene& scene, const CurvatureConfig& config) {
    VertexCurvature out;
    out.weld = weld_by_position(scene);
    const WeldedMesh m = weld_mesh(scene, out.weld);
    const size_t n = m.position.size();
    std::vector<glm::mat3> sum(n, glm::mat3(0.0f));
    std::vector<float> weight(n, 0.0f);
    for (size_t f = 0; f < m.faces.size(); f += 3) {
        float area = 0.0f;
        const glm::mat3 t = face_tensor(m, &m.faces[f], &area);
        for (int k = 0; k < 3; ++k) {
            sum[m.faces[f + k]] += area * t;
            weight[m.faces[f + k]] += area;
        }
    }
    out.tensor.resize(n);
    for (size_t v = 0; v < n; ++v)
        out.tensor[v] =
            weight[v] > 0.0f ? project(sum[v] / weight[v], m.normal[v]) : glm::mat3(0.0f);
    // Smoothing: each vertex takes the mean of the tensors of its faces' corners (itself
    // included), back in its own tangent plane.
    for (int round = 0; round < config.smoothing; ++round) {
        std::fill(sum.begin(), sum.end(), glm::mat3(0.0f));
        std::fill(weight.begin(), weight.end(), 0.0f);
        for (size_t f = 0; f < m.faces.size(); f += 3) {
            const uint32_t* c = &m.faces[f];
            const glm::mat3 corners = out.tensor[c[0]] + out.tensor[c[1]] + out.tensor[c[2]];
            for (int k = 0; k < 3; ++k) {
                sum[c[k]] += corners;
                weight[c[k]] += 3.0f;
            }
        }
        for (size_t v = 0; v < n; ++v)
            if (weight[v] > 0.0f) out.tensor[v] = project(sum[v] / weight[v], m.normal[v]);
    }
    const float diagonal = bounding_diagonal(m.position);
    out.flat = diagonal > 0.0f ? 2.0f / diagonal : 0.0f;
    return out;
}

PointCurvature point_curvature(const RawScene& scene, const VertexCurvature& vertices,
                               uint32_t triangle, float u, float v) {
    const glm::mat3 tensor = interpolated(scene, vertices, triangle, u, v);
    const SurfaceFrame f = frame_at(scene, triangle, u, v);
    // The 2x2 form in the frame's (x, y), and its eigen-decomposition.
    const float a = glm::dot(f.x, tensor * f.x), b = glm::dot(f.x, tensor * f.y),
                c = glm::dot(f.y, tensor * f.y);
    const float mean = 0.5f * (a + c);
    const float radius = std::sqrt(0.25f * (a - c) * (a - c) + b * b);
    // atan2 gives the direction of the algebraically larger eigenvalue, mean + radius; the
    // other one, mean - radius, is larger in magnitude where the mean is negative.
    float angle = 0.5f * std::atan2(2.0f * b, a - c);
    if (mean < 0.0f) angle += 1.57079632679f;
    const float pi = 3.14159265359f;
    angle = std::fmod(angle + 2.0f * pi, pi);
    PointCurvature p;
    p.angle = angle < pi ? angle : 0.0f;
    p.k_major = std::abs(mean) + radius;
    p.k_minor = std::abs(std::abs(mean) - radius);
    const float denominator = p.k_major + p.k_minor + vertices.flat;
    p.confidence = denominator > 0.0f ? (p.k_major - p.k_minor) / denominator : 0.0f;
    return p;
}

BakedCurvature bake_curvature(const RawScene& scene, const PointHierarchy& points,
                              const CurvatureConfig& config) {
    const VertexCurvature vertices = vertex_curvature(scene, config);
    BakedCurvature out;
    out.angle.resize(points.size());
    out.confidence.resize(points.size());
    for (size_t i = 0; i < points.size(); ++i) {
        const PointCurvature p = point_curvature(scene, vertices, points.host_triangle[i],
                                                 points.bary_u[i], points.bary_v[i]);
        out.angle[i] = uint8_t(std::lround(p.angle / format::kCurvatureAngleStep) & 255);
        out.confidence[i] = uint8_t(
            std::lround(std::clamp(p.confidence, 0.0f, 1.0f) / format::kCurvatureConfidenceStep));
    }
    return out;
}

}  // namespace stipple::bake
