// The bake's only source of randomness: splitmix64 (Steele, Lea, Flood 2014) on a seeded
// state. No std:: distributions: their output differs between standard libraries, and the
// same input, options and seed must give the same bytes everywhere.
#pragma once
#include <cstdint>

namespace stipple::bake {

struct Rng {
    uint64_t state = 1;

    uint64_t next() {
        uint64_t z = (state += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    // Uniform in [0, 1) with 53 random bits.
    double uniform() { return double(next() >> 11) * (1.0 / 9007199254740992.0); }
    // Uniform in [0, n), n > 0 (the modulo bias is below 2^-40 for the sizes used here).
    uint32_t below(uint64_t n) { return uint32_t(next() % n); }
};

}  // namespace stipple::bake
