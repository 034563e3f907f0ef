// glTF 2.0 accessors, §3.6.2: component decoding, buffer view bounds, sparse substitution.
#include "bake/gltf_accessors.h"

#include <algorithm>
#include <cassert>
#include <cstring>
#include <string>

#include "bake/gltf_parts.h"  // str()

namespace stipple::bake::gltf {

namespace {

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

// Where a run of elements lies: the first element and the distance between elements.
struct Located {
    const unsigned char* data = nullptr;
    size_t stride = 0;
};

// Finds `count` elements of `element_size` bytes, `offset` bytes into buffer view
// `view_index`, and checks that all of them lie inside the view and the view inside its
// buffer (§3.6.1 "Buffers and Buffer Views", §3.6.2.4 "Data Alignment"). Sparse index and
// value views are tightly packed (§3.6.2.3), so only vertex attributes use byteStride.
BakeError locate(const Model& model, int view_index, size_t offset, size_t count,
                 size_t element_size, bool use_stride, Located* out) {
    if (view_index < 0 || size_t(view_index) >= model.bufferViews.size()) {
        return malformed_input("bufferView " + str(view_index) +
                               " out of range (bufferView count " + str(model.bufferViews.size()) +
                               ")");
    }
    const tinygltf::BufferView& view = model.bufferViews[size_t(view_index)];
    const std::string label = "bufferView " + str(view_index);
    if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size()) {
        return malformed_input(label + ": buffer " + str(view.buffer) +
                               " out of range (buffer count " + str(model.buffers.size()) + ")");
    }
    const std::vector<unsigned char>& bytes = model.buffers[size_t(view.buffer)].data;
    if (view.byteOffset > bytes.size() || view.byteLength > bytes.size() - view.byteOffset) {
        return malformed_input(label + ": byteOffset " + str(view.byteOffset) + " + byteLength " +
                               str(view.byteLength) + " exceeds buffer " + str(view.buffer) + " (" +
                               str(bytes.size()) + " bytes)");
    }
    out->stride = (use_stride && view.byteStride != 0) ? view.byteStride : element_size;
    if (out->stride < element_size) {
        return malformed_input(label + ": byteStride " + str(view.byteStride) +
                               " is smaller than the element (" + str(element_size) + " bytes)");
    }
    // The last element ends at offset + stride * (count - 1) + element_size; compared
    // without forming that sum, which could overflow.
    const size_t length = view.byteLength;
    if (count == 0 || offset > length || element_size > length - offset ||
        (count - 1) > (length - offset - element_size) / out->stride) {
        return malformed_input(str(count) + " elements of " + str(element_size) +
                               " bytes at byteOffset " + str(offset) + " (stride " +
                               str(out->stride) + ") exceed " + label + " (byteLength " +
                               str(length) + ")");
    }
    out->data = bytes.data() + view.byteOffset + offset;
    return BakeError();
}

// The accessor itself: in range, of the required type and an accepted format, not empty.
BakeError check_accessor(const Model& model, int index, int type, unsigned formats) {
    if (index < 0 || size_t(index) >= model.accessors.size()) {
        return malformed_input("accessor " + str(index) + " out of range (accessor count " +
                               str(model.accessors.size()) + ")");
    }
    const tinygltf::Accessor& acc = model.accessors[size_t(index)];
    const std::string label = "accessor " + str(index);
    if (acc.type != type) {
        return malformed_input(label + ": type " + type_name(acc.type) + ", expected " +
                               type_name(type));
    }
    if ((format_of(acc.componentType, acc.normalized) & formats) == 0) {
        return malformed_input(label + ": component type " +
                               component_name(acc.componentType, acc.normalized) +
                               " is not allowed here");
    }
    assert(
        (type != TINYGLTF_TYPE_MAT2 && type != TINYGLTF_TYPE_MAT3 && type != TINYGLTF_TYPE_MAT4) ||
        component_size(acc.componentType) == 4);
    if (acc.count == 0) return malformed_input(label + ": count is 0");
    return BakeError();
}

// The dense part: the bufferView's elements, or zeros when there is none (§3.6.2.3).
template <typename T>
BakeError read_dense(const Model& model, const tinygltf::Accessor& acc, size_t components,
                     std::vector<T>* out) {
    const size_t csize = component_size(acc.componentType);
    if (acc.bufferView < 0) {
        // §3.6.2.3: no bufferView means zeros (possibly overridden by sparse values).
        if (acc.count > kMaxZeroFilledElements) {
            return bake_error(BakeErrorCode::unsupported,
                              str(acc.count) + " elements without a bufferView (at most " +
                                  str(kMaxZeroFilledElements) + " supported)");
        }
        out->assign(acc.count * components, T(0));
        return BakeError();
    }
    Located at;
    const BakeError located =
        locate(model, acc.bufferView, acc.byteOffset, acc.count, components * csize, true, &at);
    if (!located.ok()) return located;
    out->resize(acc.count * components);
    for (size_t i = 0; i < acc.count; ++i) {
        for (size_t c = 0; c < components; ++c) {
            (*out)[i * components + c] = static_cast<T>(read_component(
                at.data + i * at.stride + c * csize, acc.componentType, acc.normalized));
        }
    }
    return BakeError();
}

// Sparse substitution (§3.6.2.3): `count` strictly increasing element indices, each
// replacing one element with a value from the tightly packed values view.
template <typename T>
BakeError apply_sparse(const Model& model, const tinygltf::Accessor& acc, size_t components,
                       std::vector<T>* out) {
    const auto& sparse = acc.sparse;
    if (sparse.count < 1 || size_t(sparse.count) > acc.count) {
        // tinygltf keeps the low 32 bits of the JSON count in an int: a count of 2^31 or
        // more reads as negative, so it is shown as the unsigned 32-bit value it was.
        return malformed_input("sparse count " + str(size_t(uint32_t(sparse.count))) +
                               " out of range (accessor count " + str(acc.count) + ")");
    }
    const int ict = sparse.indices.componentType;
    if ((format_of(ict, false) & (kU8 | kU16 | kU32)) == 0) {
        return malformed_input("sparse indices have component type " + component_name(ict, false));
    }
    if (sparse.indices.byteOffset < 0 || sparse.values.byteOffset < 0) {
        return malformed_input("negative sparse byteOffset");
    }
    const size_t n = size_t(sparse.count);
    const size_t csize = component_size(acc.componentType);
    Located indices, values;
    BakeError located = locate(model, sparse.indices.bufferView, size_t(sparse.indices.byteOffset),
                               n, component_size(ict), false, &indices);
    if (located.ok()) {
        located = locate(model, sparse.values.bufferView, size_t(sparse.values.byteOffset), n,
                         components * csize, false, &values);
    }
    if (!located.ok()) return prefixed("sparse: ", located);
    double previous = -1.0;
    for (size_t k = 0; k < n; ++k) {
        const double target = read_component(indices.data + k * indices.stride, ict, false);
        if (target <= previous || target >= double(acc.count)) {
            return malformed_input("sparse index " + str(size_t(target)) +
                                   " is out of range or not increasing");
        }
        previous = target;
        for (size_t c = 0; c < components; ++c) {
            (*out)[size_t(target) * components + c] = static_cast<T>(read_component(
                values.data + k * values.stride + c * csize, acc.componentType, acc.normalized));
        }
    }
    return BakeError();
}

}  // namespace

template <typename T>
BakeError read_accessor(const Model& model, int index, int type, unsigned formats,
                        std::vector<T>* out) {
    const BakeError checked = check_accessor(model, index, type, formats);
    if (!checked.ok()) return checked;
    const tinygltf::Accessor& acc = model.accessors[size_t(index)];
    const std::string label = "accessor " + str(index) + ": ";
    const size_t components = component_count(type);
    const BakeError dense = read_dense(model, acc, components, out);
    if (!dense.ok()) return prefixed(label, dense);
    if (acc.sparse.isSparse) return prefixed(label, apply_sparse(model, acc, components, out));
    return BakeError();
}

template BakeError read_accessor<float>(const Model&, int, int, unsigned, std::vector<float>*);
template BakeError read_accessor<uint32_t>(const Model&, int, int, unsigned,
                                           std::vector<uint32_t>*);

}  // namespace stipple::bake::gltf
