#include "runtime/status.h"

#include <cstdarg>
#include <cstdio>

namespace stipple {

namespace {

Status vstatus(StatusCode code, LoadError error, const char* format, va_list args) {
    Status s;
    s.code = code;
    s.error = error;
    std::vsnprintf(s.message, sizeof(s.message), format, args);
    return s;
}

}  // namespace

Status make_status(StatusCode code, const char* format, ...) {
    va_list args;
    va_start(args, format);
    Status s = vstatus(code, LoadError::ok, format, args);
    va_end(args);
    return s;
}

Status load_failure(LoadError error, const char* format, ...) {
    char raw[sizeof(Status::message) * 2];
    va_list args;
    va_start(args, format);
    std::vsnprintf(raw, sizeof(raw), format, args);
    va_end(args);
    Status s;
    s.code = status_code_of(error);
    s.error = error;
    // Printable ASCII only; everything else as \xNN (truncated at a whole escape).
    size_t at = 0;
    for (const char* c = raw; *c != '\0'; ++c) {
        const unsigned char b = static_cast<unsigned char>(*c);
        const bool plain = b >= 0x20 && b < 0x7F;
        if (at + (plain ? 1 : 4) >= sizeof(s.message)) break;
        if (plain)
            s.message[at++] = char(b);
        else
            at += size_t(std::snprintf(s.message + at, 5, "\\x%02x", b));
    }
    s.message[at] = '\0';
    return s;
}

StatusCode status_code_of(LoadError error) {
    switch (error) {
        case LoadError::ok:
            return StatusCode::ok;
        case LoadError::io_error:
            return StatusCode::io_error;
        case LoadError::unsupported_version:
            return StatusCode::unsupported_version;
        case LoadError::out_of_memory:
            return StatusCode::out_of_memory;
        case LoadError::invalid_argument:
            return StatusCode::invalid_argument;
        default:
            return StatusCode::bad_asset;
    }
}

const char* status_code_name(StatusCode code) {
    switch (code) {
        case StatusCode::ok:
            return "ok";
        case StatusCode::invalid_argument:
            return "invalid_argument";
        case StatusCode::io_error:
            return "io_error";
        case StatusCode::bad_asset:
            return "bad_asset";
        case StatusCode::unsupported_version:
            return "unsupported_version";
        case StatusCode::gl_error:
            return "gl_error";
        case StatusCode::out_of_memory:
            return "out_of_memory";
    }
    return "unknown";
}

const char* load_error_name(LoadError error) {
    switch (error) {
        case LoadError::ok:
            return "ok";
        case LoadError::io_error:
            return "io_error";
        case LoadError::bad_magic:
            return "bad_magic";
        case LoadError::unsupported_version:
            return "unsupported_version";
        case LoadError::wrong_endianness:
            return "wrong_endianness";
        case LoadError::truncated:
            return "truncated";
        case LoadError::checksum_mismatch:
            return "checksum_mismatch";
        case LoadError::missing_section:
            return "missing_section";
        case LoadError::malformed_section:
            return "malformed_section";
        case LoadError::out_of_range:
            return "out_of_range";
        case LoadError::bad_value:
            return "bad_value";
        case LoadError::out_of_memory:
            return "out_of_memory";
        case LoadError::invalid_argument:
            return "invalid_argument";
        case LoadError::count_over_limit:
            return "count_over_limit";
        case LoadError::count_exceeds_data:
            return "count_exceeds_data";
        case LoadError::decoded_size_limit:
            return "decoded_size_limit";
        case LoadError::zero_count:
            return "zero_count";
        case LoadError::bad_normal:
            return "bad_normal";
        case LoadError::bad_skin_weight:
            return "bad_skin_weight";
        case LoadError::bad_radius:
            return "bad_radius";
    }
    return "unknown";
}

}  // namespace stipple
