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
// StatusCode: io_error, unsupported_version and out_of_memory onto theirs, the rest onto
// bad_asset.
enum class LoadError {
    ok = 0,
    io_error,             // file missing or unreadable
    bad_magic,            // not a .stip file
    unsupported_version,  // written by a newer or older format
    wrong_endianness,
    truncated,          // file shorter than its header or a section says
    checksum_mismatch,  // a section's bytes do not match its CRC
    missing_section,
    malformed_section,  // sizes inside a section disagree
    out_of_range,       // an index points outside its array
    bad_value,          // NaN, infinity, or a value outside its domain
    out_of_memory,      // the asset's storage could not be allocated
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
// A failed asset load: code from the load error (see LoadError), printf-style message.
[[nodiscard]] Status load_failure(LoadError error, const char* format, ...)
    __attribute__((format(printf, 2, 3)));

StatusCode status_code_of(LoadError error);
const char* status_code_name(StatusCode code);
const char* load_error_name(LoadError error);

}  // namespace stipple
