// Command-line helpers shared by the stipple tools: one-line errors with the tool's name,
// an argument cursor, and range-checked numbers. Header-only; no library to link.
#pragma once
#include <cstdio>
#include <cstdlib>
#include <string>

namespace stipple::cli {

struct Args {
    const char* tool;
    int argc;
    char** argv;
    int at = 0;

    // The next argument, or false when there is none.
    bool next(std::string* arg) {
        if (++at >= argc) return false;
        *arg = argv[at];
        return true;
    }
    // The value of `option`, which must follow it.
    const char* value(const std::string& option) {
        if (at + 1 >= argc) die("option " + option + " needs a value");
        return argv[++at];
    }
    [[noreturn]] void die(const std::string& message) const {
        std::fprintf(stderr, "%s: %s\n", tool, message.c_str());
        std::exit(1);
    }
    // A number in [lo, hi] or a one-line error naming the option and the range.
    double number(const std::string& option, const char* text, double lo, double hi) const {
        char* end = nullptr;
        const double v = std::strtod(text, &end);
        if (end == text || *end != '\0' || !(v >= lo && v <= hi)) {
            char buf[200];
            std::snprintf(buf, sizeof(buf), "%s must be a number in [%g, %g], got '%s'",
                          option.c_str(), lo, hi, text);
            die(buf);
        }
        return v;
    }
};

}  // namespace stipple::cli
