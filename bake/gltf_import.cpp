// glTF 2.0 importer: tinygltf parses the JSON/GLB container, everything after that (accessor
// decoding, hierarchy, skin, clips) is validated here, because tinygltf checks little beyond
// the JSON schema. Section numbers refer to the glTF 2.0 specification,
// https://registry.khronos.org/glTF/specs/2.0/glTF-2.0.html
//
// Malformed geometry, hierarchy or skin data fails the whole import with one line naming the
// problem; a malformed animation channel only drops that channel (with a warning), so one bad
// track does not cost the whole asset.
#include <tiny_gltf.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <limits>
#include <new>
#include <string>
#include <utility>
#include <vector>

#include "bake/scene_import.h"

namespace stipple::bake {

namespace detail {
// Area-weighted vertex normals; defined in static_mesh_import.cpp (shared by both importers).
void compute_vertex_normals(const std::vector<float>& positions,
                            const std::vector<uint32_t>& indices, std::vector<float>* normals);
}  // namespace detail

namespace {

using tinygltf::Model;

// An accessor without a bufferView is all zeros (§3.6.2.3), so its count is not bounded by
// the file size; this caps what such an accessor may make us allocate.
constexpr size_t kMaxZeroFilledElements = size_t(1) << 24;
// RawScene::joints is uint16_t.
constexpr size_t kMaxJoints = size_t(1) << 16;

std::string str(size_t v) {
    return std::to_string(v);
}
std::string str(int v) {
    return std::to_string(v);
}

// First non-empty line of a (possibly multi-line) message, trimmed, with bytes that are not
// printable ASCII (tinygltf quotes raw input bytes) replaced by '?'.
std::string first_line(const std::string& text) {
    size_t begin = 0;
    while (begin < text.size()) {
        size_t end = text.find('\n', begin);
        if (end == std::string::npos) end = text.size();
        std::string line = text.substr(begin, end - begin);
        const size_t a = line.find_first_not_of(" \t\r");
        if (a != std::string::npos) {
            const size_t b = line.find_last_not_of(" \t\r");
            line = line.substr(a, b - a + 1);
            for (char& c : line) {
                if (c < 0x20 || c > 0x7e) c = '?';
            }
            return line;
        }
        begin = end + 1;
    }
    return std::string();
}

bool contains(const std::vector<std::string>& list, const std::string& s) {
    return std::find(list.begin(), list.end(), s) != list.end();
}

bool all_finite(const float* v, size_t n) {
    for (size_t i = 0; i < n; ++i) {
        if (!std::isfinite(v[i])) return false;
    }
    return true;
}

// ---------------------------------------------------------------------------------------
// Accessors, §3.6.2

// Element formats a caller accepts: component type plus the `normalized` flag, as a bit set.
enum Format : unsigned {
    kF32 = 1u << 0,
    kI8 = 1u << 1,
    kI8N = 1u << 2,
    kU8 = 1u << 3,
    kU8N = 1u << 4,
    kI16 = 1u << 5,
    kI16N = 1u << 6,
    kU16 = 1u << 7,
    kU16N = 1u << 8,
    kU32 = 1u << 9,
};

// §3.6.2.2 "Accessor Data Types": normalized MUST NOT be set on FLOAT or UNSIGNED_INT, and
// INT (5124) does not exist in glTF 2.0; such combinations map to no format at all.
unsigned format_of(int component_type, bool normalized) {
    switch (component_type) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
            return normalized ? 0u : kF32;
        case TINYGLTF_COMPONENT_TYPE_BYTE:
            return normalized ? kI8N : kI8;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return normalized ? kU8N : kU8;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
            return normalized ? kI16N : kI16;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            return normalized ? kU16N : kU16;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
            return normalized ? 0u : kU32;
        default:
            return 0u;
    }
}

size_t component_size(int component_type) {
    switch (component_type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return 1;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            return 2;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
            return 4;
        default:
            return 0;
    }
}

size_t component_count(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR:
            return 1;
        case TINYGLTF_TYPE_VEC2:
            return 2;
        case TINYGLTF_TYPE_VEC3:
            return 3;
        case TINYGLTF_TYPE_VEC4:
        case TINYGLTF_TYPE_MAT2:
            return 4;
        case TINYGLTF_TYPE_MAT3:
            return 9;
        case TINYGLTF_TYPE_MAT4:
            return 16;
        default:
            return 0;
    }
}

std::string type_name(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR:
            return "SCALAR";
        case TINYGLTF_TYPE_VEC2:
            return "VEC2";
        case TINYGLTF_TYPE_VEC3:
            return "VEC3";
        case TINYGLTF_TYPE_VEC4:
            return "VEC4";
        case TINYGLTF_TYPE_MAT2:
            return "MAT2";
        case TINYGLTF_TYPE_MAT3:
            return "MAT3";
        case TINYGLTF_TYPE_MAT4:
            return "MAT4";
        default:
            return "unknown type " + str(type);
    }
}

std::string component_name(int component_type, bool normalized) {
    std::string name;
    switch (component_type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
            name = "BYTE";
            break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            name = "UNSIGNED_BYTE";
            break;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
            name = "SHORT";
            break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            name = "UNSIGNED_SHORT";
            break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
            name = "UNSIGNED_INT";
            break;
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
            name = "FLOAT";
            break;
        default:
            name = "unknown component type " + str(component_type);
            break;
    }
    return normalized ? name + " (normalized)" : name;
}

// One component as a double (exact for every glTF component type). Normalized integers
// use the decoding of §3.11 "Animations" / §3.6.2.2: c / (2^(n-1) - 1) clamped to -1 for
// signed types, c / (2^n - 1) for unsigned ones. Data is little-endian (§3.6.2.4); the
// bake only runs on little-endian hosts.
double read_component(const unsigned char* p, int component_type, bool normalized) {
    switch (component_type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
            int8_t v;
            std::memcpy(&v, p, 1);
            return normalized ? std::max(v / 127.0, -1.0) : double(v);
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
            uint8_t v;
            std::memcpy(&v, p, 1);
            return normalized ? v / 255.0 : double(v);
        }
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
            int16_t v;
            std::memcpy(&v, p, 2);
            return normalized ? std::max(v / 32767.0, -1.0) : double(v);
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            uint16_t v;
            std::memcpy(&v, p, 2);
            return normalized ? v / 65535.0 : double(v);
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
            uint32_t v;
            std::memcpy(&v, p, 4);
            return double(v);
        }
        case TINYGLTF_COMPONENT_TYPE_FLOAT: {
            float v;
            std::memcpy(&v, p, 4);
            return double(v);
        }
        default:
            return 0.0;  // unreachable: formats are checked before reading
    }
}

// Finds `count` elements of `element_size` bytes, `offset` bytes into buffer view
// `view_index`, and checks that all of them lie inside the view and the view inside its
// buffer (§3.6.1 "Buffers and Buffer Views", §3.6.2.4 "Data Alignment"). Sparse index and
// value views are tightly packed (§3.6.2.3), so only vertex attributes use byteStride.
bool locate(const Model& model, int view_index, size_t offset, size_t count, size_t element_size,
            bool use_stride, const unsigned char** data, size_t* stride, std::string* err) {
    if (view_index < 0 || size_t(view_index) >= model.bufferViews.size()) {
        *err = "bufferView " + str(view_index) + " out of range (bufferView count " +
               str(model.bufferViews.size()) + ")";
        return false;
    }
    const tinygltf::BufferView& view = model.bufferViews[size_t(view_index)];
    const std::string label = "bufferView " + str(view_index);
    if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size()) {
        *err = label + ": buffer " + str(view.buffer) + " out of range (buffer count " +
               str(model.buffers.size()) + ")";
        return false;
    }
    const std::vector<unsigned char>& bytes = model.buffers[size_t(view.buffer)].data;
    if (view.byteOffset > bytes.size() || view.byteLength > bytes.size() - view.byteOffset) {
        *err = label + ": byteOffset " + str(view.byteOffset) + " + byteLength " +
               str(view.byteLength) + " exceeds buffer " + str(view.buffer) + " (" +
               str(bytes.size()) + " bytes)";
        return false;
    }
    *stride = (use_stride && view.byteStride != 0) ? view.byteStride : element_size;
    if (*stride < element_size) {
        *err = label + ": byteStride " + str(view.byteStride) + " is smaller than the element (" +
               str(element_size) + " bytes)";
        return false;
    }
    // The last element ends at offset + stride * (count - 1) + element_size; compared
    // without forming that sum, which could overflow.
    const size_t length = view.byteLength;
    if (count == 0 || offset > length || element_size > length - offset ||
        (count - 1) > (length - offset - element_size) / *stride) {
        *err = str(count) + " elements of " + str(element_size) + " bytes at byteOffset " +
               str(offset) + " (stride " + str(*stride) + ") exceed " + label + " (byteLength " +
               str(length) + ")";
        return false;
    }
    *data = bytes.data() + view.byteOffset + offset;
    return true;
}

// Reads accessor `index` into `out` (count * components values), applying sparse
// substitution (§3.6.2.3). `type` is the required element type and `formats` the accepted
// component formats. Only 4-byte components are accepted for matrices, so the column
// padding of small matrix components (§3.6.2.4) never applies.
template <typename T>
bool read_accessor(const Model& model, int index, int type, unsigned formats, std::vector<T>* out,
                   std::string* err) {
    if (index < 0 || size_t(index) >= model.accessors.size()) {
        *err = "accessor " + str(index) + " out of range (accessor count " +
               str(model.accessors.size()) + ")";
        return false;
    }
    const tinygltf::Accessor& acc = model.accessors[size_t(index)];
    const std::string label = "accessor " + str(index);
    if (acc.type != type) {
        *err = label + ": type " + type_name(acc.type) + ", expected " + type_name(type);
        return false;
    }
    if ((format_of(acc.componentType, acc.normalized) & formats) == 0) {
        *err = label + ": component type " + component_name(acc.componentType, acc.normalized) +
               " is not allowed here";
        return false;
    }
    assert(
        (type != TINYGLTF_TYPE_MAT2 && type != TINYGLTF_TYPE_MAT3 && type != TINYGLTF_TYPE_MAT4) ||
        component_size(acc.componentType) == 4);
    if (acc.count == 0) {
        *err = label + ": count is 0";
        return false;
    }
    const size_t components = component_count(type);
    const size_t csize = component_size(acc.componentType);
    const size_t element_size = components * csize;

    if (acc.bufferView < 0) {
        // §3.6.2.3: no bufferView means zeros (possibly overridden by sparse values).
        if (acc.count > kMaxZeroFilledElements) {
            *err = label + ": " + str(acc.count) + " elements without a bufferView (at most " +
                   str(kMaxZeroFilledElements) + " supported)";
            return false;
        }
        out->assign(acc.count * components, T(0));
    } else {
        const unsigned char* data = nullptr;
        size_t stride = 0;
        std::string sub;
        if (!locate(model, acc.bufferView, acc.byteOffset, acc.count, element_size, true, &data,
                    &stride, &sub)) {
            *err = label + ": " + sub;
            return false;
        }
        out->resize(acc.count * components);
        for (size_t i = 0; i < acc.count; ++i) {
            for (size_t c = 0; c < components; ++c) {
                (*out)[i * components + c] = static_cast<T>(read_component(
                    data + i * stride + c * csize, acc.componentType, acc.normalized));
            }
        }
    }

    if (acc.sparse.isSparse) {
        const auto& sparse = acc.sparse;
        if (sparse.count < 1 || size_t(sparse.count) > acc.count) {
            *err = label + ": sparse count " + str(sparse.count) +
                   " out of range (accessor count " + str(acc.count) + ")";
            return false;
        }
        const int ict = sparse.indices.componentType;
        if ((format_of(ict, false) & (kU8 | kU16 | kU32)) == 0) {
            *err = label + ": sparse indices have component type " + component_name(ict, false);
            return false;
        }
        if (sparse.indices.byteOffset < 0 || sparse.values.byteOffset < 0) {
            *err = label + ": negative sparse byteOffset";
            return false;
        }
        const size_t n = size_t(sparse.count);
        const unsigned char* idata = nullptr;
        const unsigned char* vdata = nullptr;
        size_t istride = 0;
        size_t vstride = 0;
        std::string sub;
        if (!locate(model, sparse.indices.bufferView, size_t(sparse.indices.byteOffset), n,
                    component_size(ict), false, &idata, &istride, &sub) ||
            !locate(model, sparse.values.bufferView, size_t(sparse.values.byteOffset), n,
                    element_size, false, &vdata, &vstride, &sub)) {
            *err = label + ": sparse: " + sub;
            return false;
        }
        double previous = -1.0;
        for (size_t k = 0; k < n; ++k) {
            const double target = read_component(idata + k * istride, ict, false);
            if (target <= previous || target >= double(acc.count)) {
                *err = label + ": sparse index " + str(size_t(target)) +
                       " is out of range or not increasing";
                return false;
            }
            previous = target;
            for (size_t c = 0; c < components; ++c) {
                (*out)[size_t(target) * components + c] = static_cast<T>(read_component(
                    vdata + k * vstride + c * csize, acc.componentType, acc.normalized));
            }
        }
    }
    return true;
}

// ---------------------------------------------------------------------------------------
// Nodes, §3.5

// Splits a node matrix into T * R * S (§3.5.3 "Transformations": a matrix MUST be
// decomposable to TRS). A negative determinant becomes a negative x scale. Returns false
// with a warning text when the matrix is not exactly a TRS (shear, projection, zero scale).
bool decompose_trs(const glm::dmat4& m, RawNode* node, std::string* problem) {
    const glm::dvec3 c0(m[0]), c1(m[1]), c2(m[2]);
    glm::dvec3 s(glm::length(c0), glm::length(c1), glm::length(c2));
    if (glm::dot(c0, glm::cross(c1, c2)) < 0.0) s.x = -s.x;
    glm::dquat q(1.0, 0.0, 0.0, 0.0);
    const double tiny = 1e-12;
    const bool degenerate = std::abs(s.x) < tiny || std::abs(s.y) < tiny || std::abs(s.z) < tiny;
    if (!degenerate) {
        q = glm::normalize(glm::quat_cast(glm::dmat3(c0 / s.x, c1 / s.y, c2 / s.z)));
    }
    for (int i = 0; i < 3; ++i) {
        node->translation[i] = float(m[3][i]);
        node->scale[i] = float(s[i]);
    }
    node->rotation[0] = float(q.x);
    node->rotation[1] = float(q.y);
    node->rotation[2] = float(q.z);
    node->rotation[3] = float(q.w);
    if (degenerate) {
        *problem = "matrix has a zero scale; its rotation is dropped";
        return false;
    }
    // Rebuild and compare: any difference is shear or a projective bottom row.
    glm::dmat4 rebuilt = glm::mat4_cast(q);
    for (int c = 0; c < 3; ++c) rebuilt[c] *= s[c];
    rebuilt[3] = glm::dvec4(m[3][0], m[3][1], m[3][2], 1.0);
    double scale = 1.0;
    double diff = 0.0;
    for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) {
            scale = std::max(scale, std::abs(m[c][r]));
            diff = std::max(diff, std::abs(m[c][r] - rebuilt[c][r]));
        }
    }
    if (diff > 1e-4 * scale) {
        *problem = "matrix is not a pure TRS (shear or projection); approximated";
        return false;
    }
    return true;
}

// Reads a node's local transform into `raw` (TRS) and `local` (the exact matrix, used to
// bake static scenes).
bool read_node_transform(const tinygltf::Node& node, size_t index, RawNode* raw, glm::dmat4* local,
                         std::vector<std::string>* warnings, std::string* err) {
    const std::string label = "node " + str(index);
    auto finite = [](const std::vector<double>& v) {
        return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
    };
    if (!node.matrix.empty()) {
        if (node.matrix.size() != 16 || !finite(node.matrix)) {
            *err = label + ": matrix must be 16 finite numbers";
            return false;
        }
        for (int c = 0; c < 4; ++c) {
            for (int r = 0; r < 4; ++r) (*local)[c][r] = node.matrix[size_t(c * 4 + r)];
        }
        std::string problem;
        if (!decompose_trs(*local, raw, &problem)) warnings->push_back(label + ": " + problem);
    } else if ((!node.translation.empty() && node.translation.size() != 3) ||
               (!node.rotation.empty() && node.rotation.size() != 4) ||
               (!node.scale.empty() && node.scale.size() != 3) || !finite(node.translation) ||
               !finite(node.rotation) || !finite(node.scale)) {
        *err = label + ": translation/rotation/scale must be 3/4/3 finite numbers";
        return false;
    } else {
        for (size_t i = 0; i < node.translation.size(); ++i) {
            raw->translation[i] = float(node.translation[i]);
        }
        for (size_t i = 0; i < node.scale.size(); ++i) raw->scale[i] = float(node.scale[i]);
        if (!node.rotation.empty()) {
            const glm::dvec4 r(node.rotation[0], node.rotation[1], node.rotation[2],
                               node.rotation[3]);
            const double len = glm::length(r);
            if (!(len > 1e-6)) {
                *err = label + ": rotation is not a unit quaternion";
                return false;
            }
            for (int i = 0; i < 4; ++i) raw->rotation[i] = float(r[i] / len);
        }
        const glm::dquat q(raw->rotation[3], raw->rotation[0], raw->rotation[1], raw->rotation[2]);
        *local = glm::mat4_cast(q);
        for (int c = 0; c < 3; ++c) (*local)[c] *= double(raw->scale[c]);
        (*local)[3] =
            glm::dvec4(raw->translation[0], raw->translation[1], raw->translation[2], 1.0);
    }
    // Finite doubles can still overflow the floats the runtime uses.
    if (!all_finite(raw->translation, 3) || !all_finite(raw->rotation, 4) ||
        !all_finite(raw->scale, 3)) {
        *err = label + ": transform exceeds the float range";
        return false;
    }
    return true;
}

// ---------------------------------------------------------------------------------------
// Primitives, §3.7.2

// One primitive's triangles, compacted to the vertices they use.
struct Primitive {
    std::vector<float> positions;   // 3 per vertex
    std::vector<float> normals;     // 3 per vertex, unit
    std::vector<uint32_t> indices;  // 3 per triangle, local
    std::vector<uint16_t> joints;   // 4 per vertex, when skinned
    std::vector<float> weights;     // 4 per vertex, when skinned
    bool skinned = false;
    // Morph targets (§3.7.2.2), one entry per target of the primitive: POSITION deltas (3
    // per vertex; zeros when the target has none) and NORMAL deltas (3 per vertex, or empty
    // when the target has none or the primitive's normals were not given).
    std::vector<std::vector<float>> target_positions;
    std::vector<std::vector<float>> target_normals;
};

struct MeshContext {
    const Model& model;
    bool quantized;           // KHR_mesh_quantization is used: integer positions/normals
    size_t skin_joint_count;  // joints of skin 0
    std::vector<std::string>* warnings;
};

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

// Reads every JOINTS_n/WEIGHTS_n set of the vertices `used` (old indices) and keeps the 4
// largest influences per vertex, renormalised to sum 1 (§3.7.3.3 "Skinned Mesh
// Attributes"). Returns false on malformed data.
bool read_skin_attributes(const MeshContext& ctx, const tinygltf::Primitive& prim,
                          const std::string& label, size_t vertex_count,
                          const std::vector<uint32_t>& used, Primitive* out, std::string* err) {
    std::vector<std::vector<uint32_t>> joint_sets;
    std::vector<std::vector<float>> weight_sets;
    for (int set = 0;; ++set) {
        const auto j = prim.attributes.find("JOINTS_" + str(set));
        const auto w = prim.attributes.find("WEIGHTS_" + str(set));
        if (j == prim.attributes.end() && w == prim.attributes.end()) break;
        if (j == prim.attributes.end() || w == prim.attributes.end()) {
            *err =
                label + ": JOINTS_" + str(set) + " and WEIGHTS_" + str(set) + " must come together";
            return false;
        }
        std::vector<uint32_t> joints;
        std::vector<float> weights;
        std::string sub;
        if (!read_accessor(ctx.model, j->second, TINYGLTF_TYPE_VEC4, kU8 | kU16, &joints, &sub)) {
            *err = label + " JOINTS_" + str(set) + ": " + sub;
            return false;
        }
        if (!read_accessor(ctx.model, w->second, TINYGLTF_TYPE_VEC4, kF32 | kU8N | kU16N, &weights,
                           &sub)) {
            *err = label + " WEIGHTS_" + str(set) + ": " + sub;
            return false;
        }
        if (joints.size() != vertex_count * 4 || weights.size() != vertex_count * 4) {
            *err = label + ": JOINTS_" + str(set) + "/WEIGHTS_" + str(set) +
                   " count differs from POSITION count " + str(vertex_count);
            return false;
        }
        joint_sets.push_back(std::move(joints));
        weight_sets.push_back(std::move(weights));
    }
    if (joint_sets.empty()) return true;  // not skinned

    size_t clamped = 0, unbound = 0, truncated = 0;
    out->skinned = true;
    out->joints.assign(used.size() * 4, 0);
    out->weights.assign(used.size() * 4, 0.0f);
    std::vector<std::pair<uint32_t, float>> influences;
    for (size_t v = 0; v < used.size(); ++v) {
        const size_t old = used[v];
        influences.clear();
        for (size_t set = 0; set < joint_sets.size(); ++set) {
            for (size_t c = 0; c < 4; ++c) {
                const uint32_t joint = joint_sets[set][old * 4 + c];
                float weight = weight_sets[set][old * 4 + c];
                if (!std::isfinite(weight)) {
                    *err = label + ": vertex " + str(old) + " has a non-finite weight";
                    return false;
                }
                if (weight < 0.0f) {
                    ++clamped;
                    weight = 0.0f;
                }
                // A zero weight's joint index is never used; exporters often leave garbage.
                if (weight == 0.0f) continue;
                if (joint >= ctx.skin_joint_count) {
                    *err = label + ": joint index " + str(size_t(joint)) +
                           " out of range (skin 0 has " + str(ctx.skin_joint_count) + " joints)";
                    return false;
                }
                auto same = std::find_if(influences.begin(), influences.end(),
                                         [&](const auto& p) { return p.first == joint; });
                if (same != influences.end()) {
                    same->second += weight;
                } else {
                    influences.emplace_back(joint, weight);
                }
            }
        }
        std::stable_sort(influences.begin(), influences.end(),
                         [](const auto& a, const auto& b) { return a.second > b.second; });
        if (influences.size() > 4) {
            ++truncated;
            influences.resize(4);
        }
        float sum = 0.0f;
        for (const auto& p : influences) sum += p.second;
        if (!(sum > 0.0f)) {
            ++unbound;
            out->weights[v * 4] = 1.0f;  // joints stay 0: the whole vertex follows joint 0
            continue;
        }
        for (size_t c = 0; c < influences.size(); ++c) {
            out->joints[v * 4 + c] = uint16_t(influences[c].first);
            out->weights[v * 4 + c] = influences[c].second / sum;
        }
    }
    if (clamped) {
        ctx.warnings->push_back(label + ": " + str(clamped) + " negative weights clamped to 0");
    }
    if (unbound) {
        ctx.warnings->push_back(label + ": " + str(unbound) +
                                " vertices have no positive weight; bound to joint 0");
    }
    if (truncated) {
        ctx.warnings->push_back(label + ": " + str(truncated) +
                                " vertices have more than 4 influences; the 4 largest are kept");
    }
    return true;
}

// Reads the morph targets of a primitive (§3.7.2.2) for the vertices `used` (old indices).
// POSITION and NORMAL deltas are VEC3 floats (or, with KHR_mesh_quantization, normalized or
// plain integers); TANGENT deltas are ignored (the runtime has no tangents). NORMAL deltas
// are dropped when the primitive's normals are computed, since they would be deltas to
// normals that do not exist.
bool read_morph_targets(const MeshContext& ctx, const tinygltf::Primitive& prim,
                        const std::string& label, size_t vertex_count,
                        const std::vector<uint32_t>& used, bool has_normals, Primitive* out,
                        std::string* err) {
    const unsigned formats =
        ctx.quantized ? (kF32 | kI8 | kI8N | kU8 | kU8N | kI16 | kI16N | kU16 | kU16N) : kF32;
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
            std::vector<float> deltas;
            std::string sub;
            if (!read_accessor(ctx.model, it->second, TINYGLTF_TYPE_VEC3, formats, &deltas,
                               &sub)) {
                *err = tlabel + " " + attribute + ": " + sub;
                return false;
            }
            if (deltas.size() != vertex_count * 3) {
                *err = tlabel + ": " + attribute + " count " + str(deltas.size() / 3) +
                       " differs from POSITION count " + str(vertex_count);
                return false;
            }
            std::vector<float>& dst = is_normal ? normals : positions;
            dst.resize(used.size() * 3);
            for (size_t v = 0; v < used.size(); ++v) {
                const float* d = &deltas[size_t(used[v]) * 3];
                if (!all_finite(d, 3)) {
                    *err = tlabel + ": " + attribute + " delta of vertex " + str(size_t(used[v])) +
                           " is not finite";
                    return false;
                }
                std::copy(d, d + 3, &dst[v * 3]);
            }
        }
        out->target_positions.push_back(std::move(positions));
        out->target_normals.push_back(std::move(normals));
    }
    return true;
}

// Reorders a skinned primitive's vertices by descending influence count (number of leading
// weights up to the last non-zero one), stable, and remaps its indices and morph deltas.
// The skinning job picks its kernel per block of 4 vertices from the largest count in the
// block, so grouped vertices run the 1-, 2- and 3-influence kernels instead of the 4 one.
void sort_by_influence_count(Primitive* prim) {
    const size_t n = prim->positions.size() / 3;
    std::vector<uint32_t> order(n);
    std::vector<int> count(n);
    for (size_t v = 0; v < n; ++v) {
        order[v] = uint32_t(v);
        int c = 1;
        for (int k = 0; k < 4; ++k) {
            if (prim->weights[v * 4 + size_t(k)] != 0.0f) c = k + 1;
        }
        count[v] = c;
    }
    std::stable_sort(order.begin(), order.end(),
                     [&](uint32_t a, uint32_t b) { return count[a] > count[b]; });
    bool identity = true;
    for (size_t v = 0; v < n; ++v) identity = identity && order[v] == v;
    if (identity) return;
    auto permute = [&](std::vector<float>* values, size_t width) {
        if (values->empty()) return;
        std::vector<float> sorted(values->size());
        for (size_t v = 0; v < n; ++v) {
            std::copy(values->begin() + long(order[v] * width),
                      values->begin() + long(order[v] * width + width), sorted.begin() + long(v * width));
        }
        *values = std::move(sorted);
    };
    permute(&prim->positions, 3);
    permute(&prim->normals, 3);
    permute(&prim->weights, 4);
    for (auto& t : prim->target_positions) permute(&t, 3);
    for (auto& t : prim->target_normals) permute(&t, 3);
    std::vector<uint16_t> joints(prim->joints.size());
    for (size_t v = 0; v < n; ++v) {
        std::copy(prim->joints.begin() + long(order[v] * 4),
                  prim->joints.begin() + long(order[v] * 4 + 4), joints.begin() + long(v * 4));
    }
    prim->joints = std::move(joints);
    std::vector<uint32_t> inverse(n);
    for (size_t v = 0; v < n; ++v) inverse[order[v]] = uint32_t(v);
    for (uint32_t& index : prim->indices) index = inverse[index];
}

// Reads one primitive. *skipped is set (with a warning) for primitives that are legal but
// not triangles or have no positions.
bool read_primitive(const MeshContext& ctx, size_t mesh_index, size_t prim_index, bool want_skin,
                    Primitive* out, bool* skipped, std::string* err) {
    const tinygltf::Primitive& prim = ctx.model.meshes[mesh_index].primitives[prim_index];
    const std::string label = "mesh " + str(mesh_index) + " primitive " + str(prim_index);
    *skipped = false;

    // §3.7.2.1: mode defaults to TRIANGLES (4).
    const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
    if (mode > TINYGLTF_MODE_TRIANGLE_FAN) {
        *err = label + ": invalid mode " + str(mode);
        return false;
    }
    if (mode < TINYGLTF_MODE_TRIANGLES) {
        ctx.warnings->push_back(label + ": mode " + mode_name(mode) +
                                " is not a triangle mode; primitive skipped");
        *skipped = true;
        return true;
    }
    const auto position_it = prim.attributes.find("POSITION");
    if (position_it == prim.attributes.end()) {
        // §3.7.2.1: without positions the primitive is not rendered.
        ctx.warnings->push_back(label + ": no POSITION attribute; primitive skipped");
        *skipped = true;
        return true;
    }

    // KHR_mesh_quantization allows integer positions and normalized normals.
    const unsigned position_formats =
        ctx.quantized ? (kF32 | kI8 | kI8N | kU8 | kU8N | kI16 | kI16N | kU16 | kU16N) : kF32;
    const unsigned normal_formats = ctx.quantized ? (kF32 | kI8N | kI16N) : kF32;
    std::vector<float> positions;
    std::string sub;
    if (!read_accessor(ctx.model, position_it->second, TINYGLTF_TYPE_VEC3, position_formats,
                       &positions, &sub)) {
        *err = label + " POSITION: " + sub;
        return false;
    }
    const size_t vertex_count = positions.size() / 3;
    if (vertex_count > std::numeric_limits<uint32_t>::max()) {
        *err = label + ": too many vertices";
        return false;
    }
    std::vector<float> normals;
    const auto normal_it = prim.attributes.find("NORMAL");
    if (normal_it != prim.attributes.end()) {
        if (!read_accessor(ctx.model, normal_it->second, TINYGLTF_TYPE_VEC3, normal_formats,
                           &normals, &sub)) {
            *err = label + " NORMAL: " + sub;
            return false;
        }
        if (normals.size() != positions.size()) {
            // §3.7.2.1: all attribute accessors of a primitive have the same count.
            *err = label + ": NORMAL count " + str(normals.size() / 3) +
                   " differs from POSITION count " + str(vertex_count);
            return false;
        }
    }

    // The vertex sequence, then triangles by topology (§3.7.2.1 "Topology types").
    std::vector<uint32_t> sequence;
    if (prim.indices >= 0) {
        if (!read_accessor(ctx.model, prim.indices, TINYGLTF_TYPE_SCALAR, kU8 | kU16 | kU32,
                           &sequence, &sub)) {
            *err = label + " indices: " + sub;
            return false;
        }
        for (uint32_t index : sequence) {
            if (index >= vertex_count) {
                *err = label + ": index " + str(size_t(index)) + " out of range (vertex count " +
                       str(vertex_count) + ")";
                return false;
            }
        }
    } else {
        sequence.resize(vertex_count);
        for (size_t i = 0; i < vertex_count; ++i) sequence[i] = uint32_t(i);
    }
    std::vector<uint32_t> triangles;
    const size_t n = sequence.size();
    if (mode == TINYGLTF_MODE_TRIANGLES) {
        if (n % 3 != 0) {
            *err = label + ": " + (prim.indices >= 0 ? "index" : "vertex") + " count " + str(n) +
                   " is not a multiple of 3";
            return false;
        }
        triangles = std::move(sequence);
    } else {
        for (size_t i = 0; i + 2 < n; ++i) {
            if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
                // {v_i, v_(i+1+i%2), v_(i+2-i%2)}: every other triangle flips to keep winding.
                triangles.insert(triangles.end(),
                                 {sequence[i], sequence[i + 1 + i % 2], sequence[i + 2 - i % 2]});
            } else {
                triangles.insert(triangles.end(), {sequence[i + 1], sequence[i + 2], sequence[0]});
            }
        }
    }
    if (triangles.empty()) {
        ctx.warnings->push_back(label + ": no triangles; primitive skipped");
        *skipped = true;
        return true;
    }

    // Keep only the vertices the triangles use, so unused (and unvalidated) data is dropped.
    constexpr uint32_t kUnused = std::numeric_limits<uint32_t>::max();
    std::vector<uint32_t> remap(vertex_count, kUnused);
    std::vector<uint32_t> used;
    out->indices.resize(triangles.size());
    for (size_t i = 0; i < triangles.size(); ++i) {
        uint32_t& slot = remap[triangles[i]];
        if (slot == kUnused) {
            slot = uint32_t(used.size());
            used.push_back(triangles[i]);
        }
        out->indices[i] = slot;
    }
    out->positions.resize(used.size() * 3);
    for (size_t v = 0; v < used.size(); ++v) {
        const float* p = &positions[size_t(used[v]) * 3];
        if (!all_finite(p, 3)) {
            *err = label + ": POSITION of vertex " + str(size_t(used[v])) + " is not finite";
            return false;
        }
        std::copy(p, p + 3, &out->positions[v * 3]);
    }

    // Normals: given ones are normalised; missing or unusable ones are computed from the
    // triangles (area-weighted). Note: §3.7.2.1 asks for flat normals when NORMAL is
    // absent; smooth normals over shared vertices are what the stipple shading wants.
    std::vector<float> computed;
    detail::compute_vertex_normals(out->positions, out->indices, &computed);
    out->normals = computed;
    if (!normals.empty()) {
        size_t repaired = 0;
        for (size_t v = 0; v < used.size(); ++v) {
            const float* nv = &normals[size_t(used[v]) * 3];
            const double len =
                std::sqrt(double(nv[0]) * nv[0] + double(nv[1]) * nv[1] + double(nv[2]) * nv[2]);
            if (all_finite(nv, 3) && len > 1e-12) {
                for (int c = 0; c < 3; ++c) out->normals[v * 3 + c] = float(nv[c] / len);
            } else {
                ++repaired;
            }
        }
        if (repaired) {
            ctx.warnings->push_back(label + ": " + str(repaired) +
                                    " zero or non-finite normals recomputed");
        }
    }

    if (want_skin && !read_skin_attributes(ctx, prim, label, vertex_count, used, out, err)) {
        return false;
    }
    if (!read_morph_targets(ctx, prim, label, vertex_count, used, !normals.empty(), out, err)) {
        return false;
    }
    if (out->skinned) sort_by_influence_count(out);
    return true;
}

// ---------------------------------------------------------------------------------------
// Animations, §3.11

// Morph weight slots of each output node: [begin, begin + count) of RawScene::morph_weights.
struct MorphSlots {
    uint32_t begin = 0;
    uint32_t count = 0;
};

// Reads one channel; returns false with `why` (the channel is then skipped).
bool read_channel(const Model& model, const tinygltf::Animation& anim,
                  const tinygltf::AnimationChannel& ch, const std::vector<int32_t>& out_index,
                  const std::vector<MorphSlots>& slots, RawChannel* out,
                  std::vector<std::string>* notes, std::string* why) {
    if (ch.sampler < 0 || size_t(ch.sampler) >= anim.samplers.size()) {
        *why = "sampler " + str(ch.sampler) + " out of range (sampler count " +
               str(anim.samplers.size()) + ")";
        return false;
    }
    if (ch.target_node < 0) {
        *why = "no target node";
        return false;
    }
    if (size_t(ch.target_node) >= model.nodes.size()) {
        *why = "target node " + str(ch.target_node) + " out of range (node count " +
               str(model.nodes.size()) + ")";
        return false;
    }
    if (out_index[size_t(ch.target_node)] < 0) {
        *why = "target node " + str(ch.target_node) + " is not in the scene";
        return false;
    }
    out->node = uint32_t(out_index[size_t(ch.target_node)]);
    size_t components = 3;
    if (ch.target_path == "translation") {
        out->path = RawPath::translation;
    } else if (ch.target_path == "rotation") {
        out->path = RawPath::rotation;
        components = 4;
    } else if (ch.target_path == "scale") {
        out->path = RawPath::scale;
    } else if (ch.target_path == "weights") {
        // §3.11: the node's mesh instance's morph weights, one per target.
        const MorphSlots& s = slots[out->node];
        if (s.count == 0) {
            *why = "target node " + str(ch.target_node) + " has no mesh with morph targets";
            return false;
        }
        out->path = RawPath::weights;
        out->weight_begin = s.begin;
        out->weight_count = s.count;
        components = s.count;
    } else {
        *why = "unknown target path '" + ch.target_path + "'";
        return false;
    }
    const tinygltf::AnimationSampler& sampler = anim.samplers[size_t(ch.sampler)];
    if (sampler.interpolation == "LINEAR" || sampler.interpolation.empty()) {
        out->interp = RawInterp::linear;
    } else if (sampler.interpolation == "STEP") {
        out->interp = RawInterp::step;
    } else if (sampler.interpolation == "CUBICSPLINE") {
        out->interp = RawInterp::cubic_spline;
    } else {
        *why = "unknown interpolation '" + sampler.interpolation + "'";
        return false;
    }
    const bool cubic = out->interp == RawInterp::cubic_spline;
    // Appendix C: a CUBICSPLINE key is (in-tangent, value, out-tangent).
    const size_t per_key = components * (cubic ? 3 : 1);

    std::vector<float> times;
    std::vector<float> values;
    std::string sub;
    if (!read_accessor(model, sampler.input, TINYGLTF_TYPE_SCALAR, kF32, &times, &sub)) {
        *why = "input: " + sub;
        return false;
    }
    // Rotations and weights may be normalized integers (§3.11 "Animations", accessor
    // table); translation and scale are float. Weights outputs are SCALAR, N per key.
    const unsigned formats = out->path == RawPath::rotation || out->path == RawPath::weights
                                 ? (kF32 | kI8N | kU8N | kI16N | kU16N)
                                 : kF32;
    const int type = out->path == RawPath::weights ? TINYGLTF_TYPE_SCALAR
                     : components == 4             ? TINYGLTF_TYPE_VEC4
                                                   : TINYGLTF_TYPE_VEC3;
    if (!read_accessor(model, sampler.output, type, formats, &values, &sub)) {
        *why = "output: " + sub;
        return false;
    }
    if (values.size() != times.size() * per_key) {
        *why = "output count " + str(values.size()) + " floats does not match input count " +
               str(times.size()) + " x " + str(per_key);
        return false;
    }
    if (!all_finite(times.data(), times.size()) || !all_finite(values.data(), values.size())) {
        *why = "non-finite key time or value";
        return false;
    }
    // §3.11: times are non-negative and strictly increasing. Equal neighbours (a common
    // exporter encoding of a jump) keep the later key, which is the value after the jump.
    if (times[0] < 0.0f) {
        *why = "negative key time " + std::to_string(times[0]);
        return false;
    }
    size_t dropped = 0;
    for (size_t k = 0; k < times.size(); ++k) {
        if (k + 1 < times.size() && times[k + 1] < times[k]) {
            *why = "key times decrease at key " + str(k + 1);
            return false;
        }
        if (k + 1 < times.size() && times[k + 1] == times[k]) {
            ++dropped;
            continue;
        }
        float* value = &values[k * per_key];
        if (components == 4 && out->path == RawPath::rotation) {
            float* q = cubic ? value + 4 : value;  // the value, not the tangents
            const double len = std::sqrt(double(q[0]) * q[0] + double(q[1]) * q[1] +
                                         double(q[2]) * q[2] + double(q[3]) * q[3]);
            if (!(len > 1e-6)) {
                *why = "rotation key " + str(k) + " is not a unit quaternion";
                return false;
            }
            // LINEAR/STEP keys are normalised; CUBICSPLINE values stay as written, since
            // scaling a value without its tangents would change the curve (the sampler
            // normalises the interpolated result, Appendix C).
            if (!cubic) {
                for (size_t c = 0; c < 4; ++c) q[c] = float(q[c] / len);
            }
        }
        out->times.push_back(times[k]);
        out->values.insert(out->values.end(), value, value + per_key);
    }
    if (dropped) notes->push_back(str(dropped) + " keys with duplicate times dropped");
    return true;
}

std::vector<RawClip> read_clips(const Model& model, const std::vector<int32_t>& out_index,
                                const std::vector<MorphSlots>& slots,
                                std::vector<std::string>* warnings) {
    std::vector<RawClip> clips;
    for (size_t a = 0; a < model.animations.size(); ++a) {
        const tinygltf::Animation& anim = model.animations[a];
        RawClip clip;
        clip.name = anim.name.empty() ? "clip" + str(a) : anim.name;
        const std::string label = "animation '" + clip.name + "'";
        // §3.11: each (node, path) target is used at most once per animation.
        std::vector<std::pair<uint32_t, RawPath>> targets;
        for (size_t c = 0; c < anim.channels.size(); ++c) {
            const std::string channel_label = label + " channel " + str(c);
            RawChannel channel;
            std::vector<std::string> notes;
            std::string why;
            if (!read_channel(model, anim, anim.channels[c], out_index, slots, &channel, &notes,
                              &why)) {
                warnings->push_back(channel_label + ": " + why + "; channel skipped");
                continue;
            }
            const std::pair<uint32_t, RawPath> target(channel.node, channel.path);
            if (std::find(targets.begin(), targets.end(), target) != targets.end()) {
                warnings->push_back(
                    channel_label + ": target node " + str(anim.channels[c].target_node) + " '" +
                    anim.channels[c].target_path + "' is already animated; channel skipped");
                continue;
            }
            targets.push_back(target);
            for (const std::string& note : notes) warnings->push_back(channel_label + ": " + note);
            clip.duration = std::max(clip.duration, channel.times.back());
            clip.channels.push_back(std::move(channel));
        }
        if (clip.channels.empty()) {
            warnings->push_back(label + ": no usable channels; clip dropped");
            continue;
        }
        clips.push_back(std::move(clip));
    }
    return clips;
}

// ---------------------------------------------------------------------------------------
// Loading

// Images are irrelevant to the bake: accept them without decoding.
bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int,
                const unsigned char*, int, void*) {
    return true;
}

bool load_model(const std::string& path, Model* model, std::vector<std::string>* warnings,
                std::string* err) {
    std::ifstream file(path, std::ios::binary);
    if (!file) {
        *err = "cannot open file";
        return false;
    }
    // GLB starts with the magic "glTF" (§4 "GLB File Format Specification", header); anything
    // else is tried as JSON.
    char magic[4] = {};
    file.read(magic, 4);
    const bool binary = file.gcount() == 4 && std::memcmp(magic, "glTF", 4) == 0;
    file.close();

    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(&skip_image, nullptr);
    std::string terr;
    std::string twarn;
    const bool ok = binary ? loader.LoadBinaryFromFile(model, &terr, &twarn, path)
                           : loader.LoadASCIIFromFile(model, &terr, &twarn, path);
    size_t begin = 0;
    while (begin < twarn.size()) {
        size_t end = twarn.find('\n', begin);
        if (end == std::string::npos) end = twarn.size();
        const std::string line = first_line(twarn.substr(begin, end - begin));
        if (!line.empty()) warnings->push_back("glTF loader: " + line);
        begin = end + 1;
    }
    if (!ok) {
        std::string why = first_line(terr);
        if (why.empty()) why = "unknown error";
        // tinygltf may quote a whole data URI; keep the log line readable.
        if (why.size() > 200) why = why.substr(0, 200) + "...";
        *err = "not a valid glTF file: " + why;
        return false;
    }
    return true;
}

// §3.12: a required extension must be understood. Material and texture extensions do not
// change geometry; compressed geometry cannot be read without a decoder.
bool check_extensions(const Model& model, std::vector<std::string>* warnings, std::string* err) {
    for (const std::string& ext : model.extensionsRequired) {
        if (ext == "KHR_draco_mesh_compression" || ext == "EXT_meshopt_compression") {
            *err = "required extension " + ext + " is unsupported (compressed geometry)";
            return false;
        }
        const bool harmless =
            ext == "KHR_mesh_quantization" || ext.rfind("KHR_materials_", 0) == 0 ||
            ext.rfind("KHR_texture_", 0) == 0 || ext.rfind("EXT_texture_", 0) == 0;
        if (!harmless) {
            warnings->push_back("required extension " + ext +
                                " is not supported; the geometry may be incomplete");
        }
    }
    if (contains(model.extensionsUsed, "EXT_mesh_gpu_instancing")) {
        warnings->push_back("EXT_mesh_gpu_instancing is unsupported; instanced meshes appear once");
    }
    return true;
}

// ---------------------------------------------------------------------------------------

bool import_model(const Model& model, RawScene* scene, std::string* err) {
    std::vector<std::string>& warnings = scene->warnings;
    if (!check_extensions(model, &warnings, err)) return false;
    const size_t node_count = model.nodes.size();

    // Roots: the default scene, else scene 0, else every node that is nobody's child.
    std::vector<int> roots;
    if (!model.scenes.empty()) {
        if (model.defaultScene >= 0 && size_t(model.defaultScene) >= model.scenes.size()) {
            *err = "default scene " + str(model.defaultScene) + " out of range (scene count " +
                   str(model.scenes.size()) + ")";
            return false;
        }
        roots = model.scenes[size_t(std::max(model.defaultScene, 0))].nodes;
    } else {
        std::vector<bool> is_child(node_count, false);
        for (const tinygltf::Node& node : model.nodes) {
            for (int child : node.children) {
                if (child >= 0 && size_t(child) < node_count) is_child[size_t(child)] = true;
            }
        }
        for (size_t i = 0; i < node_count; ++i) {
            if (!is_child[i]) roots.push_back(int(i));
        }
    }

    // Depth-first preorder with an explicit stack (no recursion on deep chains): parents are
    // emitted before children. §3.5.2: the hierarchy is a set of disjoint strict trees, so a
    // node reached twice means a cycle or a shared child.
    std::vector<int32_t> out_index(node_count, -1);
    std::vector<size_t> order;  // glTF node of each output node
    struct Pending {
        int node;
        int32_t parent;
    };
    std::vector<Pending> stack;
    for (auto it = roots.rbegin(); it != roots.rend(); ++it) {
        if (*it < 0 || size_t(*it) >= node_count) {
            *err = "scene node " + str(*it) + " out of range (node count " + str(node_count) + ")";
            return false;
        }
        stack.push_back({*it, -1});
    }
    while (!stack.empty()) {
        const Pending item = stack.back();
        stack.pop_back();
        const size_t gi = size_t(item.node);
        if (out_index[gi] >= 0) {
            *err = "node " + str(gi) +
                   " is reached twice (the node hierarchy must be a set of disjoint trees)";
            return false;
        }
        out_index[gi] = int32_t(order.size());
        order.push_back(gi);
        RawNode raw;
        raw.parent = item.parent;
        raw.name = model.nodes[gi].name;
        scene->nodes.push_back(std::move(raw));
        const std::vector<int>& children = model.nodes[gi].children;
        for (auto it = children.rbegin(); it != children.rend(); ++it) {
            if (*it < 0 || size_t(*it) >= node_count) {
                *err = "node " + str(gi) + ": child " + str(*it) + " out of range (node count " +
                       str(node_count) + ")";
                return false;
            }
            stack.push_back({*it, out_index[gi]});
        }
    }

    // Local transforms and world matrices (parents first, so one forward pass).
    std::vector<glm::dmat4> world(order.size());
    for (size_t i = 0; i < order.size(); ++i) {
        glm::dmat4 local(1.0);
        if (!read_node_transform(model.nodes[order[i]], order[i], &scene->nodes[i], &local,
                                 &warnings, err)) {
            return false;
        }
        const int32_t parent = scene->nodes[i].parent;
        world[i] = parent < 0 ? local : world[size_t(parent)] * local;
    }

    // Skin 0 (§3.7.3): its joints become joints 0..J-1.
    bool has_skin = false;
    std::vector<uint32_t> skin_joints;
    std::vector<float> inverse_bind;
    if (!model.skins.empty()) {
        const tinygltf::Skin& skin = model.skins[0];
        bool used_in_scene = false;
        for (size_t gi : order) {
            if (model.nodes[gi].skin == 0 && model.nodes[gi].mesh >= 0) used_in_scene = true;
        }
        if (skin.joints.empty() || skin.joints.size() > kMaxJoints) {
            *err = "skin 0: joint count " + str(skin.joints.size()) + " out of range [1, " +
                   str(kMaxJoints) + "]";
            return false;
        }
        bool joints_in_scene = true;
        for (int joint : skin.joints) {
            if (joint < 0 || size_t(joint) >= node_count) {
                *err = "skin 0: joint node " + str(joint) + " out of range (node count " +
                       str(node_count) + ")";
                return false;
            }
            if (out_index[size_t(joint)] < 0) {
                if (used_in_scene) {
                    *err = "skin 0: joint node " + str(joint) + " is not in the scene";
                    return false;
                }
                joints_in_scene = false;
                break;
            }
            skin_joints.push_back(uint32_t(out_index[size_t(joint)]));
        }
        if (!joints_in_scene) {
            warnings.push_back(
                "skin 0 is not used by the scene and its joints are not in it; "
                "skin ignored");
            skin_joints.clear();
        } else {
            has_skin = true;
            const size_t joint_count = skin_joints.size();
            if (skin.inverseBindMatrices >= 0) {
                std::string sub;
                if (!read_accessor(model, skin.inverseBindMatrices, TINYGLTF_TYPE_MAT4, kF32,
                                   &inverse_bind, &sub)) {
                    *err = "skin 0 inverseBindMatrices: " + sub;
                    return false;
                }
                if (inverse_bind.size() < joint_count * 16) {
                    *err = "skin 0: " + str(inverse_bind.size() / 16) +
                           " inverse bind matrices for " + str(joint_count) + " joints";
                    return false;
                }
                inverse_bind.resize(joint_count * 16);
                if (!all_finite(inverse_bind.data(), inverse_bind.size())) {
                    *err = "skin 0: inverse bind matrices are not finite";
                    return false;
                }
            } else {
                // §3.7.3: absent inverse bind matrices are identities.
                for (size_t j = 0; j < joint_count; ++j) {
                    for (int k = 0; k < 16; ++k) inverse_bind.push_back(k % 5 == 0 ? 1.0f : 0.0f);
                }
            }
        }
    }

    // Morph weight slots (§3.7.2.2): every node drawing a mesh with morph targets owns one
    // slot per target. Defaults: the node's weights, else the mesh's, else 0.
    std::vector<MorphSlots> slots(order.size());
    std::vector<float> morph_weights;
    std::vector<uint32_t> morph_weight_nodes;
    for (size_t oi = 0; oi < order.size(); ++oi) {
        const tinygltf::Node& node = model.nodes[order[oi]];
        if (node.mesh < 0 || size_t(node.mesh) >= model.meshes.size()) continue;
        const tinygltf::Mesh& mesh = model.meshes[size_t(node.mesh)];
        size_t count = 0;
        for (const tinygltf::Primitive& prim : mesh.primitives) {
            count = std::max(count, prim.targets.size());
        }
        if (count == 0) continue;
        const std::string label = "node " + str(order[oi]) + " (mesh " + str(node.mesh) + ")";
        for (const tinygltf::Primitive& prim : mesh.primitives) {
            if (prim.targets.size() != count) {
                // §3.7.2.2: all primitives MUST have the same number of targets.
                warnings.push_back(label + ": primitives have different morph target counts; "
                                   "target i of every primitive uses weight i");
                break;
            }
        }
        const std::vector<double>* defaults = nullptr;
        if (node.weights.size() == count) {
            defaults = &node.weights;
        } else if (mesh.weights.size() == count) {
            defaults = &mesh.weights;
        }
        if ((!node.weights.empty() && node.weights.size() != count) ||
            (!mesh.weights.empty() && mesh.weights.size() != count && defaults == nullptr)) {
            warnings.push_back(label + ": default morph weights do not match its " + str(count) +
                               " targets; ignored");
        }
        slots[oi] = {uint32_t(morph_weights.size()), uint32_t(count)};
        for (size_t i = 0; i < count; ++i) {
            double w = defaults != nullptr ? (*defaults)[i] : 0.0;
            if (!std::isfinite(w) || std::abs(w) > 1e30) {
                warnings.push_back(label + ": default morph weight " + str(i) +
                                   " is not finite; 0 used");
                w = 0.0;
            }
            morph_weights.push_back(float(w));
            morph_weight_nodes.push_back(uint32_t(oi));
        }
    }

    std::vector<RawClip> clips = read_clips(model, out_index, slots, &warnings);
    const bool animated = has_skin || !clips.empty();

    // Meshes of every node, in output node order.
    MeshContext ctx{model, contains(model.extensionsUsed, "KHR_mesh_quantization"),
                    skin_joints.size(), &warnings};
    std::vector<uint32_t> joint_nodes = skin_joints;
    std::vector<int64_t> rigid_joint(order.size(), -1);  // joint of a rigidly attached node
    for (size_t oi = 0; oi < order.size(); ++oi) {
        const size_t gi = order[oi];
        const tinygltf::Node& node = model.nodes[gi];
        if (node.mesh < 0) continue;
        if (size_t(node.mesh) >= model.meshes.size()) {
            *err = "node " + str(gi) + ": mesh " + str(node.mesh) + " out of range (mesh count " +
                   str(model.meshes.size()) + ")";
            return false;
        }
        if (node.skin >= 0 && size_t(node.skin) >= model.skins.size()) {
            *err = "node " + str(gi) + ": skin " + str(node.skin) + " out of range (skin count " +
                   str(model.skins.size()) + ")";
            return false;
        }
        const bool skinned_node = has_skin && node.skin == 0;
        if (node.skin > 0) {
            warnings.push_back("node " + str(gi) + " uses skin " + str(node.skin) +
                               "; only the first skin is supported, so its mesh is attached "
                               "rigidly to the node");
        }
        const size_t mesh_index = size_t(node.mesh);
        for (size_t p = 0; p < model.meshes[mesh_index].primitives.size(); ++p) {
            Primitive prim;
            bool skipped = false;
            if (!read_primitive(ctx, mesh_index, p, skinned_node, &prim, &skipped, err)) {
                return false;
            }
            if (skipped) continue;
            if (skinned_node && !prim.skinned) {
                warnings.push_back("mesh " + str(mesh_index) + " primitive " + str(p) +
                                   " on skinned node " + str(gi) +
                                   " has no JOINTS_0/WEIGHTS_0; attached rigidly to the node");
            }
            // §3.9.5 (material.doubleSided): back faces are lit and drawn too. The
            // default material (no material index) is single-sided.
            const int material = model.meshes[mesh_index].primitives[p].material;
            const bool double_sided = material >= 0 &&
                                      size_t(material) < model.materials.size() &&
                                      model.materials[size_t(material)].doubleSided;
            scene->double_sided.insert(scene->double_sided.end(), prim.indices.size() / 3,
                                       uint8_t(double_sided));
            const size_t base = scene->vertex_count();
            const size_t count = prim.positions.size() / 3;
            const MorphSlots& node_slots = slots[oi];
            if (count > std::numeric_limits<uint32_t>::max() - base) {
                *err = "more than 2^32 vertices";
                return false;
            }
            if (!animated) {
                // Static: bake the default morph weights (§3.7.2.2), then the world transform.
                for (size_t t = 0; t < prim.target_positions.size() && t < node_slots.count;
                     ++t) {
                    const float w = morph_weights[node_slots.begin + t];
                    if (w == 0.0f) continue;
                    for (size_t i = 0; i < count * 3; ++i) {
                        prim.positions[i] += w * prim.target_positions[t][i];
                    }
                    if (!prim.target_normals[t].empty()) {
                        for (size_t i = 0; i < count * 3; ++i) {
                            prim.normals[i] += w * prim.target_normals[t][i];
                        }
                    }
                }
                // Static: bake the world transform. Normals use the cofactor matrix
                // (det * inverse transpose, valid even for singular matrices), sign-fixed;
                // a mirroring transform flips the winding to keep triangles front-facing.
                const glm::dmat4& m = world[oi];
                const glm::dmat3 linear(m);
                const double det = glm::determinant(linear);
                const glm::dmat3 cofactor =
                    glm::dmat3(glm::cross(linear[1], linear[2]), glm::cross(linear[2], linear[0]),
                               glm::cross(linear[0], linear[1]));
                for (size_t v = 0; v < count; ++v) {
                    const glm::dvec4 pw =
                        m * glm::dvec4(prim.positions[v * 3], prim.positions[v * 3 + 1],
                                       prim.positions[v * 3 + 2], 1.0);
                    glm::dvec3 nw =
                        cofactor * glm::dvec3(prim.normals[v * 3], prim.normals[v * 3 + 1],
                                              prim.normals[v * 3 + 2]);
                    if (det < 0.0) nw = -nw;
                    const double len = glm::length(nw);
                    nw = len > 1e-300 ? nw / len : glm::dvec3(0.0, 0.0, 1.0);
                    for (int c = 0; c < 3; ++c) {
                        scene->positions.push_back(float(pw[c]));
                        scene->normals.push_back(float(nw[c]));
                    }
                }
                if (!all_finite(scene->positions.data() + base * 3, count * 3)) {
                    *err = "node " + str(gi) + ": transformed positions are not finite";
                    return false;
                }
                for (size_t t = 0; t < prim.indices.size(); t += 3) {
                    const uint32_t b = uint32_t(base);
                    scene->indices.push_back(b + prim.indices[t]);
                    scene->indices.push_back(b + prim.indices[det < 0.0 ? t + 2 : t + 1]);
                    scene->indices.push_back(b + prim.indices[det < 0.0 ? t + 1 : t + 2]);
                }
                continue;
            }
            // Morph targets over this primitive's vertex range; all-zero targets are dropped.
            for (size_t t = 0; t < prim.target_positions.size() && t < node_slots.count; ++t) {
                auto nonzero = [](const std::vector<float>& v) {
                    return std::any_of(v.begin(), v.end(), [](float x) { return x != 0.0f; });
                };
                const bool has_p = nonzero(prim.target_positions[t]);
                const bool has_n = nonzero(prim.target_normals[t]);
                if (!has_p && !has_n) continue;
                RawMorphTarget target;
                target.weight = uint32_t(node_slots.begin + t);
                target.vertex_begin = uint32_t(base);
                target.vertex_count = uint32_t(count);
                target.position_deltas = std::move(prim.target_positions[t]);
                if (has_n) target.normal_deltas = std::move(prim.target_normals[t]);
                scene->morph_targets.push_back(std::move(target));
            }
            scene->positions.insert(scene->positions.end(), prim.positions.begin(),
                                    prim.positions.end());
            scene->normals.insert(scene->normals.end(), prim.normals.begin(), prim.normals.end());
            for (uint32_t index : prim.indices) scene->indices.push_back(uint32_t(base) + index);
            if (prim.skinned) {
                scene->joints.insert(scene->joints.end(), prim.joints.begin(), prim.joints.end());
                scene->weights.insert(scene->weights.end(), prim.weights.begin(),
                                      prim.weights.end());
                continue;
            }
            // Rigid attachment: one joint per node, identity inverse bind, local positions.
            if (rigid_joint[oi] < 0) {
                if (joint_nodes.size() >= kMaxJoints) {
                    *err = "more than " + str(kMaxJoints) + " joints";
                    return false;
                }
                rigid_joint[oi] = int64_t(joint_nodes.size());
                joint_nodes.push_back(uint32_t(oi));
                for (int k = 0; k < 16; ++k) inverse_bind.push_back(k % 5 == 0 ? 1.0f : 0.0f);
            }
            for (size_t v = 0; v < count; ++v) {
                scene->joints.insert(scene->joints.end(), {uint16_t(rigid_joint[oi]), 0, 0, 0});
                scene->weights.insert(scene->weights.end(), {1.0f, 0.0f, 0.0f, 0.0f});
            }
        }
    }
    if (scene->indices.empty()) {
        *err = "no triangle primitives found";
        return false;
    }
    if (std::find(scene->double_sided.begin(), scene->double_sided.end(), 1) ==
        scene->double_sided.end())
        scene->double_sided.clear();  // no double-sided material: nothing to record
    if (animated) {
        scene->joint_nodes = std::move(joint_nodes);
        scene->inverse_bind = std::move(inverse_bind);
        scene->clips = std::move(clips);
        if (!scene->morph_targets.empty()) {
            scene->morph_weights = std::move(morph_weights);
            scene->morph_weight_nodes = std::move(morph_weight_nodes);
        } else {
            // No target survived: weights channels would animate nothing.
            for (RawClip& clip : scene->clips) {
                clip.channels.erase(std::remove_if(clip.channels.begin(), clip.channels.end(),
                                                   [](const RawChannel& c) {
                                                       return c.path == RawPath::weights;
                                                   }),
                                    clip.channels.end());
            }
        }
    }
    return true;
}

}  // namespace

bool import_gltf(const std::string& path, RawScene* out, std::string* error) {
    assert(out != nullptr);
    std::string err;
    RawScene scene;
    bool ok = false;
    try {
        Model model;
        ok = load_model(path, &model, &scene.warnings, &err) && import_model(model, &scene, &err);
    } catch (const std::bad_alloc&) {
        err = "out of memory";
    } catch (const std::exception& e) {
        err = std::string("glTF loader failed: ") + first_line(e.what());
    } catch (...) {
        err = "glTF loader failed";
    }
    if (!ok) {
        *out = RawScene();
        if (error) *error = path + ": " + (err.empty() ? std::string("import failed") : err);
        return false;
    }
    *out = std::move(scene);
    return true;
}

}  // namespace stipple::bake
