#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "laguerre/core/Error.hpp"
#include "laguerre/sim/Network.hpp"

namespace laguerre::sim {
namespace {

TEST(NetworkTest, AdjacencyIsSortedDeduplicatedAndSymmetric) {
  const Edge edges[] = {{2, 0}, {0, 1}, {1, 0}, {0, 2}, {3, 1}};
  Network net(4, edges);
  EXPECT_EQ(net.node_count(), 4u);
  EXPECT_EQ(net.link_count(), 6u);
  const auto n0 = net.neighbours(0);
  EXPECT_EQ(std::vector<NodeIndex>(n0.begin(), n0.end()), (std::vector<NodeIndex>{1, 2}));
  const auto n1 = net.neighbours(1);
  EXPECT_EQ(std::vector<NodeIndex>(n1.begin(), n1.end()), (std::vector<NodeIndex>{0, 3}));
  for (LinkIndex l = 0; l < net.link_count(); ++l) {
    const auto back = net.find_link(net.link_target(l), net.link_source(l));
    ASSERT_TRUE(back.has_value());
    EXPECT_EQ(net.link_target(*back), net.link_source(l));
  }
  EXPECT_FALSE(net.find_link(2, 3).has_value());
  EXPECT_FALSE(net.find_link(9, 0).has_value());
  EXPECT_EQ(net.link_at(1, 1), *net.find_link(1, 3));
}

TEST(NetworkTest, RejectsBadEdgesIdsPositionsAndCrashes) {
  const Edge loop[] = {{1, 1}};
  EXPECT_THROW(Network(3, loop), laguerre::core::InternalError);
  const Edge outside[] = {{0, 3}};
  EXPECT_THROW(Network(3, outside), laguerre::core::InternalError);
  const Edge edges[] = {{0, 1}, {1, 2}};
  Network net(3, edges);
  EXPECT_THROW(net.set_ids({1, 2}), laguerre::core::InternalError);
  EXPECT_THROW(net.set_ids({5, 6, 5}), laguerre::core::InternalError);
  EXPECT_THROW(net.set_positions({{0, 0}}), laguerre::core::InternalError);
  EXPECT_THROW(net.set_positions({{0, 0}, {1, std::numeric_limits<double>::infinity()}, {2, 2}}),
               laguerre::core::InternalError);
  EXPECT_THROW(net.add_crash(3, 0), laguerre::core::InternalError);
  EXPECT_THROW(net.add_crash(0, -1), laguerre::core::InternalError);
  EXPECT_THROW(net.add_crash(0, 10, 10), laguerre::core::InternalError);
  EXPECT_THROW(net.set_link_model(0, 2, LinkModel{}), laguerre::core::InternalError);
}

TEST(NetworkTest, IdsMapBothWays) {
  const Edge edges[] = {{0, 1}};
  Network net(2, edges);
  EXPECT_EQ(net.id(1), 1u);
  EXPECT_EQ(net.index_of(1), NodeIndex{1});
  EXPECT_FALSE(net.index_of(2).has_value());
  net.set_ids({100, 7});
  EXPECT_EQ(net.id(0), 100u);
  EXPECT_EQ(net.index_of(7), NodeIndex{1});
  EXPECT_FALSE(net.index_of(1).has_value());
  EXPECT_FALSE(net.index_of(8).has_value());
  net.set_ids({0, 1});  // the identity again (stored as no table)
  EXPECT_EQ(net.id(0), 0u);
  EXPECT_EQ(net.index_of(1), NodeIndex{1});
  EXPECT_FALSE(net.index_of(7).has_value());
}

TEST(NetworkTest, PerLinkModelsOverrideTheDefault) {
  const Edge edges[] = {{0, 1}};
  Network net(2, edges);
  net.set_link_model(LinkModel{LatencyModel::constant(5), 0.1, 0});
  net.set_link_model(0, 1, LinkModel{LatencyModel::constant(9), 0, 0});
  EXPECT_EQ(net.link_model(*net.find_link(0, 1)).latency.base, 9);
  EXPECT_EQ(net.link_model(*net.find_link(1, 0)).latency.base, 5);
  EXPECT_DOUBLE_EQ(net.link_model(*net.find_link(1, 0)).loss, 0.1);
}

}  // namespace
}  // namespace laguerre::sim
