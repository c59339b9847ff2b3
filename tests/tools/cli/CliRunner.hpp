#pragma once
/// @file
/// Shared by the CLI tests: run the `laguerre` program as a user would and collect what it prints, and
/// a scratch folder per test.

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace laguerre::cli_test {

/// What a run of the program gave.
struct Outcome {
  int status = -1;  ///< exit status, -1 if it did not exit normally
  std::string out;  ///< standard output, and standard error when asked for
};

/// Runs `laguerre ARGS` through the shell; `with_stderr` merges standard error into `out`.
inline Outcome run(const std::string& args, bool with_stderr = true) {
  const std::string cmd = std::string(LAGUERRE_EXE) + " " + args + (with_stderr ? " 2>&1" : " 2>/dev/null");
  Outcome r;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf{};
  std::size_t got;
  while ((got = std::fread(buf.data(), 1, buf.size(), p)) > 0) r.out.append(buf.data(), got);
  const int st = pclose(p);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return r;
}

/// Runs `laguerre ARGS` (standard output only), expects exit status `status` and parses the JSON
/// it printed (null, and a failure, if it does not parse).
inline nlohmann::json run_json(const std::string& args, int status = 0) {
  const Outcome r = run(args, false);
  EXPECT_EQ(r.status, status) << args << "\n" << r.out;
  const auto doc = nlohmann::json::parse(r.out, nullptr, false);
  if (doc.is_discarded()) ADD_FAILURE() << args << ": no JSON on standard output:\n" << r.out;
  return doc.is_discarded() ? nlohmann::json() : doc;
}

/// Runs `laguerre ARGS` and expects exit status 2 (bad input) with each of `needles` in the output.
inline void expect_bad_input(const std::string& args, std::initializer_list<const char*> needles) {
  const Outcome r = run(args);
  EXPECT_EQ(r.status, 2) << args << "\n" << r.out;
  for (const char* n : needles) EXPECT_NE(r.out.find(n), std::string::npos) << args << "\n" << r.out;
}

/// A fixture with a fresh scratch folder per test, removed afterwards.
class ScratchDir : public ::testing::Test {
protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() /
           ("laguerre-cli-" + std::to_string(::getpid()) + "-" + info->test_suite_name() + "-" + info->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  /// A path inside the scratch folder.
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  /// Writes `text` to a file of the scratch folder and returns its path.
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(path(name)) << text;
    return path(name);
  }
  std::filesystem::path dir_;  ///< the scratch folder
};

}  // namespace laguerre::cli_test
