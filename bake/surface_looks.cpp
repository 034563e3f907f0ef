#include "bake/surface_looks.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "bake/scene_import.h"
#include "bake/silhouette_edges.h"
#include "bake/vertex_normals.h"
#include "runtime/asset_format.h"

namespace stipple::bake {

namespace {

// glTF 2.0 §3.9.2: the base colour texture holds sRGB-encoded colour; the factor and the
// result are linear.
float srgb_to_linear(uint8_t c) {
    const float x = float(c) / 255.0f;
    return x <= 0.04045f ? x / 12.92f : std::pow((x + 0.055f) / 1.055f, 2.4f);
}

const std::array<float, 256>& srgb_table() {
    static const std::array<float, 256> table = [] {
        std::array<float, 256> t{};
        for (int i = 0; i < 256; ++i) t[size_t(i)] = srgb_to_linear(uint8_t(i));
        return t;
    }();
    return table;
}

// Texel index `i` wrapped into [0, n) by a glTF sampler wrap mode (§3.8.4.2).
uint32_t wrap(int64_t i, uint32_t n, int mode) {
    const int64_t m = int64_t(n);
    if (mode == 33071) return uint32_t(std::clamp<int64_t>(i, 0, m - 1));  // CLAMP_TO_EDGE
    if (mode == 33648) {                                                   // MIRRORED_REPEAT
        const int64_t k = ((i % (2 * m)) + 2 * m) % (2 * m);
        return uint32_t(k < m ? k : 2 * m - 1 - k);
    }
    return uint32_t(((i % m) + m) % m);  // REPEAT
}

// Bilinear texture lookup at (u, v), row 0 at v = 0 (§3.8.4: texel centres at half
// integers), linear RGBA.
void sample(const RawTexture& t, float u, float v, float out[4]) {
    const double x = double(std::isfinite(u) ? u : 0.0f) * t.width - 0.5;
    const double y = double(std::isfinite(v) ? v : 0.0f) * t.height - 0.5;
    const double fx = std::floor(x), fy = std::floor(y);
    // Far-away coordinates lose the fraction, not the wrap: keep them within 2^31 texels.
    const int64_t x0 = int64_t(std::fmod(fx, 1 << 30)), y0 = int64_t(std::fmod(fy, 1 << 30));
    const float ax = float(x - fx), ay = float(y - fy);
    const auto& lin = srgb_table();
    for (int c = 0; c < 4; ++c) out[c] = 0.0f;
    for (int k = 0; k < 4; ++k) {
        const uint32_t tx = wrap(x0 + (k & 1), t.width, t.wrap_s);
        const uint32_t ty = wrap(y0 + (k >> 1), t.height, t.wrap_t);
        const float w = ((k & 1) ? ax : 1.0f - ax) * ((k >> 1) ? ay : 1.0f - ay);
        const uint8_t* p = &t.rgba[(size_t(ty) * t.width + tx) * 4];
        for (int c = 0; c < 3; ++c) out[c] += w * lin[p[c]];
        out[3] += w * float(p[3]) / 255.0f;
    }
}

uint8_t unorm8(float x) {
    return uint8_t(std::lround(std::clamp(x, 0.0f, 1.0f) * 255.0f));
}

bool plain_white(const RawPart& p) {
    return p.texture < 0 && !p.transparent && p.colour[0] == 1.0f && p.colour[1] == 1.0f &&
           p.colour[2] == 1.0f && p.colour[3] == 1.0f;
}

// The vertex colour (RawScene::colours) interpolated at barycentrics w on triangle t.
void vertex_colour_at(const RawScene& s, uint32_t t, const float w[3], float out[4]) {
    for (int c = 0; c < 4; ++c) out[c] = s.colours.empty() ? 1.0f : 0.0f;
    if (s.colours.empty()) return;
    for (int k = 0; k < 3; ++k)
        for (int c = 0; c < 4; ++c)
            out[c] +=
                w[k] * s.colours[size_t(s.indices[size_t(t) * 3 + size_t(k)]) * 4 + size_t(c)];
}

// Thesis §8.6: each point's colour is its part's base colour at the point (the texture
// coordinates interpolated from its host triangle's vertices at its barycentrics) times the
// interpolated vertex colour (glTF §3.9.2).
std::vector<uint8_t> point_colours(const RawScene& s, const PointHierarchy& points) {
    const RawPart white;
    std::vector<uint8_t> colours(points.size() * 4);
    for (size_t i = 0; i < points.size(); ++i) {
        const uint32_t t = points.host_triangle[i];
        const RawPart& part =
            s.parts.empty() ? white : s.parts[s.triangle_part.empty() ? 0 : s.triangle_part[t]];
        const float w[3] = {points.bary_u[i], points.bary_v[i],
                            1.0f - points.bary_u[i] - points.bary_v[i]};
        float uv[2] = {0, 0};
        if (part.texture >= 0 && !s.uvs.empty())
            for (int k = 0; k < 3; ++k)
                for (int c = 0; c < 2; ++c)
                    uv[c] +=
                        w[k] * s.uvs[size_t(s.indices[size_t(t) * 3 + size_t(k)]) * 2 + size_t(c)];
        float rgba[4], vertex[4];
        base_colour_at(s, part, uv[0], uv[1], rgba);
        vertex_colour_at(s, t, w, vertex);
        for (int c = 0; c < 4; ++c) colours[i * 4 + size_t(c)] = unorm8(rgba[c] * vertex[c]);
    }
    if (std::all_of(colours.begin(), colours.end(), [](uint8_t c) { return c == 255; }))
        colours.clear();
    return colours;
}

}  // namespace

void base_colour_at(const RawScene& scene, const RawPart& part, float u, float v, float out[4]) {
    float texel[4] = {1, 1, 1, 1};
    if (part.texture >= 0 && size_t(part.texture) < scene.textures.size())
        sample(scene.textures[size_t(part.texture)], u, v, texel);
    for (int c = 0; c < 4; ++c) out[c] = part.colour[c] * texel[c];
}

std::vector<uint32_t> crease_edges(const RawScene& scene, float degrees) {
    const double cos_crease = std::cos(double(degrees) * M_PI / 180.0);
    const std::vector<uint32_t> edges = silhouette_edges(scene);
    std::vector<uint32_t> creases;
    for (size_t e = 0; e + 3 < edges.size(); e += 4) {
        if (edges[e + 3] == format::kNoFace) continue;  // a boundary: the silhouettes' job
        const auto n0 = face_normal(scene.positions, scene.indices, edges[e + 2]);
        const auto n1 = face_normal(scene.positions, scene.indices, edges[e + 3]);
        const double l0 = std::sqrt(n0[0] * n0[0] + n0[1] * n0[1] + n0[2] * n0[2]);
        const double l1 = std::sqrt(n1[0] * n1[0] + n1[1] * n1[1] + n1[2] * n1[2]);
        if (!(l0 > 0) || !(l1 > 0)) continue;  // a degenerate face has no angle
        const double dot = (n0[0] * n1[0] + n0[1] * n1[1] + n0[2] * n1[2]) / (l0 * l1);
        if (dot < cos_crease)
            creases.insert(creases.end(), edges.begin() + long(e), edges.begin() + long(e) + 4);
    }
    return creases;
}

BakedLooks bake_looks(const RawScene& scene, const PointHierarchy& points,
                      const LooksConfig& config) {
    BakedLooks looks;
    if (config.creases) looks.creases = crease_edges(scene, config.crease_degrees);
    const bool one_plain_part =
        scene.parts.empty() || (scene.parts.size() == 1 && plain_white(scene.parts[0]));
    if (!one_plain_part || !scene.colours.empty())
        looks.point_colour = point_colours(scene, points);
    if (one_plain_part) return looks;  // no part table: the mesh is one part
    for (const RawPart& p : scene.parts) {
        for (int c = 0; c < 4; ++c) looks.part_colour.push_back(unorm8(p.colour[c]));
        looks.part_flags.push_back(p.transparent ? format::kLookPartTransparent : 0);
    }
    looks.triangle_part = scene.triangle_part;
    if (looks.triangle_part.size() != scene.triangle_count())
        looks.triangle_part.assign(scene.triangle_count(), 0);
    return looks;
}

BakeError check_transparent_names(const ImportOptions& options, const RawScene& scene) {
    std::string unknown;
    for (const std::string& name : options.transparent) {
        bool found = false;
        for (const RawPart& p : scene.parts)
            found = found || p.material_name == name ||
                    std::find(p.mesh_names.begin(), p.mesh_names.end(), name) != p.mesh_names.end();
        if (!found) unknown += (unknown.empty() ? "'" : ", '") + name + "'";
    }
    if (unknown.empty()) return BakeError();
    std::string known;  // the input's names, the first dozen
    int listed = 0;
    auto add = [&](const std::string& name) {
        if (name.empty() || known.find("'" + name + "'") != std::string::npos) return;
        if (listed++ < 12) known += (known.empty() ? "'" : ", '") + name + "'";
    };
    for (const RawPart& p : scene.parts) {
        add(p.material_name);
        for (const std::string& m : p.mesh_names) add(m);
    }
    if (listed > 12) known += ", ...";
    return bake_error(BakeErrorCode::invalid_option,
                      "--transparent: no material or mesh named " + unknown +
                          (known.empty() ? " (the input names none)" : " (names: " + known + ")"));
}

}  // namespace stipple::bake
