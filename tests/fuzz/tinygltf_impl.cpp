// Fuzz builds only (bake/CMakeLists.txt, STIPPLE_FUZZ): tinygltf's implementation compiled
// with the fuzz flags, replacing Debian's libtinygltf.so, so the glTF parser is
// instrumented. The bake sets its own image loader, so stb is left out; the default image
// callbacks the header's TinyGLTF members name are defined here as refusals.
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#include <tiny_gltf.h>

namespace tinygltf {

bool LoadImageData(Image*, const int, std::string* err, std::string*, int, int,
                   const unsigned char*, int, void*) {
    if (err) *err += "image decoding is not built into the fuzz build\n";
    return false;
}

bool WriteImageData(const std::string*, const std::string*, const Image*, bool, std::string*,
                    void*) {
    return false;
}

}  // namespace tinygltf
