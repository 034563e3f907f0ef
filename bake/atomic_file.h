// Writing a file all-or-nothing: the bytes go to a fresh temporary file next to the target
// (created exclusively with mkstemp, "TARGET.XXXXXX", so a symlink or another bake's temp
// file at a fixed name is never opened), are fsync'ed, and the temp file is renamed over the
// target (which replaces a symlink there, never its target) and the folder fsync'ed. Every
// failure removes the temp file and names the cause (strerror: "No space left on device",
// "File too large", ...).
//
// A process that may be killed while writing (stipple-bake) calls remove_pending_temp_file()
// from its SIGINT/SIGTERM handlers and ignores SIGXFSZ, so a write over `ulimit -f` fails
// with EFBIG instead of killing the process and its temp file is removed too.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "bake/bake_error.h"

namespace stipple::bake {

// Errors: io. The file gets mode 0666 minus the umask, as fopen would have given it.
[[nodiscard]] BakeError write_file_atomically(const std::string& path,
                                              const std::vector<uint8_t>& bytes);

// Unlinks the temp file a write_file_atomically in progress holds, if any. Async-signal-
// safe (the path lives in a static buffer; only unlink(2) is called).
void remove_pending_temp_file() noexcept;

}  // namespace stipple::bake
