#include "tools/json_line.h"

#include <cmath>
#include <cstdlib>

namespace stipple::cli {

namespace {

void write(const Json& v, std::string* out) {
    if (v.is_object()) {
        *out += '{';
        bool first = true;
        for (auto it = v.begin(); it != v.end(); ++it) {
            *out += first ? "" : ", ";
            *out += Json(it.key()).dump() + ": ";
            write(it.value(), out);
            first = false;
        }
        *out += '}';
    } else if (v.is_array()) {
        *out += '[';
        for (size_t i = 0; i < v.size(); ++i) {
            *out += i ? ", " : "";
            write(v[i], out);
        }
        *out += ']';
    } else {
        // Scalars: nlohmann's escaping (invalid UTF-8 replaced, not thrown) and numbers; a
        // whole float prints as printf's %g did ("2", not nlohmann's "2.0").
        std::string text = v.dump(-1, ' ', false, Json::error_handler_t::replace);
        if (v.is_number_float() && text.size() > 2 && text.compare(text.size() - 2, 2, ".0") == 0)
            text.resize(text.size() - 2);
        *out += text;
    }
}

double reparse(const char* format, int precision, double value) {
    if (!std::isfinite(value)) return value;
    char buf[64];
    std::snprintf(buf, sizeof(buf), format, precision, value);
    return std::strtod(buf, nullptr);
}

}  // namespace

std::string json_line(const Json& value) {
    std::string out;
    write(value, &out);
    return out;
}

void print_json(const Json& value, std::FILE* out) {
    std::fprintf(out, "%s\n", json_line(value).c_str());
}

double fixed(double value, int decimals) {
    return reparse("%.*f", decimals, value);
}

double significant(double value, int digits) {
    return reparse("%.*g", digits, value);
}

}  // namespace stipple::cli
