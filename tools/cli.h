// Command-line parsing shared by the dss executables. An ArgCursor walks argv one argument at
// a time and the caller asks it what the current argument is: an option with a value
// (`--name value` or `--name=value`), a bare flag, or a positional. Values are read strictly:
// a number must be the whole argument, decimal, finite and within the caller's range. Every
// usage error goes through usageError(), which prints `PROGRAM: WHAT` and a hint line to
// stderr and exits with kExitUsage, so that all tools fail the same way on a bad command line.
// The cursor reads argv in place (no copies of the arguments).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace dss::cli {

/// Exit code of a usage error (bad option, bad value, missing argument).
inline constexpr int kExitUsage = 2;

/// Prints "PROGRAM: WHAT" and "(PROGRAM --help for usage)" to stderr and exits with kExitUsage.
[[noreturn]] void usageError(const char* program, const std::string& what);

/// `text` as a finite double in [min, max]; nullopt unless the whole text is one decimal
/// number (as strtod reads it, leading whitespace excepted). Rejected: "", " 1", "1e", "1x",
/// "nan", "inf", hexadecimal ("0x10", "0x1p3": a typo more often than intended) and values
/// that overflow. A value below the smallest subnormal rounds to zero as strtod rounds it.
std::optional<double> parseNumber(const char* text, double min, double max);

/// `text` as a base-10 integer in [min, max]; nullopt unless the whole text is one (optional
/// sign, then digits only: "1e3", "1.0", "0x10" and " 1" are rejected) and it fits.
std::optional<long long> parseInteger(const char* text, long long min, long long max);

/// Walks argv[1..argc). Typical loop:
///   ArgCursor args(argc, argv, "dss_tool", kUsage);
///   while (args.next()) {
///     if (args.option("--repeat")) repeat = int(args.integer(1, 1000));
///     else if (args.flag("--time")) time = true;
///     else if (args.positional("FILE")) file = args.value();
///     else args.unknown();
///   }
/// "--help" and "-h" print `usage` to stdout and exit 0. After "--" every argument is a
/// positional. "-" and arguments like "-5" are positionals, any other "-x" is an option.
class ArgCursor {
 public:
  ArgCursor(int argc, char** argv, const char* program, const char* usage);

  /// Moves to the next argument; false when none is left.
  bool next();
  /// The current argument is option `name` ("--name" or "--name=value"); its value is read
  /// with value(), number() or integer().
  bool option(std::string_view name);
  /// The current argument is flag `name`; "--name=value" is a usage error.
  bool flag(std::string_view name);
  /// The current argument is a positional; `label` names it in error messages.
  bool positional(const char* label = "argument");

  /// The value of the current option (attached, else the next argument: a usage error when
  /// there is none), or the current positional itself.
  const char* value();
  /// value() parsed by parseNumber / parseInteger; a usage error naming the option (or the
  /// positional's label), the accepted range and the text when it does not parse.
  double number(double min, double max);
  /// The value as exactly `count` finite numbers separated by commas ("1,2.5,-3").
  std::vector<double> numbers(std::size_t count);
  long long integer(long long min, long long max);

  /// Usage error for the current argument: "unknown option --x" or "unexpected argument 'x'".
  [[noreturn]] void unknown() const;
  /// usageError(program, what).
  [[noreturn]] void error(const std::string& what) const;

  /// The current option's name (without "=value"), or the positional's label.
  std::string_view name() const { return name_; }

 private:
  int argc_;
  char** argv_;
  const char* program_;
  const char* usage_;
  int index_ = 0;
  bool options_ended_ = false;  // "--" seen
  bool is_option_ = false;
  std::string_view name_;
  const char* value_ = nullptr;  // attached or already taken value of the current option
};

}  // namespace dss::cli
