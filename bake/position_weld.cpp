#include "bake/position_weld.h"

#include <cstring>

namespace stipple::bake {

std::vector<uint32_t> weld_by_position(const RawScene& s) {
    const size_t n = s.vertex_count();
    struct Slot {
        uint32_t bits[3];
        uint32_t id = 0xFFFFFFFFu;
    };
    std::vector<Slot> table(hash_table_size(n));
    const size_t mask = table.size() - 1;
    std::vector<uint32_t> welded(n);
    uint32_t next = 0;
    for (size_t v = 0; v < n; ++v) {
        uint32_t bits[3];
        for (int k = 0; k < 3; ++k) {
            const float x = s.positions[v * 3 + size_t(k)] + 0.0f;  // -0 -> +0
            std::memcpy(&bits[k], &x, 4);
        }
        size_t h =
            size_t(hash_mix(uint64_t(bits[0]) << 32 ^ uint64_t(bits[1]) << 16 ^ bits[2])) & mask;
        while (table[h].id != 0xFFFFFFFFu &&
               !(table[h].bits[0] == bits[0] && table[h].bits[1] == bits[1] &&
                 table[h].bits[2] == bits[2]))
            h = (h + 1) & mask;
        if (table[h].id == 0xFFFFFFFFu) {
            std::memcpy(table[h].bits, bits, sizeof bits);
            table[h].id = next++;
        }
        welded[v] = table[h].id;
    }
    return welded;
}

}  // namespace stipple::bake
