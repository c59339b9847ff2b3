// `laguerre live` as a user runs it: on the bundled 3-connected network, 2 processes over UDP on
// 127.0.0.1 give `laguerre simulate`'s result (same iterations, rounds and delivery, and --verify says
// bit for bit); the JSON has the simulate keys plus the live section; the quick-start scenario's network
// verifies on 4 processes; a port in use and a bad
// --processes are bad input (exit status 2) with a message naming them.

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <string>

#include "../../support/BusyUdpPort.hpp"
#include "CliRunner.hpp"

namespace {
using laguerre::cli_test::Outcome;
using laguerre::cli_test::run;
using laguerre::cli_test::run_json;

const std::string graph3 = std::string(LAGUERRE_SOURCE_DIR) + "/scenarios/graphs/three-connected-60.txt";
}  // namespace

TEST(CliLive, TwoProcessesGiveTheSimulatorsResultBitForBit) {
  const nlohmann::json sim = run_json("simulate " + graph3 + " --pairs 300 --verify --json");
  const nlohmann::json live = run_json("live " + graph3 + " --processes 2 --pairs 300 --verify --timeout 30 --json");
  ASSERT_TRUE(live.is_object());
  EXPECT_EQ(live["verify"], "identical to core::pack, bit for bit");
  for (const char* key : {"iterations", "rounds", "converged_nodes", "packets", "delivered", "hops_mean", "nodes", "kind"})
    EXPECT_EQ(live[key], sim[key]) << key;
  EXPECT_EQ(live["live"]["processes"], 2);
  ASSERT_EQ(live["live"]["workers"].size(), 2u);
  EXPECT_EQ(live["live"]["workers"][1]["first_node"], 30);
  EXPECT_EQ(live["live"]["workers"][1]["nodes"], 30);
  EXPECT_GT(live["live"]["datagrams"].get<std::uint64_t>(), 0u);
}

TEST(CliLive, MetisPartitionGivesTheSameResult) {
  const nlohmann::json sim = run_json("simulate " + graph3 + " --pairs 100 --json");
  const nlohmann::json live =
      run_json("live " + graph3 + " --processes 3 --partition metis --pairs 100 --verify --timeout 30 --json");
  ASSERT_TRUE(live.is_object());
  EXPECT_EQ(live["verify"], "identical to core::pack, bit for bit");
  for (const char* key : {"iterations", "rounds", "converged_nodes", "delivered", "hops_mean"}) EXPECT_EQ(live[key], sim[key]) << key;
  std::uint64_t nodes = 0;
  for (const auto& w : live["live"]["workers"]) nodes += w["nodes"].get<std::uint64_t>();
  EXPECT_EQ(nodes, 60u);
  EXPECT_EQ(run("live " + graph3 + " --partition halves").status, 2);
}

TEST(CliLive, TextSummaryHasSimulatesLinesAndTheLiveLine) {
  const Outcome r = run("live " + graph3 + " --processes 2 --pairs 50 --loss 0.1 --retransmit-after 1ms --verify --timeout 30");
  EXPECT_EQ(r.status, 0) << r.out;
  for (const char* line : {"protocol     converged", "reliability  ", "verify       identical to core::pack, bit for bit",
                           "forwarding   greedy_power  50/50", "live         2 process(es) on 127.0.0.1"})
    EXPECT_NE(r.out.find(line), std::string::npos) << line << "\n" << r.out;
}

TEST(CliLive, TheQuickStartScenarioOnFourProcessesVerifies) {
  const Outcome r = run("live " + std::string(LAGUERRE_SOURCE_DIR) + "/scenarios/quickstart.yaml --processes 4 --verify --timeout 30");
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("delaunay(n=60): 60 nodes"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("verify       identical to core::pack, bit for bit"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("live         4 process(es)"), std::string::npos) << r.out;
}

TEST(CliLive, APortInUseAndBadProcessCountsAreBadInput) {
  {
    const laguerre::testing::BusyUdpPort held;
    const std::string port = std::to_string(held.port());
    const Outcome busy = run("live " + graph3 + " --base-port " + port + " --timeout 10");
    EXPECT_EQ(busy.status, 2) << busy.out;
    EXPECT_NE(busy.out.find("127.0.0.1:" + port + " is in use"), std::string::npos) << busy.out;
  }
  const Outcome many = run("live " + graph3 + " --processes 100 --timeout 10");
  EXPECT_EQ(many.status, 2) << many.out;
  EXPECT_NE(many.out.find("--processes"), std::string::npos) << many.out;
}
