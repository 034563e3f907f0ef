// The runtime's one error type: every runtime call that can fail (asset load, GL loading,
// renderer and pipeline creation, frame-setting resolution) returns a Status. Its code maps
// 1:1 onto the C API's stipple_result (runtime/stipple.h); a failed asset load also says
// which check failed (LoadError). No exceptions, no allocation: the message is a fixed
// buffer.
#pragma once
#include <cstdint>

namespace stipple {

// One per stipple_result, in the same order and with the same values.
enum class StatusCode : uint8_t {
    ok = 0,
    invalid_argument,     // a caller's value is outside its documented range
    io_error,             // file missing or unreadable
    bad_asset,            // truncated, corrupted or inconsistent asset (LoadError says how)
    unsupported_version,  // asset written by a newer or older format
    gl_error,             // missing GL entry point, shader or framebuffer error
    out_of_memory,        // an allocation at load or create failed
};

// Which check of an asset load failed (Status::error of load_asset_*). Each maps onto one
// StatusCode: io_error, unsupported_version, out_of_memory and invalid_argument onto theirs,
// the rest onto bad_asset. docs/errors.md lists every rule, message and code.
enum class LoadError {
    ok = 0,
    io_error,             // file missing or unreadable
    bad_magic,            // not a .stip file
    unsupported_version,  // written by a newer or older format
    wrong_endianness,
    truncated,          // file shorter than its header or a section says
    checksum_mismatch,  // a section's bytes do not match its CRC
    missing_section,
    malformed_section,   // sizes inside a section disagree
    out_of_range,        // an index points outside its array
    bad_value,           // NaN, infinity, or a value outside its domain
    out_of_memory,       // the asset's storage could not be allocated
    invalid_argument,    // the caller passed no bytes, no path or no output (StatusCode's too)
    count_over_limit,    // a count above its limit in runtime/asset_limits.h
    count_exceeds_data,  // a count needs more bytes than its section holds
    decoded_size_limit,  // the asset would decode into more memory than the limit allows
    zero_count,          // a count the runtime needs to be >= 1 is 0 (vertices, points, ...)
    bad_normal,          // a MESH normal neither zero nor of unit length
    bad_skin_weight,     // a SKIN weight outside [0, 1], or a vertex's weights not summing to 1
    bad_radius,          // a PNTQ radius scale negative or not finite
};

struct Status {
    StatusCode code = StatusCode::ok;
    LoadError error = LoadError::ok;  // asset loads only: the check that failed
    char message[200] = {};  // one line naming the problem, e.g. "PNTS: host triangle 9 >= 8"
    bool ok() const { return code == StatusCode::ok; }
};

// A failed Status with a printf-style message.
[[nodiscard]] Status make_status(StatusCode code, const char* format, ...)
    __attribute__((format(printf, 2, 3)));
// A failed asset load: code from the load error (see LoadError), printf-style message. The
// message keeps only printable ASCII: any other byte (from the file: a tag, a clip name) is
// written as \xNN, so a hostile asset cannot put control characters on a terminal.
[[nodiscard]] Status load_failure(LoadError error, const char* format, ...)
    __attribute__((format(printf, 2, 3)));

StatusCode status_code_of(LoadError error);
const char* status_code_name(StatusCode code);
const char* load_error_name(LoadError error);

}  // namespace stipple
