#include "tools/cli_options.h"

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstdlib>

namespace stipple::cli {

namespace {

// strtol and friends skip leading white space and take an empty string as 0: a value must
// start with a digit or a sign (or, for numbers, a point) to count.
bool starts_like_number(const std::string& text) {
    if (text.empty()) return false;
    const unsigned char c = static_cast<unsigned char>(text[0]);
    return std::isdigit(c) || c == '-' || c == '+' || c == '.';
}

std::string format_double(double v) {
    char buf[64];
    std::snprintf(buf, sizeof(buf), "%g", v);
    return buf;
}

std::vector<std::string> split_names(const char* names) {
    std::vector<std::string> out;
    std::string current;
    for (const char* c = names; *c; ++c) {
        if (*c == ',') {
            out.push_back(current);
            current.clear();
        } else {
            current += *c;
        }
    }
    out.push_back(current);
    return out;
}

}  // namespace

bool parse_integer(const std::string& text, long long lo, long long hi, long long* out) {
    if (!starts_like_number(text)) return false;
    errno = 0;
    char* end = nullptr;
    const long long v = std::strtoll(text.c_str(), &end, 10);
    if (errno != 0 || end == text.c_str() || *end != '\0' || v < lo || v > hi) return false;
    *out = v;
    return true;
}

bool parse_unsigned(const std::string& text, uint64_t* out) {
    if (text.empty() || !std::isdigit(static_cast<unsigned char>(text[0]))) return false;
    errno = 0;
    char* end = nullptr;
    const unsigned long long v = std::strtoull(text.c_str(), &end, 10);
    if (errno != 0 || *end != '\0') return false;
    *out = uint64_t(v);
    return true;
}

bool parse_number(const std::string& text, double lo, double hi, double* out) {
    // Decimal only: strtod would also take hexadecimal ("0x1p-2"), "inf" and "nan".
    if (!starts_like_number(text) || text.find_first_of("xXnN") != std::string::npos) return false;
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (end == text.c_str() || *end != '\0' || !(v >= lo && v <= hi)) return false;
    *out = v;
    return true;
}

bool parse_size(const std::string& text, int lo, int hi, int* width, int* height) {
    const size_t x = text.find('x');
    long long w = 0, h = 0;
    if (x == std::string::npos || !parse_integer(text.substr(0, x), lo, hi, &w) ||
        !parse_integer(text.substr(x + 1), lo, hi, &h))
        return false;
    *width = int(w);
    *height = int(h);
    return true;
}

Parser::Parser(const char* tool, const char* usage, int usage_status)
    : tool_(tool), usage_(usage), usage_status_(usage_status) {}

Parser& Parser::command(const char* name) {
    command_ = name;
    return *this;
}

Parser& Parser::flag(const char* names, bool* out, bool value) {
    options_.push_back(
        Option{split_names(names), false,
               [out, value](const std::string&, const std::string&) { *out = value; }});
    return *this;
}

Parser& Parser::text(const char* names, std::string* out) {
    return custom(names, [out](const std::string&, const std::string& v) { *out = v; });
}

Parser& Parser::seed(const char* names, uint64_t* out) {
    return custom(names, [this, out](const std::string& name, const std::string& v) {
        if (!parse_unsigned(v, out)) bad_value(name, "a non-negative integer below 2^64", v);
    });
}

Parser& Parser::custom(const char* names,
                       std::function<void(const std::string&, const std::string&)> handle) {
    options_.push_back(Option{split_names(names), true, std::move(handle)});
    return *this;
}

Parser& Parser::positional(const char* what, std::string* out) {
    positionals_.push_back(Positional{what, out});
    return *this;
}

Parser& Parser::rest(std::vector<std::string>* out) {
    rest_ = out;
    return *this;
}

const Parser::Option* Parser::find(const std::string& name) const {
    for (const Option& o : options_)
        for (const std::string& n : o.names)
            if (n == name) return &o;
    return nullptr;
}

void Parser::check_usage_names() const {
    for (const Option& o : options_)
        for (const std::string& n : o.names)
            if (usage_.find(n) == std::string::npos)
                fail("internal error: option " + n + " is missing from --help");
}

void Parser::parse(int argc, char** argv, int first) {
    const std::string lead = command_.empty() ? "" : command_ + ": ";
    const std::string see = command_.empty() ? "see --help" : "see " + command_ + " --help";
    size_t next_positional = 0;
    for (int i = first; i < argc; ++i) {
        std::string arg = argv[i];
        if (arg == "-h" || arg == "--help") {
            check_usage_names();
            std::fputs(usage_.c_str(), stdout);
            std::exit(0);
        }
        if (arg.size() > 1 && arg[0] == '-') {
            std::string value;
            bool inline_value = false;
            const size_t eq = arg.find('=');
            if (arg.rfind("--", 0) == 0 && eq != std::string::npos) {
                value = arg.substr(eq + 1);
                arg = arg.substr(0, eq);
                inline_value = true;
            }
            const Option* o = find(arg);
            if (!o) fail(lead + "unknown option '" + arg + "' (" + see + ")");
            if (!o->takes_value && inline_value) fail("option " + arg + " takes no value");
            if (o->takes_value && !inline_value) {
                if (i + 1 >= argc) fail("option " + arg + " needs a value");
                value = argv[++i];
            }
            o->handle(arg, value);
        } else if (next_positional < positionals_.size()) {
            *positionals_[next_positional++].out = arg;
        } else if (rest_) {
            rest_->push_back(arg);
        } else if (!positionals_.empty()) {
            const Positional& last = positionals_.back();
            fail(lead + "more than one " + last.what + " given ('" + *last.out + "', '" + arg +
                 "')");
        } else {
            fail(lead + "unexpected argument '" + arg + "' (" + see + ")");
        }
    }
}

void Parser::fail(const std::string& message) const {
    std::fprintf(stderr, "%s: %s\n", tool_.c_str(), message.c_str());
    std::exit(usage_status_);
}

void Parser::bad_value(const std::string& option, const std::string& what,
                       const std::string& value) const {
    fail(option + " must be " + what + ", got '" + value + "'");
}

long long Parser::integer_value(const std::string& option, const std::string& text, long long lo,
                                long long hi) const {
    long long v = 0;
    if (!parse_integer(text, lo, hi, &v))
        bad_value(option, "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]",
                  text);
    return v;
}

double Parser::number_value(const std::string& option, const std::string& text, double lo,
                            double hi) const {
    double v = 0;
    if (!parse_number(text, lo, hi, &v))
        bad_value(option, "a number in [" + format_double(lo) + ", " + format_double(hi) + "]",
                  text);
    return v;
}

std::string Parser::alternatives(const std::vector<std::string>& words) {
    std::string out;
    for (size_t i = 0; i < words.size(); ++i)
        out += (i == 0 ? "" : (i + 1 == words.size() ? " or " : ", ")) + words[i];
    return out;
}

}  // namespace stipple::cli
