// The point of triangle abc nearest to p (Ericson, Real-Time Collision Detection §5.1.5), for
// any 3-vector type with +, - and * by a scalar; `dot` is its dot product. Used in double
// precision by the surface projection (bake/surface_projection.cpp, OpenMesh's Vec3d) and in
// float by the occluder's gap queries (bake/triangle_grid.cpp, glm::vec3).
#pragma once

namespace stipple::bake {

template <typename V, typename Dot>
V closest_on_triangle(const V& p, const V& a, const V& b, const V& c, Dot dot) {
    const V ab = b - a, ac = c - a, ap = p - a;
    const auto d1 = dot(ab, ap), d2 = dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) return a;
    const V bp = p - b;
    const auto d3 = dot(ab, bp), d4 = dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) return b;
    const auto vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
    const V cp = p - c;
    const auto d5 = dot(ab, cp), d6 = dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) return c;
    const auto vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
    const auto va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    const auto denom = decltype(va)(1) / (va + vb + vc);
    return a + ab * (vb * denom) + ac * (vc * denom);
}

}  // namespace stipple::bake
