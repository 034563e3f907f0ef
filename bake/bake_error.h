// The bake layer's one error type. Every public bake function that can fail returns a
// BakeError; `code` says what kind of failure it is (so callers and tests can tell a missing
// file from a malformed one), `message` is one line naming the problem (and, for importers,
// the file). A default BakeError is success.
#pragma once
#include <cstdint>
#include <string>
#include <utility>

namespace stipple::bake {

enum class BakeErrorCode : uint8_t {
    none = 0,         // success
    io,               // a file cannot be opened, read or written
    malformed_input,  // the input breaks its format's rules (bad accessor, cycle, NaN, ...)
    unsupported,      // valid input this bake cannot handle (compressed geometry, size limits)
    out_of_memory,    // std::bad_alloc, caught at the bake's public entry points
    invalid_option,   // a bake option outside its domain
    internal,         // a library the bake uses failed in an unexpected way
};

struct [[nodiscard]] BakeError {
    BakeErrorCode code = BakeErrorCode::none;
    std::string message;

    bool ok() const { return code == BakeErrorCode::none; }
};

[[nodiscard]] inline BakeError bake_error(BakeErrorCode code, std::string message) {
    return BakeError{code, std::move(message)};
}

// The most common failure: the input breaks its format's rules.
[[nodiscard]] inline BakeError malformed_input(std::string message) {
    return BakeError{BakeErrorCode::malformed_input, std::move(message)};
}

// The same failure with `prefix` put in front of its message (for nested labels such as
// "mesh 0 primitive 1 POSITION: accessor 3: ..."). Success stays success.
[[nodiscard]] inline BakeError prefixed(const std::string& prefix, BakeError error) {
    if (!error.ok()) error.message = prefix + error.message;
    return error;
}

// Name of a code, for logs and tests ("malformed_input").
const char* bake_error_code_name(BakeErrorCode code);

}  // namespace stipple::bake
