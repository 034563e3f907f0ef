// libFuzzer target: the static-mesh importer (bake/static_mesh_import.cpp over OpenMesh's
// readers). The first byte picks the format (0: OBJ, 1: PLY, 2: STL, modulo 3), the rest is
// the file. OpenMesh is Debian's shared library: its readers run under the fuzzer but are
// not instrumented (docs/fuzzing.md).
#include <cstddef>
#include <cstdint>

#include "bake/scene_import.h"
#include "tests/fuzz/fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size < 1) return 0;
    static const char* const kNames[] = {"mesh.obj", "mesh.ply", "mesh.stl"};
    const std::string path = stipple::fuzz::write_scratch(kNames[data[0] % 3], data + 1, size - 1);
    if (path.empty()) return 0;
    stipple::bake::RawScene scene;
    (void)stipple::bake::import_static_mesh(path, &scene);
    return 0;
}
