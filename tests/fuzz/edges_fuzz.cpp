// Fuzz harness: the edges graph format (core/graph/GraphIO.hpp), read and round-tripped.
#include "GraphHarness.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return laguerre::fuzz::fuzz_graph_format(data, size, laguerre::core::GraphFormat::edges);
}
