#pragma once
/// @file
/// Scratch files for tests: one folder per test process under the system's temporary folder, removed
/// when the process ends, so that test cases run at the same time (`ctest -j`, several build trees
/// on one machine) never write the same file. ::testing::TempDir() alone is /tmp/, shared by all.

#include <unistd.h>

#include <filesystem>
#include <string>
#include <system_error>

namespace laguerre::testing {

/// This process's scratch folder (created on first use, removed with its contents at exit).
inline const std::filesystem::path& scratch_folder() {
  struct Folder {
    std::filesystem::path path =
        std::filesystem::temp_directory_path() / ("laguerre-test-" + std::to_string(::getpid()));
    Folder() { std::filesystem::create_directories(path); }
    ~Folder() {
      std::error_code ignored;
      std::filesystem::remove_all(path, ignored);
    }
  };
  static const Folder folder;
  return folder.path;
}

/// The path of the scratch file `name` (its folder exists; the file may not).
inline std::string scratch_path(const std::string& name) { return (scratch_folder() / name).string(); }

}  // namespace laguerre::testing
