#include "Common.hpp"

#include <filesystem>
#include <stdexcept>

namespace laguerre::tools {

LoadedGraph load_graph(const std::string& path, const std::string& format, std::size_t index) {
  auto graphs = core::read_graphs(path, core::parse_graph_format(format));
  if (index < 1 || index > graphs.size())
    throw std::invalid_argument("Graph index " + std::to_string(index) + " is out of range: " + path + " holds " +
                                std::to_string(graphs.size()) + " graph(s).");
  LoadedGraph out{std::move(graphs[index - 1]), {}};
  out.input.graph = core::prepare_for_packing(out.input, &out.kind);
  return out;
}

void check_writable(const std::string& path, bool force) {
  if (!force && std::filesystem::exists(path))
    throw std::invalid_argument("Refusing to overwrite " + path + "; pass --force to replace it or -o to write elsewhere.");
}

std::string file_stem(const std::string& path) { return std::filesystem::path(path).stem().string(); }

}  // namespace laguerre::tools
