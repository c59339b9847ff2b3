#include <gtest/gtest.h>

#include "laguerre/core/routing/Routing.hpp"

using namespace laguerre::core;

TEST(Routing, SchemeNamesRoundTrip) {
  for (const Scheme s : all_schemes) EXPECT_EQ(parse_scheme(to_string(s)), s);
  EXPECT_FALSE(parse_scheme("greedy").has_value());
}
