// What the C API's source files share (runtime/stipple_c_api.cpp defines it): the error every
// failing call records for stipple_last_error and reports to the logger.
#pragma once
#include "runtime/stipple.h"

namespace stipple {

// Records `message` as the last error, logs it, and returns `result`.
stipple_result c_api_fail(stipple_result result, const char* message);

}  // namespace stipple
