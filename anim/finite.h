// The one finiteness check of stipple (anim, runtime and bake): true if none of the values
// is NaN or infinite.
#pragma once
#include <cmath>
#include <cstddef>

namespace stipple {

template <typename T>
bool all_finite(const T* values, size_t n) {
    for (size_t i = 0; i < n; ++i) {
        if (!std::isfinite(values[i])) return false;
    }
    return true;
}

// Any contiguous container with data() and size() (std::vector in the bake's importers).
template <typename Container>
auto all_finite(const Container& values) -> decltype(values.data(), values.size(), true) {
    return all_finite(values.data(), values.size());
}

}  // namespace stipple
