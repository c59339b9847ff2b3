#pragma once
/// @file
/// What the harnesses of tests/fuzz share. A harness defines `LLVMFuzzerTestOneInput`, feeds the bytes
/// to one parser, ignores the parser's documented bad-input exceptions and checks what it can on
/// success. Anything else is a finding: `fail` prints it and aborts, which libFuzzer and the standalone
/// driver (StandaloneFuzzMain.cpp) both record with the input.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <string_view>
#include <typeinfo>

/// The entry point every harness defines (libFuzzer's interface).
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace laguerre::fuzz {

/// The input as text (bytes unchanged).
inline std::string_view as_text(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

/// A finding: prints `what` and aborts.
[[noreturn]] inline void fail(const std::string& what) {
  std::fprintf(stderr, "fuzz finding: %s\n", what.c_str());
  std::fflush(stderr);
  std::abort();
}

/// Runs `parse`. Returns true if it returned, false if it threw one of `Expected...` (bad input); any
/// other exception is a finding.
template <class... Expected, class F>
bool parses(F&& parse) {
  try {
    parse();
    return true;
  } catch (const std::exception& e) {
    if ((... || (dynamic_cast<const Expected*>(&e) != nullptr))) return false;
    fail(std::string("unexpected exception ") + typeid(e).name() + ": " + e.what());
  } catch (...) {
    fail("unexpected exception of a type not derived from std::exception");
  }
}

}  // namespace laguerre::fuzz

/// A property a harness checks on a successful parse; a finding when false.
#define LAGUERRE_FUZZ_CHECK(condition)                                                                  \
  do {                                                                                                  \
    if (!(condition))                                                                                   \
      ::laguerre::fuzz::fail(std::string("check failed: ") + #condition + " (" + __FILE__ + ":" +       \
                             std::to_string(__LINE__) + ")");                                           \
  } while (false)
