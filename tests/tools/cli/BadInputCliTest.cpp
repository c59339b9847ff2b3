// Bad command-line input: every problem exits with status 2 and a message naming the option or the
// file, whether CLI11 or laguerre finds it (missing files, folders given as files, out-of-range
// numbers, seeds, pair counts, crash and latency specifications).
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "CliRunner.hpp"

namespace {
using laguerre::cli_test::Outcome;
using laguerre::cli_test::run;

class CliBadInput : public laguerre::cli_test::ScratchDir {};

const std::string graph = std::string(LAGUERRE_SOURCE_DIR) + "/scenarios/graphs/delaunay-60.txt";
const auto expect_bad = laguerre::cli_test::expect_bad_input;
}  // namespace

TEST_F(CliBadInput, PairsMustBeAllOrPositive) {
  expect_bad("simulate " + graph + " --pairs 0", {"--pairs", "'0'"});
  expect_bad("route " + graph + " --pairs 0", {"--pairs"});
  expect_bad("simulate " + graph + " --pairs -3", {"--pairs"});
}

TEST_F(CliBadInput, SeedMustFitIn64Bits) {
  for (const char* cmd : {"simulate ", "route "}) {
    expect_bad(cmd + graph + " --seed -1", {"--seed", "18446744073709551615"});
    expect_bad(cmd + graph + " --seed 99999999999999999999", {"--seed", "18446744073709551615"});
  }
  expect_bad("generate delaunay --seed -1", {"--seed"});
  expect_bad("thesis-table --count 1 --size 20 --seed x", {"--seed"});
  EXPECT_EQ(run("simulate " + graph + " --seed 18446744073709551615 --pairs 3").status, 0);
}

TEST_F(CliBadInput, StepsPerRoundZeroIsAClearError) {
  const Outcome r = run("simulate " + graph + " -N 0");
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("--steps-per-round: Value 0 not in range 1 to 10000"), std::string::npos) << r.out;
  EXPECT_LT(r.out.size(), 300u) << "a short message, not a 300-digit range: " << r.out;
  expect_bad("pack " + graph + " -N 0 --no-picture -o " + path("p"), {"--steps-per-check"});
  expect_bad("simulate " + graph + " --max-iterations 0", {"--max-iterations"});
}

TEST_F(CliBadInput, SimulateRefusesAccelerationsTheNetworkCannotRun) {
  for (const char* a : {"anderson", "superstep", "newton"})
    expect_bad("simulate " + graph + " --accelerate " + a, {"--accelerate", a, "chebyshev"});
  expect_bad("simulate " + graph + " --accelerate chebyshev --mode async", {"--accelerate", "--mode async"});
  expect_bad("simulate " + graph + " --accelerate newton-krylov --mode async",
             {"--accelerate", "newton-krylov", "--mode async", "consistent"});
  expect_bad("simulate " + graph + " --accelerate warp", {"--accelerate"});
  for (const char* a : {"chebyshev", "newton-krylov"}) {
    const Outcome r = run("simulate " + graph + " --accelerate " + a + " --verify --pairs 20");
    EXPECT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find("identical to core::pack, bit for bit"), std::string::npos) << a << ": " << r.out;
  }
}

TEST_F(CliBadInput, SimulateRadiusOnlyTermination) {
  expect_bad("simulate " + graph + " --termination radius-only --mode async", {"--termination", "--mode async"});
  expect_bad("simulate " + graph + " --termination soon", {"--termination"});
  const Outcome r = run("simulate " + graph + " --termination radius-only --verify --pairs 20");
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("identical to core::pack, bit for bit"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("termination  radius-only"), std::string::npos) << r.out;
}

TEST_F(CliBadInput, ParseErrorsExitWith2) {
  expect_bad("simulate " + graph + " --no-such-option", {"--no-such-option"});
  expect_bad("simulate", {"graph"});
  expect_bad("simulate " + graph + " --mode sometimes", {"--mode"});
  expect_bad("bogus-command", {"subcommand"});
  EXPECT_EQ(run("simulate --help").status, 0);
  EXPECT_EQ(run("--version").status, 0);
}

TEST_F(CliBadInput, MissingFilesAndFoldersAreNamed) {
  const std::string missing = path("nope.txt");
  for (const char* cmd : {"pack ", "simulate ", "route ", "thesis-table "}) {
    expect_bad(cmd + missing, {"nope.txt", "does not exist"});
    expect_bad(cmd + dir_.string(), {dir_.string().c_str(), "is a directory"});
  }
  for (const char* cmd : {"run ", "compare "}) {
    expect_bad(cmd + missing + " -o " + path("out"), {"nope.txt", "does not exist"});
    expect_bad(cmd + dir_.string() + " -o " + path("out"), {dir_.string().c_str(), "is a directory"});
  }
}

TEST_F(CliBadInput, CrashSpecifications) {
  const Outcome r = run("simulate " + graph + " --crash -1@1ms");
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("--crash"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("18446744073709551615"), std::string::npos) << r.out;
  expect_bad("simulate " + graph + " --crash 17@", {"--crash"});
  expect_bad("simulate " + graph + " --crash 17@1ms-", {"--crash"});
  expect_bad("simulate " + graph + " --recover 17x", {"--recover"});
  expect_bad("simulate " + graph + " --retransmit-after soon", {"--retransmit-after"});
}

TEST_F(CliBadInput, UniformLatencyNeedsLoBelowHi) {
  expect_bad("simulate " + graph + " --latency uniform:5ms:1ms", {"--latency", "LO <= HI"});
  EXPECT_EQ(run("simulate " + graph + " --latency uniform:1ms:1ms --pairs 3").status, 0);
}

TEST_F(CliBadInput, LossAndDuplicationAreProbabilities) {  // exited 1 ("error: ...") before issue 15
  expect_bad("simulate " + graph + " --loss 2", {"--loss", "not in range"});
  expect_bad("simulate " + graph + " --loss -0.1", {"--loss"});
  expect_bad("simulate " + graph + " --dup -1", {"--dup", "not in range"});
  expect_bad("simulate " + graph + " --dup 1.5", {"--dup"});
  EXPECT_EQ(run("simulate " + graph + " --loss 0 --dup 0 --pairs 3").status, 0);
}

TEST_F(CliBadInput, EmbeddingWithAnInvalidRotationSystemIsNamed) {
  // PlanarGraph::from_rotation reports bad rotations as core::InputError; the embedding reader names
  // the file (exit 2, not an internal error).
  const std::string file = path("asymmetric.json");
  std::ofstream(file) << R"({"format": "laguerre-embedding",
                             "vertices": [{"id": 0, "x": 0, "y": 0, "r": 1, "neighbours": [1]},
                                           {"id": 1, "x": 2, "y": 0, "r": 1, "neighbours": []}],
                             "outer_face": [0, 1]})";
  expect_bad("route " + file, {"asymmetric.json", "rotation system is invalid"});
}

// A 3-connected graph whose polygon-face node ids do not fit the face-vertex encoding (2^31 − 1): the
// ids come from the user's file, so it is bad input (exit 2), not an internal error (it exited 1).
TEST_F(CliBadInput, FaceNodeIdsAboveTheProtocolLimitAreBadInput) {
  expect_bad("simulate " LAGUERRE_SOURCE_DIR "/tests/data/graphs/three-connected-60-big-ids.txt", {"4294967296", "2^31"});
}

TEST_F(CliBadInput, OuterRuleMustBeFaceOrPuncture) {
  for (const char* cmd : {"pack ", "simulate "}) expect_bad(cmd + graph + " --outer hole", {"--outer", "hole", "face", "puncture"});
  expect_bad("thesis-table --count 1 --size 20 --outer hole", {"--outer", "hole"});
  const std::string triangle = write("triangle.edges", "1 2\n2 3\n3 1\n");
  expect_bad("pack " + triangle + " --outer puncture --no-picture", {"triangle.edges", "at least 4"});
}
