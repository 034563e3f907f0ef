// The option-parsing layer every stipple tool uses. A tool registers its options (flags,
// text, range-checked integers and numbers, named choices, custom values) and positionals
// on a Parser, then parses argv. Every problem ends the tool the same way: one line on
// stderr, "TOOL: OPTION must be WHAT, got 'VALUE'", and exit status 1 (or the tool's own
// usage status). Numbers are parsed whole ("10x", "" and " 5" are rejected), integers are
// integers, and unsigned values reject a sign. `--name=value` works as `--name value`.
// -h/--help prints the tool's hand-written usage text (which must name every option: the
// parser checks that at --help, so a test running --help catches a missing line).
#pragma once
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

namespace stipple::cli {

// Whole-text value parsers: true and *out on success, false (and *out untouched) otherwise.
bool parse_integer(const std::string& text, long long lo, long long hi, long long* out);
bool parse_unsigned(const std::string& text, uint64_t* out);  // 0 .. 2^64 - 1, no sign
bool parse_number(const std::string& text, double lo, double hi, double* out);
// "WxH" with both in [lo, hi].
bool parse_size(const std::string& text, int lo, int hi, int* width, int* height);

class Parser {
  public:
    // `tool` prefixes every error; `usage` is what --help prints; a bad command line exits
    // with `usage_status` (1; stipple-compare keeps 2, its documented "bad usage" status).
    Parser(const char* tool, const char* usage, int usage_status = 1);
    // Registered handlers refer to the parser: it stays where it was made.
    Parser(const Parser&) = delete;
    Parser& operator=(const Parser&) = delete;

    // A sub-command ("tone"): its name leads the parser's own messages ("tone: unknown
    // option '--x' (see tone --help)").
    Parser& command(const char* name);

    // `names`: "--name" or "-o,--output".
    Parser& flag(const char* names, bool* out, bool value = true);
    Parser& text(const char* names, std::string* out);
    template <class Int>
    Parser& integer(const char* names, long long lo, long long hi, Int* out) {
        return custom(names, [this, lo, hi, out](const std::string& name, const std::string& v) {
            *out = Int(integer_value(name, v, lo, hi));
        });
    }
    Parser& seed(const char* names, uint64_t* out);  // any unsigned 64-bit integer
    template <class Real>
    Parser& number(const char* names, double lo, double hi, Real* out) {
        return custom(names, [this, lo, hi, out](const std::string& name, const std::string& v) {
            *out = Real(number_value(name, v, lo, hi));
        });
    }
    // One of the named values: "--method must be eliminate, simplify or random, got 'x'".
    template <class T>
    Parser& choice(const char* names, std::initializer_list<std::pair<const char*, T>> values,
                   T* out) {
        std::vector<std::pair<std::string, T>> list(values.begin(), values.end());
        return custom(names, [this, list, out](const std::string& name, const std::string& v) {
            std::vector<std::string> words;
            for (const auto& w : list) {
                if (w.first == v) {
                    *out = w.second;
                    return;
                }
                words.push_back(w.first);
            }
            bad_value(name, alternatives(words), v);
        });
    }
    // Any other value: `handle(option name, value)`; it calls fail()/bad_value() on error.
    Parser& custom(const char* names,
                   std::function<void(const std::string&, const std::string&)> handle);

    // Positional arguments, in order; `what` names one in messages ("more than one asset
    // given ('a', 'b')"). rest() takes every positional left (no "more than one" error).
    Parser& positional(const char* what, std::string* out);
    Parser& rest(std::vector<std::string>* out);

    // Parses argv[first, argc). --help prints the usage on stdout and exits 0.
    void parse(int argc, char** argv, int first = 1);

    // "TOOL: message" on stderr, exit usage_status.
    [[noreturn]] void fail(const std::string& message) const;
    // "OPTION must be WHAT, got 'VALUE'".
    [[noreturn]] void bad_value(const std::string& option, const std::string& what,
                                const std::string& value) const;
    long long integer_value(const std::string& option, const std::string& text, long long lo,
                            long long hi) const;
    double number_value(const std::string& option, const std::string& text, double lo,
                        double hi) const;

    // "a, b or c".
    static std::string alternatives(const std::vector<std::string>& words);

  private:
    struct Option {
        std::vector<std::string> names;
        bool takes_value = true;
        std::function<void(const std::string&, const std::string&)> handle;
    };
    struct Positional {
        std::string what;
        std::string* out = nullptr;
    };
    const Option* find(const std::string& name) const;
    void check_usage_names() const;

    std::string tool_, usage_, command_;
    int usage_status_;
    std::vector<Option> options_;
    std::vector<Positional> positionals_;
    std::vector<std::string>* rest_ = nullptr;
};

}  // namespace stipple::cli
