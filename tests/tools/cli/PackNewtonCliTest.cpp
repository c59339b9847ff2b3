// `laguerre pack --accelerate newton --newton-solver …`: every solver reaches LPD on the same graph,
// the JSON names the solver, a cap ends with a clean status, and a bad name is exit status 2.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "CliRunner.hpp"

#include <fstream>
#include <string>

namespace {
using laguerre::cli_test::Outcome;
using laguerre::cli_test::run;

class PackNewtonCli : public laguerre::cli_test::ScratchDir {};

const std::string example = std::string(LAGUERRE_SOURCE_DIR) + "/scenarios/graphs/delaunay-60.txt";
}  // namespace

TEST_F(PackNewtonCli, EverySolverReachesLpdAndIsNamed) {
  for (const char* solver : {"lu", "cholesky", "pcg"}) {
    const std::string stem = path(std::string("p-") + solver);
    const Outcome r = run("pack " + example + " --accelerate newton --newton-solver " + solver + " --no-picture -o " + stem);
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find("linear solver " + std::string(solver)), std::string::npos) << r.out;
    std::ifstream in(stem + ".json");
    const nlohmann::json doc = nlohmann::json::parse(in);
    EXPECT_EQ(doc["packing"]["status"], "converged");
    EXPECT_EQ(doc["packing"]["newton_solver"], solver);
    EXPECT_EQ(doc["packing"]["local_ok"], 60);
    EXPECT_GE(doc["packing"]["cpu_seconds"].get<double>(), 0.0);
  }
}

TEST_F(PackNewtonCli, CapEndsWithAStatusAndBadSolverIsAnInputError) {
  const Outcome capped = run("pack " + example + " --max-iterations 1 --no-picture -o " + path("capped"));
  EXPECT_EQ(capped.status, 3) << capped.out;
  EXPECT_NE(capped.out.find("iteration_cap"), std::string::npos) << capped.out;
  EXPECT_NE(capped.out.find("--max-iterations 1 reached before the stop rule held"), std::string::npos) << capped.out;
  const Outcome bad = run("pack " + example + " --accelerate newton --newton-solver qr --no-picture -o " + path("bad"));
  EXPECT_EQ(bad.status, 2) << bad.out;
  EXPECT_NE(bad.out.find("--newton-solver"), std::string::npos) << bad.out;
}

TEST_F(PackNewtonCli, PrecisionStatusNamesTheLayoutAndBadLayoutIsAnInputError) {
  // docs/precision.md: both layouts of the 60-vertex example carry every circle, and say so.
  for (const char* layout : {"frames", "wave"}) {
    const std::string stem = path(std::string("l-") + layout);
    const Outcome r = run("pack " + example + " --accelerate newton --layout " + layout + " --no-picture -o " + stem);
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find("decisions exact on representable coordinates"), std::string::npos) << r.out;
    std::ifstream in(stem + ".json");
    const nlohmann::json p = nlohmann::json::parse(in)["packing"]["precision"];
    EXPECT_EQ(p["status"], "ok");
    EXPECT_EQ(p["exact_decisions"], true);
    EXPECT_EQ(p["layout"], layout);
    EXPECT_EQ(p["arithmetic"], "binary64");
    EXPECT_EQ(p["bytes_per_coordinate"], 8);
    EXPECT_EQ(p["significand_bits_needed"], 53);
    EXPECT_GE(p["resolution"].get<double>(), 1 << 20);
  }
  const Outcome bad = run("pack " + example + " --layout spiral --no-picture -o " + path("bad"));
  EXPECT_EQ(bad.status, 2) << bad.out;
  EXPECT_NE(bad.out.find("--layout"), std::string::npos) << bad.out;
}

TEST_F(PackNewtonCli, TimeLimitEndsWithItsStatusAndThePhasesAreWritten) {
  const std::string stem = path("timed");
  const Outcome r = run("pack " + example + " --time-limit 0.000000001 --no-picture -o " + stem);
  EXPECT_EQ(r.status, 3) << r.out;
  EXPECT_NE(r.out.find("time_limit"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("--time-limit 1e-09 s reached before the stop rule held"), std::string::npos) << r.out;
  std::ifstream in(stem + ".json");
  const nlohmann::json p = nlohmann::json::parse(in)["packing"];
  EXPECT_EQ(p["status"], "time_limit");
  EXPECT_EQ(p["iterations"], 1);
  EXPECT_EQ(p["time_limit"].get<double>(), 1e-9);
  for (const char* phase : {"setup", "sweeps", "jacobian", "solve", "line_search", "layout", "checks", "final"})
    EXPECT_GE(p["phase_seconds"][phase].get<double>(), 0.0) << phase;
  const Outcome newton = run("pack " + example + " --accelerate newton --no-picture -o " + path("phases"));
  ASSERT_EQ(newton.status, 0) << newton.out;
  std::ifstream in2(path("phases") + ".json");
  const nlohmann::json q = nlohmann::json::parse(in2)["packing"];
  EXPECT_GT(q["phase_seconds"]["solve"].get<double>(), 0.0);
  EXPECT_TRUE(q["time_limit"].is_null());
  const Outcome bad = run("pack " + example + " --time-limit -1 --no-picture -o " + path("bad"));
  EXPECT_EQ(bad.status, 2) << bad.out;
  EXPECT_NE(bad.out.find("--time-limit"), std::string::npos) << bad.out;
  const Outcome help = run("pack --help");
  EXPECT_NE(help.out.find("--time-limit"), std::string::npos);
  EXPECT_NE(help.out.find("time limit"), std::string::npos);
}

TEST_F(PackNewtonCli, PairsRouteGreedyPowerOnTheCoordinatesLpdWasDecidedOn) {
  // --pairs checks delivery after the pack, on the doubles or (binary128 layout) on the 16-byte
  // circles; the same sample on both arithmetics delivers everything (LPD holds on both here).
  for (const char* arithmetic : {"binary64", "binary128"}) {
    const std::string stem = path(std::string("r-") + arithmetic);
    const Outcome r = run("pack " + example + " --accelerate newton --layout-arithmetic " + arithmetic +
                          " --pairs 200 --seed 3 --no-picture -o " + stem);
    ASSERT_EQ(r.status, 0) << r.out;
    const int bytes = std::string(arithmetic) == "binary128" ? 16 : 8;
    EXPECT_NE(r.out.find("greedy power on the " + std::to_string(bytes) + "-byte coordinates: 200 / 200 sampled pairs"),
              std::string::npos)
        << r.out;
    std::ifstream in(stem + ".json");
    const nlohmann::json routing = nlohmann::json::parse(in)["routing"];
    EXPECT_EQ(routing["pairs"], 200);
    EXPECT_EQ(routing["delivered"], 200);
    EXPECT_EQ(routing["seed"], 3);
    EXPECT_EQ(routing["bytes_per_coordinate"], bytes);
    EXPECT_TRUE(routing["failures"].empty());
  }
  const Outcome none = run("pack " + example + " --no-picture -o " + path("no-routing"));
  ASSERT_EQ(none.status, 0) << none.out;
  std::ifstream in(path("no-routing") + ".json");
  EXPECT_FALSE(nlohmann::json::parse(in).contains("routing"));
  const Outcome bad = run("pack " + example + " --pairs 0 --no-picture -o " + path("bad-pairs"));
  EXPECT_EQ(bad.status, 2) << bad.out;
  EXPECT_NE(bad.out.find("--pairs"), std::string::npos) << bad.out;
}

TEST_F(PackNewtonCli, RadiusOnlyTerminationReachesLpdWithFewerLayouts) {
  const std::string every = path("t-layout"), gated = path("t-radius");
  const Outcome a = run("pack " + example + " --accelerate newton --no-picture -o " + every);
  const Outcome b = run("pack " + example + " --accelerate newton --termination radius-only --no-picture -o " + gated);
  ASSERT_EQ(a.status, 0) << a.out;
  ASSERT_EQ(b.status, 0) << b.out;
  EXPECT_NE(b.out.find("termination  radius-only: "), std::string::npos) << b.out;
  std::ifstream ia(every + ".json"), ib(gated + ".json");
  const nlohmann::json pa = nlohmann::json::parse(ia)["packing"], pb = nlohmann::json::parse(ib)["packing"];
  EXPECT_EQ(pb["termination"], "radius-only");
  EXPECT_EQ(pb["local_ok"], 60);
  EXPECT_LT(pb["layouts"].get<int>(), pa["layouts"].get<int>());
  const Outcome bad = run("pack " + example + " --termination radius-only --stop exact --no-picture -o " + path("t-bad"));
  EXPECT_EQ(bad.status, 2) << bad.out;
  EXPECT_NE(bad.out.find("--termination"), std::string::npos) << bad.out;
}
