// glTF 2.0 mesh primitives, §3.7.2: topology into triangles, the vertices the triangles use,
// POSITION and NORMAL, skin attributes (gltf_skins.cpp) and morph target deltas.
#include <algorithm>
#include <cmath>
#include <limits>

#include "anim/finite.h"
#include "bake/gltf_parts.h"
#include "bake/vertex_normals.h"
#include "runtime/asset_limits.h"

namespace stipple::bake::gltf {

namespace {

const char* mode_name(int mode) {
    switch (mode) {
        case TINYGLTF_MODE_POINTS:
            return "POINTS";
        case TINYGLTF_MODE_LINE:
            return "LINES";
        case TINYGLTF_MODE_LINE_LOOP:
            return "LINE_LOOP";
        default:
            return "LINE_STRIP";
    }
}

// The primitive's vertex attributes as written, before compaction.
struct Attributes {
    std::vector<float> positions;  // 3 per vertex
    std::vector<float> normals;    // 3 per vertex, or empty (no NORMAL)
    size_t vertex_count = 0;
};

BakeError read_attributes(const MeshContext& ctx, const tinygltf::Primitive& prim,
                          const std::string& label, int position_accessor, Attributes* out) {
    // KHR_mesh_quantization allows integer positions and normalized normals.
    const unsigned position_formats = ctx.quantized ? kAnyQuantized : kF32;
    const unsigned normal_formats = ctx.quantized ? (kF32 | kI8N | kI16N) : kF32;
    BakeError read = read_accessor(ctx.model, position_accessor, TINYGLTF_TYPE_VEC3,
                                   position_formats, &out->positions);
    if (!read.ok()) return prefixed(label + " POSITION: ", read);
    out->vertex_count = out->positions.size() / 3;
    if (out->vertex_count > limits::kMaxVertices) {
        return bake_error(BakeErrorCode::unsupported, label + ": too many vertices");
    }
    const auto normal_it = prim.attributes.find("NORMAL");
    if (normal_it == prim.attributes.end()) return BakeError();
    read = read_accessor(ctx.model, normal_it->second, TINYGLTF_TYPE_VEC3, normal_formats,
                         &out->normals);
    if (!read.ok()) return prefixed(label + " NORMAL: ", read);
    if (out->normals.size() != out->positions.size()) {
        // §3.7.2.1: all attribute accessors of a primitive have the same count.
        return malformed_input(label + ": NORMAL count " + str(out->normals.size() / 3) +
                               " differs from POSITION count " + str(out->vertex_count));
    }
    return BakeError();
}

// The vertex sequence (indices, or 0..n-1), then triangles by topology (§3.7.2.1
// "Topology types"). Strips and fans keep the winding of their first triangle.
BakeError read_triangles(const MeshContext& ctx, const tinygltf::Primitive& prim,
                         const std::string& label, int mode, size_t vertex_count,
                         std::vector<uint32_t>* triangles) {
    std::vector<uint32_t> sequence;
    if (prim.indices >= 0) {
        const BakeError read = read_accessor(ctx.model, prim.indices, TINYGLTF_TYPE_SCALAR,
                                             kU8 | kU16 | kU32, &sequence);
        if (!read.ok()) return prefixed(label + " indices: ", read);
        for (uint32_t index : sequence) {
            if (index >= vertex_count) {
                return malformed_input(label + ": index " + str(size_t(index)) +
                                       " out of range (vertex count " + str(vertex_count) + ")");
            }
        }
    } else {
        sequence.resize(vertex_count);
        for (size_t i = 0; i < vertex_count; ++i) sequence[i] = uint32_t(i);
    }
    const size_t n = sequence.size();
    if (mode == TINYGLTF_MODE_TRIANGLES) {
        if (n % 3 != 0) {
            return malformed_input(label + ": " + (prim.indices >= 0 ? "index" : "vertex") +
                                   " count " + str(n) + " is not a multiple of 3");
        }
        *triangles = std::move(sequence);
        return BakeError();
    }
    for (size_t i = 0; i + 2 < n; ++i) {
        if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
            // {v_i, v_(i+1+i%2), v_(i+2-i%2)}: every other triangle flips to keep winding.
            triangles->insert(triangles->end(),
                              {sequence[i], sequence[i + 1 + i % 2], sequence[i + 2 - i % 2]});
        } else {
            triangles->insert(triangles->end(), {sequence[i + 1], sequence[i + 2], sequence[0]});
        }
    }
    return BakeError();
}

// Keeps only the vertices the triangles use, so unused (and unvalidated) data is dropped:
// out->indices become local, `used` lists the old index of each kept vertex.
BakeError compact_vertices(const std::vector<uint32_t>& triangles, const Attributes& attributes,
                           const std::string& label, Primitive* out, std::vector<uint32_t>* used) {
    constexpr uint32_t kUnused = std::numeric_limits<uint32_t>::max();
    std::vector<uint32_t> remap(attributes.vertex_count, kUnused);
    out->indices.resize(triangles.size());
    for (size_t i = 0; i < triangles.size(); ++i) {
        uint32_t& slot = remap[triangles[i]];
        if (slot == kUnused) {
            slot = uint32_t(used->size());
            used->push_back(triangles[i]);
        }
        out->indices[i] = slot;
    }
    out->positions.resize(used->size() * 3);
    for (size_t v = 0; v < used->size(); ++v) {
        const float* p = &attributes.positions[size_t((*used)[v]) * 3];
        if (!all_finite(p, 3)) {
            return malformed_input(label + ": POSITION of vertex " + str(size_t((*used)[v])) +
                                   " is not finite");
        }
        std::copy(p, p + 3, &out->positions[v * 3]);
    }
    return BakeError();
}

// Normals: given ones are normalised; missing or unusable ones are computed from the
// triangles (area-weighted). Note: §3.7.2.1 asks for flat normals when NORMAL is
// absent; smooth normals over shared vertices are what the stipple shading wants.
void assign_primitive_normals(const MeshContext& ctx, const std::vector<float>& normals,
                              const std::vector<uint32_t>& used, const std::string& label,
                              Primitive* out) {
    compute_vertex_normals(out->positions, out->indices, &out->normals);
    if (normals.empty()) return;
    size_t repaired = 0;
    for (size_t v = 0; v < used.size(); ++v) {
        const float* nv = &normals[size_t(used[v]) * 3];
        const double len =
            std::sqrt(double(nv[0]) * nv[0] + double(nv[1]) * nv[1] + double(nv[2]) * nv[2]);
        if (all_finite(nv, 3) && len > 1e-12) {
            for (int c = 0; c < 3; ++c) out->normals[v * 3 + size_t(c)] = float(nv[c] / len);
        } else {
            ++repaired;
        }
    }
    if (repaired) {
        ctx.warnings->push_back(label + ": " + str(repaired) +
                                " zero or non-finite normals recomputed");
    }
}

// The deltas of one target attribute for the vertices `used`, into `dst` (3 per vertex).
BakeError read_target_deltas(const MeshContext& ctx, int accessor, const std::string& tlabel,
                             const char* attribute, size_t vertex_count,
                             const std::vector<uint32_t>& used, std::vector<float>* dst) {
    std::vector<float> deltas;
    const unsigned formats = ctx.quantized ? kAnyQuantized : kF32;
    const BakeError read = read_accessor(ctx.model, accessor, TINYGLTF_TYPE_VEC3, formats, &deltas);
    if (!read.ok()) return prefixed(tlabel + " " + attribute + ": ", read);
    if (deltas.size() != vertex_count * 3) {
        return malformed_input(tlabel + ": " + attribute + " count " + str(deltas.size() / 3) +
                               " differs from POSITION count " + str(vertex_count));
    }
    dst->resize(used.size() * 3);
    for (size_t v = 0; v < used.size(); ++v) {
        const float* d = &deltas[size_t(used[v]) * 3];
        if (!all_finite(d, 3)) {
            return malformed_input(tlabel + ": " + attribute + " delta of vertex " +
                                   str(size_t(used[v])) + " is not finite");
        }
        std::copy(d, d + 3, &(*dst)[v * 3]);
    }
    return BakeError();
}

// Reads the morph targets of a primitive (§3.7.2.2) for the vertices `used` (old indices).
// POSITION and NORMAL deltas are VEC3 floats (or, with KHR_mesh_quantization, normalized or
// plain integers); TANGENT deltas are ignored (the runtime has no tangents). NORMAL deltas
// are dropped when the primitive's normals are computed, since they would be deltas to
// normals that do not exist.
BakeError read_morph_targets(const MeshContext& ctx, const tinygltf::Primitive& prim,
                             const std::string& label, size_t vertex_count,
                             const std::vector<uint32_t>& used, bool has_normals, Primitive* out) {
    for (size_t t = 0; t < prim.targets.size(); ++t) {
        const std::string tlabel = label + " target " + str(t);
        std::vector<float> positions(used.size() * 3, 0.0f);
        std::vector<float> normals;
        for (const char* attribute : {"POSITION", "NORMAL"}) {
            const auto it = prim.targets[t].find(attribute);
            if (it == prim.targets[t].end()) continue;
            const bool is_normal = attribute[0] == 'N';
            if (is_normal && !has_normals) {
                ctx.warnings->push_back(tlabel +
                                        ": NORMAL deltas ignored (the primitive has no NORMAL)");
                continue;
            }
            const BakeError read =
                read_target_deltas(ctx, it->second, tlabel, attribute, vertex_count, used,
                                   is_normal ? &normals : &positions);
            if (!read.ok()) return read;
        }
        out->target_positions.push_back(std::move(positions));
        out->target_normals.push_back(std::move(normals));
    }
    return BakeError();
}

// The base colour texture's TEXCOORD_n (§3.7.2.1: VEC2 float, or normalized unsigned byte or
// short) for the vertices `used`. A missing or unusable set gives (0, 0) with a warning.
BakeError read_texcoords(const MeshContext& ctx, const tinygltf::Primitive& prim,
                         const std::string& label, size_t vertex_count,
                         const std::vector<uint32_t>& used, Primitive* out) {
    const int set = base_colour_texcoord(ctx.model, prim);
    if (set < 0) return BakeError();
    out->uvs.assign(used.size() * 2, 0.0f);
    const std::string name = "TEXCOORD_" + str(set);
    const auto it = prim.attributes.find(name);
    std::vector<float> uvs;
    if (it != prim.attributes.end()) {
        const BakeError read =
            read_accessor(ctx.model, it->second, TINYGLTF_TYPE_VEC2, kF32 | kU8N | kU16N, &uvs);
        if (!read.ok()) return prefixed(label + " " + name + ": ", read);
    }
    if (uvs.size() != vertex_count * 2) {
        ctx.warnings->push_back(label + ": " + name +
                                (uvs.empty() ? " missing" : " count differs") +
                                "; its base colour texture is sampled at (0, 0)");
        return BakeError();
    }
    for (size_t v = 0; v < used.size(); ++v)
        for (size_t c = 0; c < 2; ++c) {
            const float x = uvs[size_t(used[v]) * 2 + c];
            out->uvs[v * 2 + c] = std::isfinite(x) ? x : 0.0f;
        }
    return BakeError();
}

// COLOR_0 (§3.7.2.1: VEC3 or VEC4, float or normalized unsigned byte or short; linear) for
// the vertices `used`, RGBA with alpha 1 for VEC3, clamped to [0, 1].
BakeError read_colours(const MeshContext& ctx, const tinygltf::Primitive& prim,
                       const std::string& label, size_t vertex_count,
                       const std::vector<uint32_t>& used, Primitive* out) {
    const auto it = prim.attributes.find("COLOR_0");
    if (it == prim.attributes.end()) return BakeError();
    const bool vec4 = it->second >= 0 && size_t(it->second) < ctx.model.accessors.size() &&
                      ctx.model.accessors[size_t(it->second)].type == TINYGLTF_TYPE_VEC4;
    const size_t width = vec4 ? 4 : 3;
    std::vector<float> colours;
    const BakeError read =
        read_accessor(ctx.model, it->second, vec4 ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3,
                      kF32 | kU8N | kU16N, &colours);
    if (!read.ok()) return prefixed(label + " COLOR_0: ", read);
    if (colours.size() != vertex_count * width)
        return malformed_input(label + ": COLOR_0 count " + str(colours.size() / width) +
                               " differs from POSITION count " + str(vertex_count));
    out->colours.assign(used.size() * 4, 1.0f);
    for (size_t v = 0; v < used.size(); ++v)
        for (size_t c = 0; c < width; ++c) {
            const float x = colours[size_t(used[v]) * width + c];
            out->colours[v * 4 + c] = std::isfinite(x) ? std::clamp(x, 0.0f, 1.0f) : 1.0f;
        }
    return BakeError();
}

// §3.7.2.1: mode defaults to TRIANGLES (4); point and line modes are legal but skipped.
BakeError check_mode(const MeshContext& ctx, const tinygltf::Primitive& prim,
                     const std::string& label, int* mode, bool* skipped) {
    *mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
    if (*mode > TINYGLTF_MODE_TRIANGLE_FAN)
        return malformed_input(label + ": invalid mode " + str(*mode));
    if (*mode < TINYGLTF_MODE_TRIANGLES) {
        ctx.warnings->push_back(label + ": mode " + mode_name(*mode) +
                                " is not a triangle mode; primitive skipped");
        *skipped = true;
    }
    return BakeError();
}

}  // namespace

BakeError read_primitive(const MeshContext& ctx, size_t mesh_index, size_t prim_index,
                         bool want_skin, Primitive* out, bool* skipped) {
    const tinygltf::Primitive& prim = ctx.model.meshes[mesh_index].primitives[prim_index];
    const std::string label = "mesh " + str(mesh_index) + " primitive " + str(prim_index);
    *skipped = false;
    int mode = 0;
    BakeError error = check_mode(ctx, prim, label, &mode, skipped);
    if (!error.ok() || *skipped) return error;
    const auto position_it = prim.attributes.find("POSITION");
    if (position_it == prim.attributes.end()) {
        // §3.7.2.1: without positions the primitive is not rendered.
        ctx.warnings->push_back(label + ": no POSITION attribute; primitive skipped");
        *skipped = true;
        return BakeError();
    }
    Attributes attributes;
    std::vector<uint32_t> triangles;
    error = read_attributes(ctx, prim, label, position_it->second, &attributes);
    if (error.ok())
        error = read_triangles(ctx, prim, label, mode, attributes.vertex_count, &triangles);
    if (!error.ok()) return error;
    if (triangles.empty()) {
        ctx.warnings->push_back(label + ": no triangles; primitive skipped");
        *skipped = true;
        return BakeError();
    }
    std::vector<uint32_t> used;
    error = compact_vertices(triangles, attributes, label, out, &used);
    if (!error.ok()) return error;
    assign_primitive_normals(ctx, attributes.normals, used, label, out);
    if (want_skin) {
        error = read_skin_attributes(ctx, prim, label, attributes.vertex_count, used, out);
        if (!error.ok()) return error;
    }
    error = read_morph_targets(ctx, prim, label, attributes.vertex_count, used,
                               !attributes.normals.empty(), out);
    if (error.ok() && ctx.options && ctx.options->looks)
        error = read_texcoords(ctx, prim, label, attributes.vertex_count, used, out);
    if (error.ok() && ctx.options && ctx.options->looks)
        error = read_colours(ctx, prim, label, attributes.vertex_count, used, out);
    if (!error.ok()) return error;
    if (out->skinned) sort_by_influence_count(out);
    return BakeError();
}

}  // namespace stipple::bake::gltf
