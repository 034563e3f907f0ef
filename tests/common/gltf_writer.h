// Small glTF 2.0 files written by tests (part of the shared fixtures in tests/common/): a
// binary buffer built value by value and embedded as a base64 data URI in place of an
// "@BUFFER@" placeholder in the JSON.
#pragma once
#include <cstdint>
#include <cstring>
#include <fstream>
#include <initializer_list>
#include <string>
#include <vector>

namespace stipple::test {

struct GltfBin {
    std::vector<uint8_t> bytes;
    template <typename T>
    GltfBin& put(std::initializer_list<T> values) {
        for (T v : values) {
            uint8_t raw[sizeof(T)];
            std::memcpy(raw, &v, sizeof(T));
            bytes.insert(bytes.end(), raw, raw + sizeof(T));
        }
        return *this;
    }
    GltfBin& pad4() {
        while (bytes.size() % 4) bytes.push_back(0);
        return *this;
    }
};

inline std::string gltf_base64(const std::vector<uint8_t>& in) {
    static const char* const kAlphabet =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < in.size(); i += 3) {
        const uint32_t b0 = in[i];
        const uint32_t b1 = i + 1 < in.size() ? in[i + 1] : 0;
        const uint32_t b2 = i + 2 < in.size() ? in[i + 2] : 0;
        const uint32_t triple = (b0 << 16) | (b1 << 8) | b2;
        out += kAlphabet[(triple >> 18) & 63];
        out += kAlphabet[(triple >> 12) & 63];
        out += i + 1 < in.size() ? kAlphabet[(triple >> 6) & 63] : '=';
        out += i + 2 < in.size() ? kAlphabet[triple & 63] : '=';
    }
    return out;
}

// Writes `json` to `path` with "@BUFFER@" replaced by buffer 0 holding `bin`.
inline void write_gltf(const std::string& path, std::string json, const GltfBin& bin) {
    const std::string buffer = R"({"uri": "data:application/octet-stream;base64,)" +
                               gltf_base64(bin.bytes) + R"(", "byteLength": )" +
                               std::to_string(bin.bytes.size()) + "}";
    const size_t at = json.find("@BUFFER@");
    if (at != std::string::npos) json.replace(at, 8, buffer);
    std::ofstream(path, std::ios::binary) << json;
}

// Test scenes shared by several files.

// A unit cube (outward faces) on node 0, whose clip "run" moves it 12 units along +x and 4
// up and back in 2 seconds: far outside the rest pose's bounds.
inline void write_running_cube(const std::string& path) {
    GltfBin bin;
    bin.put<float>({-0.5f, -0.5f, -0.5f, 0.5f, -0.5f, -0.5f, 0.5f, 0.5f, -0.5f, -0.5f, 0.5f, -0.5f,
                    -0.5f, -0.5f, 0.5f,  0.5f, -0.5f, 0.5f,  0.5f, 0.5f, 0.5f,  -0.5f, 0.5f, 0.5f});
    bin.put<uint16_t>({0, 3, 2, 0, 2, 1, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                       3, 7, 6, 3, 6, 2, 0, 4, 7, 0, 7, 3, 1, 2, 6, 1, 6, 5});
    bin.put<float>({0, 1, 2});
    bin.put<float>({0, 0, 0, 12, 4, 0, 0, 0, 0});
    write_gltf(path, R"({
      "asset": {"version": "2.0"},
      "scene": 0, "scenes": [{"nodes": [0]}],
      "nodes": [{"mesh": 0}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
      "animations": [{"name": "run",
        "channels": [{"sampler": 0, "target": {"node": 0, "path": "translation"}}],
        "samplers": [{"input": 2, "output": 3, "interpolation": "LINEAR"}]}],
      "buffers": [@BUFFER@],
      "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 96},
                      {"buffer": 0, "byteOffset": 96, "byteLength": 72},
                      {"buffer": 0, "byteOffset": 168, "byteLength": 12},
                      {"buffer": 0, "byteOffset": 180, "byteLength": 36}],
      "accessors": [
        {"bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3",
         "min": [-0.5, -0.5, -0.5], "max": [0.5, 0.5, 0.5]},
        {"bufferView": 1, "componentType": 5123, "count": 36, "type": "SCALAR"},
        {"bufferView": 2, "componentType": 5126, "count": 3, "type": "SCALAR",
         "min": [0], "max": [2]},
        {"bufferView": 3, "componentType": 5126, "count": 3, "type": "VEC3"}]
    })",
               bin);
}

}  // namespace stipple::test
