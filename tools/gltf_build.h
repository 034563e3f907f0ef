// Building a glTF 2.0 model in memory for the generated test assets (tools/make_stretch_tube.cpp,
// tools/bend_rig.cpp): every array goes into buffer 0 as its own buffer view, and an accessor
// over the whole view. Header-only.
#pragma once
#include <tiny_gltf.h>

#include <cstddef>
#include <utility>
#include <vector>

namespace stipple::tools::gltf_build {

// bufferView.target values (glTF 2.0 spec, bufferView.target); 0: none (animation data,
// inverse bind matrices).
constexpr int kArrayBuffer = 34962;
constexpr int kElementArrayBuffer = 34963;

// Appends `bytes` to buffer 0 as a new buffer view, 4-byte aligned so that every accessor's
// offset is a multiple of its component size (glTF 2.0 spec, "Data Alignment"). The model must
// have its buffer 0.
inline int add_view(tinygltf::Model* model, const void* bytes, size_t size, int target) {
    std::vector<unsigned char>& data = model->buffers[0].data;
    while (data.size() % 4 != 0) data.push_back(0);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = data.size();
    view.byteLength = size;
    view.target = target;
    const auto* p = static_cast<const unsigned char*>(bytes);
    data.insert(data.end(), p, p + size);
    model->bufferViews.push_back(view);
    return static_cast<int>(model->bufferViews.size() - 1);
}

// An accessor over the whole of `view` (offset 0). POSITION and animation inputs must carry
// min and max (glTF 2.0 spec, "Meshes", "Animations").
inline int add_accessor(tinygltf::Model* model, int view, int component_type, int type,
                        size_t count, std::vector<double> min_values = {},
                        std::vector<double> max_values = {}) {
    tinygltf::Accessor accessor;
    accessor.bufferView = view;
    accessor.byteOffset = 0;
    accessor.componentType = component_type;
    accessor.type = type;
    accessor.count = count;
    accessor.minValues = std::move(min_values);
    accessor.maxValues = std::move(max_values);
    model->accessors.push_back(accessor);
    return static_cast<int>(model->accessors.size() - 1);
}

// `values` as a new buffer view and an accessor over it: the accessor's index.
template <typename T>
int add_values(tinygltf::Model* model, const std::vector<T>& values, int target, int component_type,
               int type, size_t count, std::vector<double> min_values = {},
               std::vector<double> max_values = {}) {
    const int view = add_view(model, values.data(), values.size() * sizeof(T), target);
    return add_accessor(model, view, component_type, type, count, std::move(min_values),
                        std::move(max_values));
}

}  // namespace stipple::tools::gltf_build
