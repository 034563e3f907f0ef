#include "bake/bake_error.h"

namespace stipple::bake {

const char* bake_error_code_name(BakeErrorCode code) {
    switch (code) {
        case BakeErrorCode::none:
            return "none";
        case BakeErrorCode::io:
            return "io";
        case BakeErrorCode::malformed_input:
            return "malformed_input";
        case BakeErrorCode::unsupported:
            return "unsupported";
        case BakeErrorCode::out_of_memory:
            return "out_of_memory";
        case BakeErrorCode::invalid_option:
            return "invalid_option";
        case BakeErrorCode::internal:
            return "internal";
    }
    return "unknown";
}

}  // namespace stipple::bake
