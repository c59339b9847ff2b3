#pragma once
// What the graph reader tests share: bundled files, reading one graph, catching the input error.
#include <gtest/gtest.h>

#include <cstddef>
#include <string>
#include <string_view>
#include <utility>

#include "laguerre/core/graph/GraphIO.hpp"

namespace laguerre::core::test {

/// A file of tests/data/graphs.
inline std::string data_path(const std::string& name) { return std::string(LAGUERRE_TEST_DATA) + "/graphs/" + name; }

/// The one graph of `text` (a test failure if there are more), named "<input>".
inline GraphInput read_one(std::string_view text, GraphFormat format = GraphFormat::automatic) {
  auto graphs = read_graphs_from_string(text, "<input>", format);
  EXPECT_EQ(graphs.size(), 1u);
  return std::move(graphs.at(0));
}

/// Runs `f`, expects a GraphInputError and returns it.
template <class F>
GraphInputError expect_input_error(F&& f) {
  try {
    f();
  } catch (const GraphInputError& e) {
    return e;
  }
  ADD_FAILURE() << "no GraphInputError was thrown";
  return GraphInputError("<none>", 0, 0, "");
}

/// The what() of the GraphInputError that reading `text` (named "<input>") throws, "" if none; its line
/// goes to `line` if given.
inline std::string read_error(std::string_view text, std::size_t* line = nullptr,
                              GraphFormat format = GraphFormat::automatic) {
  try {
    read_graphs_from_string(text, "<input>", format);
  } catch (const GraphInputError& e) {
    if (line) *line = e.line();
    return e.what();
  }
  return "";
}

}  // namespace laguerre::core::test
