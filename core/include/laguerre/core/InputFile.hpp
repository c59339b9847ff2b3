#pragma once
/// @file
/// Opening a file the user named: the one place that tells a missing file, a directory and an
/// unreadable file apart, so every reader and command reports them the same way.

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <string_view>
#include <system_error>

#include "laguerre/core/Error.hpp"

namespace laguerre::core {

/// Opens `path` for reading in binary mode. `what` names what the file should hold ("graph file",
/// "sites file", "scenario file") and starts the message. Throws InputError, with `path` as the
/// source, if the file does not exist, is a directory (or anything but a regular file), or cannot be
/// read.
inline std::ifstream open_input_file(const std::string& path, std::string_view what) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status))
    throw InputError(path, 0, "no such " + std::string(what) + " (the file does not exist).");
  if (std::filesystem::is_directory(status))
    throw InputError(path, 0, "is a directory; expected a " + std::string(what) + ".");
  if (!std::filesystem::is_regular_file(status))
    throw InputError(path, 0, "is not a regular file; expected a " + std::string(what) + ".");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "cannot read this " + std::string(what) + " (permission denied?).");
  return in;
}

/// The whole content of `path`, opened as by open_input_file.
inline std::string read_input_file(const std::string& path, std::string_view what) {
  std::ifstream in = open_input_file(path, what);
  std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw InputError(path, 0, "read error in this " + std::string(what) + ".");
  return text;
}

}  // namespace laguerre::core
