#include "cli.h"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

namespace dss::cli {

namespace {

// After an optional sign: "0x" or "0X" (strtod would read hexadecimal).
bool isHex(const char* s) {
  if (*s == '+' || *s == '-') ++s;
  return s[0] == '0' && (s[1] == 'x' || s[1] == 'X');
}

std::string formatNumber(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10g", x);
  return buf;
}

// "a finite number >= 0", "an integer in [1, 100]", ...: what a value must be.
std::string expected(const char* kind, const std::string& min, const std::string& max, bool has_min,
                     bool has_max) {
  std::string s = kind;
  if (has_min && has_max)
    s += " in [" + min + ", " + max + "]";
  else if (has_min)
    s += " >= " + min;
  else if (has_max)
    s += " <= " + max;
  return s;
}

}  // namespace

void usageError(const char* program, const std::string& what) {
  std::fprintf(stderr, "%s: %s\n(%s --help for usage)\n", program, what.c_str(), program);
  std::exit(kExitUsage);
}

std::optional<double> parseNumber(const char* text, double min, double max) {
  if (*text == '\0' || std::isspace(static_cast<unsigned char>(*text)) || isHex(text))
    return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const double x = std::strtod(text, &end);
  // ERANGE with a finite result is underflow: keep strtod's rounding (zero or a subnormal).
  if (*end != '\0' || !std::isfinite(x) || x < min || x > max) return std::nullopt;
  return x;
}

std::optional<long long> parseInteger(const char* text, long long min, long long max) {
  const char* digits = text + (*text == '+' || *text == '-');
  if (*digits == '\0') return std::nullopt;
  for (const char* p = digits; *p; ++p)
    if (*p < '0' || *p > '9') return std::nullopt;
  errno = 0;
  const long long x = std::strtoll(text, nullptr, 10);
  if (errno == ERANGE || x < min || x > max) return std::nullopt;
  return x;
}

ArgCursor::ArgCursor(int argc, char** argv, const char* program, const char* usage)
    : argc_(argc), argv_(argv), program_(program), usage_(usage) {}

bool ArgCursor::next() {
  if (index_ + 1 >= argc_) {
    index_ = argc_;
    return false;
  }
  const char* a = argv_[++index_];
  name_ = a;
  value_ = nullptr;
  is_option_ = false;
  if (options_ended_) return true;
  if (name_ == "--") {
    options_ended_ = true;
    return next();
  }
  // "-" (stdin) and negative numbers are positionals.
  if (a[0] != '-' || a[1] == '\0' || std::isdigit(static_cast<unsigned char>(a[1])) || a[1] == '.')
    return true;
  is_option_ = true;
  if (a[1] == '-') {
    const std::size_t eq = name_.find('=');
    if (eq != std::string_view::npos) {
      name_ = name_.substr(0, eq);
      value_ = a + eq + 1;
    }
  }
  if (name_ == "--help" || name_ == "-h") {
    if (value_) error(std::string(name_) + " takes no value");
    std::fputs(usage_, stdout);
    std::exit(0);
  }
  return true;
}

bool ArgCursor::option(std::string_view name) { return is_option_ && name_ == name; }

bool ArgCursor::flag(std::string_view name) {
  if (!option(name)) return false;
  if (value_) error(std::string(name) + " takes no value, got '" + argv_[index_] + "'");
  return true;
}

bool ArgCursor::positional(const char* label) {
  if (is_option_ || index_ >= argc_) return false;
  name_ = label;
  value_ = argv_[index_];
  return true;
}

const char* ArgCursor::value() {
  if (value_) return value_;
  if (!is_option_) return argv_[index_];
  if (index_ + 1 >= argc_) error(std::string(name_) + " needs a value");
  value_ = argv_[++index_];
  return value_;
}

double ArgCursor::number(double min, double max) {
  const char* text = value();
  if (const auto x = parseNumber(text, min, max)) return *x;
  const double lowest = std::numeric_limits<double>::lowest(),
               highest = std::numeric_limits<double>::max();
  error(std::string(name_) + ": expected " +
        expected("a finite number", formatNumber(min), formatNumber(max), min > lowest,
                 max < highest) +
        ", got '" + text + "'");
}

std::vector<double> ArgCursor::numbers(std::size_t count) {
  const std::string text = value();
  std::vector<double> out;
  std::size_t begin = 0;
  for (;;) {
    const std::size_t end = text.find(',', begin);
    const std::string item = text.substr(begin, end == std::string::npos ? end : end - begin);
    const auto x = parseNumber(item.c_str(), std::numeric_limits<double>::lowest(),
                               std::numeric_limits<double>::max());
    if (!x) break;
    out.push_back(*x);
    if (end == std::string::npos) {
      if (out.size() == count) return out;
      break;
    }
    begin = end + 1;
  }
  error(std::string(name_) + ": expected " + std::to_string(count) +
        " finite numbers separated by commas, got '" + text + "'");
}

long long ArgCursor::integer(long long min, long long max) {
  const char* text = value();
  if (const auto x = parseInteger(text, min, max)) return *x;
  error(std::string(name_) + ": expected " +
        expected("an integer", std::to_string(min), std::to_string(max),
                 min > std::numeric_limits<long long>::min(),
                 max < std::numeric_limits<long long>::max()) +
        ", got '" + text + "'");
}

void ArgCursor::unknown() const {
  if (is_option_) error("unknown option " + std::string(name_));
  error("unexpected argument '" + std::string(argv_[index_]) + "'");
}

void ArgCursor::error(const std::string& what) const { usageError(program_, what); }

}  // namespace dss::cli
