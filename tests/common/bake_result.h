// Tests that check a bake call's success and message (not its code) read a BakeError
// (bake/bake_error.h) through this: true on success, else false with *message set to the
// error's one-line message. Tests of the codes themselves compare error.code directly
// (tests/bake/test_bake_errors.cpp, tests/bake/test_gltf_accessors.cpp).
#pragma once
#include <string>

#include "bake/bake_error.h"

namespace stipple::test {

inline bool bake_ok(const bake::BakeError& error, std::string* message) {
    *message = error.message;
    return error.ok();
}

}  // namespace stipple::test
