// Small glTF 2.0 files written by tests: a binary buffer built value by value and embedded as
// a base64 data URI in place of an "@BUFFER@" placeholder in the JSON.
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

}  // namespace stipple::test
