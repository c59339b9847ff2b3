// The enum name tables (EnumNames.hpp, PackingNames.hpp): every value has one name, names parse back,
// and an unknown name is an InputError listing the accepted ones.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "laguerre/core/Error.hpp"
#include "laguerre/core/packing/PackingNames.hpp"

using namespace laguerre::core;

namespace {
template <class E, std::size_t N>
void expect_round_trip(const EnumNames<E, N>& table) {
  std::set<std::string> seen;
  for (const auto& e : table) {
    EXPECT_TRUE(seen.insert(std::string(e.name)).second) << e.name << " twice";
    EXPECT_EQ(name_of(table, e.value), e.name);
    EXPECT_EQ(parse_name(table, e.name), e.value);
  }
  EXPECT_EQ(names_of(table).size(), N);
  EXPECT_FALSE(find_name(table, "no-such-name").has_value());
}
}  // namespace

TEST(PackingNames, EveryTableRoundTrips) {
  expect_round_trip(acceleration_names);
  expect_round_trip(stop_rule_names);
  expect_round_trip(sweep_names);
  expect_round_trip(root_rule_names);
  for (const auto& e : acceleration_names) EXPECT_EQ(to_string(e.value), e.name);
  for (const auto& e : stop_rule_names) EXPECT_EQ(parse_stop_rule(e.name), e.value);
}

TEST(PackingNames, UnknownNamesListTheAcceptedOnes) {
  try {
    (void)parse_name(sweep_names, "gauss_seidel", "--sweep");
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), "--sweep");
    EXPECT_EQ(std::string(e.what()), "--sweep: found 'gauss_seidel', expected jacobi or gauss-seidel");
  }
  try {
    (void)parse_acceleration("warp");
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "found 'warp', expected plain, superstep, anderson, newton, chebyshev, local-superstep or newton-krylov");
  }
  EXPECT_EQ(listed_names(root_rule_names), "deepest or smallest-id");
}
