// make-test-meshes OUTDIR [--triangles N]: writes fan_N.obj, grid_N.obj, star_N.obj and
// duplicates_N.obj (bake/connectivity_meshes.h), the hostile-connectivity inputs of
// docs/hierarchy.md's "Complexity" table.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "bake/connectivity_meshes.h"

namespace {

bool write_obj(const std::string& path, const stipple::bake::RawScene& s) {
    FILE* f = std::fopen(path.c_str(), "w");
    if (!f) return false;
    for (size_t v = 0; v < s.positions.size(); v += 3)
        std::fprintf(f, "v %.9g %.9g %.9g\n", double(s.positions[v]), double(s.positions[v + 1]),
                     double(s.positions[v + 2]));
    for (size_t t = 0; t < s.indices.size(); t += 3)
        std::fprintf(f, "f %u %u %u\n", s.indices[t] + 1, s.indices[t + 1] + 1,
                     s.indices[t + 2] + 1);
    return std::fclose(f) == 0;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2 || std::strcmp(argv[1], "-h") == 0 || std::strcmp(argv[1], "--help") == 0) {
        std::fprintf(stderr, "usage: make-test-meshes OUTDIR [--triangles N] (default 10000)\n");
        return argc < 2 ? 2 : 0;
    }
    unsigned long n = 10000;
    if (argc == 4 && std::strcmp(argv[2], "--triangles") == 0)
        n = std::strtoul(argv[3], nullptr, 10);
    if (n < 2 || n > 10000000 || (argc != 2 && argc != 4)) {
        std::fprintf(stderr, "make-test-meshes: --triangles must be in [2, 10000000]\n");
        return 2;
    }
    namespace m = stipple::bake::meshes;
    const std::string dir = argv[1], tag = "_" + std::to_string(n) + ".obj";
    const uint32_t count = uint32_t(n);
    const bool ok = write_obj(dir + "/fan" + tag, m::fan(count)) &&
                    write_obj(dir + "/grid" + tag, m::grid(count)) &&
                    write_obj(dir + "/star" + tag, m::star(count)) &&
                    write_obj(dir + "/duplicates" + tag, m::duplicates(count));
    if (!ok) std::fprintf(stderr, "make-test-meshes: cannot write to %s\n", dir.c_str());
    return ok ? 0 : 1;
}
