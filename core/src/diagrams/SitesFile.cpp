#include "laguerre/core/diagrams/SitesFile.hpp"

#include <charconv>
#include <cmath>
#include <sstream>

#include "laguerre/core/InputFile.hpp"

namespace laguerre::core {

std::vector<InputLine> read_input_lines(const std::string& path, std::string_view what) {
  std::ifstream in = open_input_file(path, what);
  std::vector<InputLine> lines;
  std::string text;
  for (std::size_t number = 1; std::getline(in, text); ++number) {
    if (const auto hash = text.find('#'); hash != std::string::npos) text.erase(hash);
    std::istringstream fields(text);
    InputLine line{number, {}};
    for (std::string w; fields >> w;) line.words.push_back(std::move(w));
    if (!line.words.empty()) lines.push_back(std::move(line));
  }
  if (in.bad()) throw InputError(path, 0, "read error in this " + std::string(what) + ".");
  return lines;
}

namespace {

std::vector<std::string> split_columns(std::string_view columns) {
  std::istringstream in{std::string(columns)};
  std::vector<std::string> names;
  for (std::string w; in >> w;) names.push_back(w);
  return names;
}

std::string joined(const std::vector<std::string>& words) {
  std::string out;
  for (const std::string& w : words) out += (out.empty() ? "" : " ") + w;
  return out;
}

}  // namespace

std::vector<SiteRow> read_site_rows(const std::string& path, std::string_view columns, std::string_view kind) {
  const std::vector<std::string> names = split_columns(columns);
  const std::string format = "`" + std::string(columns) + "`";
  std::vector<SiteRow> rows;
  for (const InputLine& line : read_input_lines(path, "sites file")) {
    if (line.words.size() != names.size())
      throw InputError(path, line.number,
                       "found " + std::to_string(line.words.size()) + " field(s) '" + joined(line.words) + "'; expected " +
                           std::to_string(names.size()) + " numbers " + format + " (" + std::string(kind) + " sites).");
    SiteRow row{line.number, {}};
    for (std::size_t k = 0; k < names.size(); ++k) {
      const std::string& w = line.words[k];
      double v = 0;
      const char* first = w.data() + (w.size() > 1 && w[0] == '+' ? 1 : 0);
      const auto [ptr, ec] = std::from_chars(first, w.data() + w.size(), v);
      const std::string found = "found '" + w + "' in column " + std::to_string(k + 1) + " `" + names[k] + "`; ";
      if (ec == std::errc::result_out_of_range ||
          (ec == std::errc() && ptr == w.data() + w.size() && std::isfinite(v) && !admissible_magnitude(v)))
        throw InputError(path, line.number,
                         found + "expected 0 or a magnitude between 1e-150 and 1e150, so that squares and products of "
                                 "two numbers are finite, normal doubles (" + std::string(kind) + " sites).");
      if (ec != std::errc() || ptr != w.data() + w.size() || !std::isfinite(v))
        throw InputError(path, line.number, found + "expected a finite number (" + std::string(kind) + " sites).");
      row.values.push_back(v);
    }
    rows.push_back(std::move(row));
  }
  if (rows.empty()) throw InputError(path, 0, "no sites; expected lines " + format + " (" + std::string(kind) + " sites).");
  return rows;
}

}  // namespace laguerre::core
