#pragma once
/// @file
/// The three tiers of errors (DESIGN.md, "Errors in three tiers"):
///  1. **Bad input** (a file, a string, a command-line value, a scenario key): a typed exception
///     derived from `InputError`, whose `what()` is a full sentence prefixed by where the problem is.
///     The CLI catches `InputError` once and exits with status 2.
///  2. **Programmer errors** (a broken precondition or invariant inside laguerre): `LAGUERRE_ASSERT`
///     and `LAGUERRE_PRECONDITION`, which throw `InternalError` (exit status 1 in the CLI), in every
///     build type: they guard cheap conditions only.
///  3. **Outcomes a caller must expect** (not converged, dead end, precision loss): `enum class`
///     results, never exceptions.

#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>

namespace laguerre::core {

/// Bad input, tier 1. `what()` is
///  - `"<source>:<line>: <message>"` when a line is known (text formats),
///  - `"<source>: <message>"` when only the source is known (a file, `--option`, `key.path`),
///  - `"<message>"` when neither is.
class InputError : public std::runtime_error {
public:
  /// An error at `line` (one-based, 0 if not applicable) of `source` (a file name, an option such as
  /// `--latency`, a key such as `network.loss`, or empty).
  InputError(std::string source, std::size_t line, std::string message)
      : std::runtime_error(compose(source, line, message)),  // before the members move from the arguments
        source_(std::move(source)), message_(std::move(message)), line_(line) {}
  /// An error with no known location.
  explicit InputError(std::string message) : InputError(std::string(), 0, std::move(message)) {}

  /// File name, option, key, or empty.
  const std::string& source() const noexcept { return source_; }
  /// One-based line number, or 0 if not applicable.
  std::size_t line() const noexcept { return line_; }
  /// The message without the location prefix.
  const std::string& message() const noexcept { return message_; }

protected:
  /// For derived errors whose `what()` adds to the location (e.g. a graph index): the full text.
  InputError(std::string what, std::string source, std::size_t line, std::string message)
      : std::runtime_error(std::move(what)), source_(std::move(source)), message_(std::move(message)), line_(line) {}

  /// `"<source>:<line>: <message>"`, without the parts that are empty or 0.
  static std::string compose(const std::string& source, std::size_t line, const std::string& message) {
    std::string where = source;
    if (line > 0) where += ":" + std::to_string(line);
    return where.empty() ? message : where + ": " + message;
  }

private:
  std::string source_;
  std::string message_;
  std::size_t line_ = 0;
};

/// A broken precondition or invariant inside laguerre (tier 2): a bug, not bad input.
class InternalError : public std::logic_error {
public:
  using std::logic_error::logic_error;
};

namespace detail {
[[noreturn]] inline void assertion_failed(const char* kind, const char* condition, const char* file, int line,
                                          const std::string& message) {
  std::string text = std::string(kind) + " failed: " + condition + " (" + file + ":" + std::to_string(line) + ")";
  if (!message.empty()) text += ": " + message;
  throw InternalError(text);
}
}  // namespace detail

}  // namespace laguerre::core

/// Tier 2: an invariant of laguerre's own code. Throws core::InternalError naming the condition.
#define LAGUERRE_ASSERT(condition)                                                                    \
  do {                                                                                                \
    if (!(condition)) ::laguerre::core::detail::assertion_failed("assertion", #condition, __FILE__, __LINE__, {}); \
  } while (false)

/// Tier 2: what a caller of a function must guarantee (documented in its header). Throws
/// core::InternalError naming the condition and `message`.
#define LAGUERRE_PRECONDITION(condition, message)                                                     \
  do {                                                                                                \
    if (!(condition))                                                                                 \
      ::laguerre::core::detail::assertion_failed("precondition", #condition, __FILE__, __LINE__, message); \
  } while (false)
