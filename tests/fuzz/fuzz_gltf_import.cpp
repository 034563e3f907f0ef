// libFuzzer target: the glTF importer (bake/gltf_import.cpp and its parts, tinygltf) on
// arbitrary bytes, as a .gltf file (a GLB is recognised by its magic, whatever the name).
// The model lies alone in a scratch folder, so external buffer URIs find nothing; data URIs
// and GLB chunks carry the buffers. docs/fuzzing.md.
#include <cstddef>
#include <cstdint>

#include "bake/scene_import.h"
#include "tests/fuzz/fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = stipple::fuzz::write_scratch("model.gltf", data, size);
    if (path.empty()) return 0;
    stipple::bake::RawScene scene;
    (void)stipple::bake::import_gltf(path, &scene);
    return 0;
}
