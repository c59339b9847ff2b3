// `laguerre simulate --scheme`: hop-by-hop forwarding of every scheme over the simulated network gives
// the figures of the centralized `laguerre route` on the same positions and pairs (delivered, hop
// stretch), one JSON entry and one text line per scheme; bad scheme names are refused.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "CliRunner.hpp"

#include <array>
#include <cstdio>
#include <string>
#include <sys/wait.h>

namespace {
using laguerre::cli_test::Outcome;
using laguerre::cli_test::run;

const std::string graph3 = std::string(LAGUERRE_SOURCE_DIR) + "/scenarios/graphs/three-connected-60.txt";
const std::string graph_tri = std::string(LAGUERRE_SOURCE_DIR) + "/scenarios/graphs/delaunay-60.txt";

const nlohmann::json& by_scheme(const nlohmann::json& list, const std::string& name) {
  for (const auto& e : list)
    if (e["scheme"] == name) return e;
  static const nlohmann::json none;
  ADD_FAILURE() << "no entry for " << name;
  return none;
}
}  // namespace

TEST(CliSimulateSchemes, HopByHopEqualsTheCentralizedRouter) {
  const Outcome sim = run("simulate " + graph3 + " --scheme all --pairs 400 --seed 5 --latency uniform:1ms:3ms --json");
  ASSERT_EQ(sim.status, 0) << sim.out;
  const auto doc = nlohmann::json::parse(sim.out);
  ASSERT_EQ(doc["forwarding"].size(), 4u);
  EXPECT_EQ(doc["forwarding_positions"], "input coordinates");
  // The geometric schemes route on the file's coordinates, greedy power on the packing's circles.
  const Outcome geo = run("route " + graph3 + " --positions input --pairs 400 --seed 5 --json");
  const Outcome lay = run("route " + graph3 + " --pairs 400 --seed 5 --json");
  ASSERT_EQ(geo.status, 0) << geo.out;
  ASSERT_EQ(lay.status, 0) << lay.out;
  const auto jgeo = nlohmann::json::parse(geo.out)["schemes"], jlay = nlohmann::json::parse(lay.out)["schemes"];
  std::size_t packets = 0, delivered = 0, failures = 0;
  for (const char* s : {"greedy_power", "greedy_euclid", "compass", "gfg"}) {
    SCOPED_TRACE(s);
    const auto& hop = by_scheme(doc["forwarding"], s);
    const auto& core = by_scheme(std::string(s) == "greedy_power" ? jlay : jgeo, s);
    EXPECT_EQ(hop["packets"], 400);
    EXPECT_EQ(hop["delivered"], core["delivered"]);
    EXPECT_EQ(hop["delivered"].get<int>() + hop["dead_ends"].get<int>() + hop["loops"].get<int>() +
                  hop["ttl_exceeded"].get<int>(),
              400);
    EXPECT_DOUBLE_EQ(hop["hops_mean"].get<double>(), core["hops_mean"].get<double>());
    // Same ratios summed in another order (packets end in simulated-time order).
    EXPECT_NEAR(hop["stretch_mean"].get<double>(), core["stretch_mean"].get<double>(), 1e-12);
    EXPECT_DOUBLE_EQ(hop["stretch_p95"].get<double>(), core["stretch_p95"].get<double>());
    EXPECT_DOUBLE_EQ(hop["stretch_max"].get<double>(), core["stretch_max"].get<double>());
    EXPECT_GE(hop["stretch_mean"].get<double>(), 1.0);
    packets += hop["packets"].get<std::size_t>();
    delivered += hop["delivered"].get<std::size_t>();
    failures += 400 - hop["delivered"].get<std::size_t>();
  }
  EXPECT_EQ(doc["packets"], packets);
  EXPECT_EQ(doc["delivered"], delivered);
  EXPECT_GT(failures, 0u) << "greedy Euclidean and compass fail on this sparse drawing";
  EXPECT_EQ(by_scheme(doc["forwarding"], "gfg")["delivered"], 400) << "GFG delivers on a plane drawing";
}

TEST(CliSimulateSchemes, OneLinePerSchemeAndTheDefaultIsGreedyPower) {
  const Outcome all = run("simulate " + graph_tri + " --scheme all --pairs 50");
  ASSERT_EQ(all.status, 0) << all.out;
  for (const char* s : {"greedy_power ", "greedy_euclid", "compass ", "gfg "})
    EXPECT_NE(all.out.find(std::string("forwarding   ") + s), std::string::npos) << all.out;
  const Outcome one = run("simulate " + graph_tri + " --pairs 50 --json");
  ASSERT_EQ(one.status, 0) << one.out;
  const auto doc = nlohmann::json::parse(one.out);
  ASSERT_EQ(doc["forwarding"].size(), 1u);
  EXPECT_EQ(doc["forwarding"][0]["scheme"], "greedy_power");
  const Outcome dash = run("simulate " + graph_tri + " --scheme greedy-euclid --pairs 50 --json");
  ASSERT_EQ(dash.status, 0) << dash.out;
  EXPECT_EQ(nlohmann::json::parse(dash.out)["forwarding"][0]["scheme"], "greedy_euclid");
  laguerre::cli_test::expect_bad_input("simulate " + graph_tri + " --scheme greedy", {"--scheme"});
}

// The hyperbolic baseline is asked for by name: `route` evaluates it (every pair delivered on a
// connected graph), `all` leaves it out, and the per-node forwarding of `simulate` refuses it up front.
TEST(CliSimulateSchemes, HyperbolicBaselineIsRoutedCentrallyOnly) {
  const auto doc = laguerre::cli_test::run_json("route " + graph3 + " --scheme hyperbolic --json");
  ASSERT_EQ(doc["schemes"].size(), 1u);
  EXPECT_EQ(doc["schemes"][0]["scheme"], "hyperbolic");
  EXPECT_EQ(doc["schemes"][0]["pairs"], 60 * 59);
  EXPECT_EQ(doc["schemes"][0]["delivered"], 60 * 59);
  EXPECT_EQ(laguerre::cli_test::run_json("route " + graph3 + " --scheme all --pairs 10 --json")["schemes"].size(), 4u);
  laguerre::cli_test::expect_bad_input("simulate " + graph3 + " --scheme hyperbolic --pairs 5", {"--scheme", "hyperbolic"});
}

TEST(CliSimulateSchemes, CrashWithRecovery) {
  // A 20 ms outage is masked by the reliability layer: the run converges, bit for bit.
  const auto a = laguerre::cli_test::run_json("simulate " + graph_tri + " --crash 17@100ms-120ms --verify --pairs 5 --json");
  EXPECT_EQ(a["converged_nodes"], 60);
  EXPECT_EQ(a["verify"], "identical to core::pack, bit for bit");
  ASSERT_EQ(a["outages"].size(), 1u);
  EXPECT_EQ(a["outages"][0]["outcome"], "converged");
  EXPECT_DOUBLE_EQ(a["outages"][0]["recover_seconds"].get<double>(), 0.12);
  // Back after 3 s: the crash was detected; every node, the recovered one included, ends final.
  const Outcome late = run("simulate " + graph_tri + " --crash 17@100ms --recover 17@3s --pairs 5 --json");
  EXPECT_EQ(late.status, 3) << late.out;
  const auto b = nlohmann::json::parse(late.out);
  EXPECT_EQ(b["survivors"], 60);
  EXPECT_EQ(b["failed_nodes"], 60);
  EXPECT_GE(b["suspects"]["17"].get<int>(), 59);
  EXPECT_EQ(b["outages"][0]["outcome"], "neighbour_failed");
  EXPECT_EQ(b["outages"][0]["final"], true);
  EXPECT_GT(b["finished_seconds"].get<double>(), 3.0);
  // Bad recoveries are refused with the option named.
  for (const char* bad : {"--recover 17@3s", "--crash 17@100ms --recover 17@50ms"})
    laguerre::cli_test::expect_bad_input("simulate " + graph_tri + " " + bad, {"--recover"});
  laguerre::cli_test::expect_bad_input("simulate " + graph_tri + " --crash 17@100ms-50ms", {"--crash"});
}
