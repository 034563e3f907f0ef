// JSON output of the stipple tools: nlohmann::json values written on one line in the
// tools' established layout ({"key": value, "list": [1, 2]}: a space after ':' and ','),
// with nlohmann's escaping, so a path with a quote or a backslash still gives valid JSON.
#pragma once
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

namespace stipple::cli {

// nlohmann::ordered_json keeps the keys in insertion order, as the tools always printed them.
using Json = nlohmann::ordered_json;

std::string json_line(const Json& value);
// json_line(value) and a newline on `out` (stdout by default).
void print_json(const Json& value, std::FILE* out = stdout);

// The value printf("%.Nf") printed, as a double (so the JSON shows at most N decimals).
double fixed(double value, int decimals);
// The value printf("%.Ng") printed (N significant digits); non-finite values stay as they
// are (and become null in the output).
double significant(double value, int digits);

}  // namespace stipple::cli
