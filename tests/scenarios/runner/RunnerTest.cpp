// The scenario runner: seed derivation, run planning, determinism across --jobs, outcomes.
#include <gtest/gtest.h>

#include <barrier>
#include <cmath>
#include <set>
#include <string>
#include <thread>

#include "laguerre/core/Error.hpp"
#include "laguerre/core/routing/RoutingMetrics.hpp"
#include "laguerre/scenarios/Comparison.hpp"
#include "laguerre/scenarios/NetworkModel.hpp"
#include "laguerre/scenarios/Results.hpp"
#include "laguerre/scenarios/Runner.hpp"
#include "laguerre/scenarios/ScenarioLoader.hpp"

using namespace laguerre;
using namespace laguerre::scenarios;

namespace {
const std::string data_dir = std::string(LAGUERRE_TEST_DATA) + "/scenarios";

Scenario from_text(const std::string& text) { return load_scenario_from_string(text, "test.yaml", data_dir); }
}  // namespace

// SplitMix64 reference outputs for the stream seeded with 0 (Vigna's splitmix64.c): the first output
// is mix(0), the second mix(γ).
TEST(Seeds, SplitMix64KnownAnswers) {
  EXPECT_EQ(splitmix64(0), 0xE220A8397B1DCDAFULL);
  EXPECT_EQ(splitmix64(0x9E3779B97F4A7C15ULL), 0x6E789E6AA1B965F4ULL);
}

TEST(Seeds, Fnv1aKnownAnswers) {
  EXPECT_EQ(fnv1a64(""), 0xcbf29ce484222325ULL);
  EXPECT_EQ(fnv1a64("a"), 0xaf63dc4c8601ec8cULL);
  EXPECT_EQ(fnv1a64("foobar"), 0x85944171f73967e8ULL);
}

TEST(Seeds, RunSeedFollowsTheDocumentedFormula) {
  for (std::uint64_t seed : {0ull, 1ull, 2008ull, ~0ull})
    for (std::size_t p = 0; p < 5; ++p)
      for (std::size_t r = 0; r < 5; ++r)
        EXPECT_EQ(derive_run_seed(seed, p, r), splitmix64(splitmix64(splitmix64(seed) ^ p) ^ r));
}

TEST(Seeds, RunSeedsAreDistinctOverAGrid) {
  std::set<std::uint64_t> seen;
  for (std::size_t p = 0; p < 100; ++p)
    for (std::size_t r = 0; r < 100; ++r) seen.insert(derive_run_seed(7, p, r));
  EXPECT_EQ(seen.size(), 10000u);
}

// Points that differ only outside `topology` share their graphs; a different topology does not.
TEST(Seeds, TopologySeedsArePairedAcrossNetworkConditions) {
  const Scenario s = load_scenario(data_dir + "/good-sweep.yaml");
  const auto plans = plan_runs(s);
  ASSERT_EQ(plans.size(), 16u);  // 8 points × 2 repetitions, point-major
  for (std::size_t i = 0; i < plans.size(); ++i) {
    EXPECT_EQ(plans[i].point, i / 2);
    EXPECT_EQ(plans[i].repetition, i % 2);
    EXPECT_EQ(plans[i].seed, derive_run_seed(9, i / 2, i % 2));
  }
  // Points 0 and 1 differ in network.loss only; 0 and 2 in topology.n.
  EXPECT_EQ(plans[0].topology_seed, plans[2].topology_seed);
  EXPECT_NE(plans[0].topology_seed, plans[4].topology_seed);
  EXPECT_NE(plans[0].topology_seed, plans[1].topology_seed);  // another repetition
  EXPECT_NE(plans[0].seed, plans[2].seed);
}

TEST(Seeds, CanonicalTextSortsParameters) {
  TopologySpec a, b;
  a.generator = b.generator = "three-connected";
  a.params.set("n", std::int64_t{5});
  a.params.set("max_face_size", std::int64_t{6});
  b.params.set("max_face_size", std::int64_t{6});
  b.params.set("n", std::int64_t{5});
  EXPECT_EQ(canonical_text(a), "three-connected;max_face_size=6;n=5");
  EXPECT_EQ(canonical_text(a), canonical_text(b));
}

TEST(NetworkModel, Durations) {
  EXPECT_EQ(parse_duration("250us"), 250000);
  EXPECT_EQ(parse_duration("1ms"), 1000000);
  EXPECT_EQ(parse_duration("2s"), 2000000000);
  EXPECT_EQ(parse_duration("100"), 100);
  EXPECT_EQ(parse_duration("0.5ms"), 500000);
  for (const char* bad : {"", "ms", "-1ms", "3h", "1e30s"}) EXPECT_THROW((void)parse_duration(bad), core::InputError) << bad;
  for (sim::Duration d : {sim::Duration{1}, sim::Duration{1000}, sim::Duration{250000}, sim::Duration{3000000000}})
    EXPECT_EQ(parse_duration(format_duration(d)), d);
  EXPECT_EQ(parse_crash("17@40ms").node, 17u);
  EXPECT_EQ(parse_crash("17@40ms").at, 40000000);
  EXPECT_FALSE(parse_crash("17@40ms").recover_at.has_value());
  EXPECT_EQ(parse_crash("17@40ms-90ms").recover_at, sim::Time{90000000});
  for (const char* bad : {"x@1ms", "-1@1ms", "+1@1ms", "17", "17@", "17@1ms-", "17@2ms-1ms", "17@1ms-1ms", "@1ms"})
    EXPECT_THROW((void)parse_crash(bad), core::InputError) << bad;
  EXPECT_THROW((void)parse_latency("uniform:3ms:1ms"), core::InputError);
  EXPECT_EQ(parse_latency("uniform:1ms:1ms").spread, 0);
}

// Messages name the source and say what was found and expected; LO > HI gets its own.
TEST(NetworkModel, MessagesNameTheSource) {
  try {
    (void)parse_latency("uniform:5ms:1ms", "--latency");
    FAIL() << "accepted";
  } catch (const core::InputError& e) {
    EXPECT_EQ(e.source(), "--latency");
    EXPECT_EQ(std::string(e.what()),
              "--latency: found 'uniform:5ms:1ms', expected uniform:LO:HI with LO <= HI (5ms is above 1ms)");
  }
  try {
    (void)parse_crash("-1@1ms", "--crash");
    FAIL() << "accepted";
  } catch (const core::InputError& e) {
    EXPECT_EQ(std::string(e.what()), "--crash: found '-1@1ms', expected " + std::string(crash_forms));
  }
}

// --recover attaches to the latest earlier outage of the node that has no recovery yet.
TEST(NetworkModel, RecoveryAttachesToTheLatestOpenOutage) {
  std::vector<CrashSpec> crashes{parse_crash("3@10ms"), parse_crash("3@50ms"), parse_crash("4@1ms")};
  add_recovery(crashes, "3@60ms");
  EXPECT_FALSE(crashes[0].recover_at.has_value());
  EXPECT_EQ(crashes[1].recover_at, sim::Time{60000000});
  add_recovery(crashes, "3@40ms");
  EXPECT_EQ(crashes[0].recover_at, sim::Time{40000000});
  EXPECT_THROW(add_recovery(crashes, "3@70ms"), core::InputError);  // both outages have a recovery
  EXPECT_THROW(add_recovery(crashes, "4@1ms"), core::InputError);   // not after the crash
  EXPECT_THROW(add_recovery(crashes, "5@9ms"), core::InputError);   // no such outage
  EXPECT_THROW(add_recovery(crashes, "4@"), core::InputError);
}

// The same results with 1 and 2 worker threads (wall times aside).
TEST(Runner, ResultsDoNotDependOnJobs) {
  const Scenario s = load_scenario(data_dir + "/good-sweep.yaml");
  RunnerOptions one, two;
  one.jobs = 1;
  two.jobs = 2;
  const ScenarioResults a = run_scenario(s, one), b = run_scenario(s, two);
  ASSERT_EQ(a.records.size(), 16u);
  ASSERT_EQ(b.records.size(), 16u);
  for (std::size_t i = 0; i < a.records.size(); ++i) {
    const RunRecord &x = a.records[i], &y = b.records[i];
    EXPECT_EQ(x.plan.seed, y.plan.seed);
    EXPECT_EQ(x.status, y.status) << x.message;
    EXPECT_EQ(x.nodes, y.nodes);
    EXPECT_EQ(x.edges, y.edges);
    EXPECT_EQ(x.iterations, y.iterations);
    EXPECT_EQ(x.rounds, y.rounds);
    EXPECT_EQ(x.messages, y.messages);
    EXPECT_EQ(x.retransmissions, y.retransmissions);
    EXPECT_EQ(x.simulated_seconds, y.simulated_seconds);
    ASSERT_EQ(x.routing.size(), y.routing.size());
    for (std::size_t k = 0; k < x.routing.size(); ++k) {
      EXPECT_EQ(x.routing[k].delivered, y.routing[k].delivered);
      EXPECT_EQ(x.routing[k].pairs, y.routing[k].pairs);
    }
  }
  // The tables written from them are identical too (they hold no wall times but results.json's).
  EXPECT_EQ(results_csv(s, a.records), results_csv(s, b.records));
}

namespace {
/// `size` processes sharing runs, played by threads: all_gather waits for every one's bytes.
struct ThreadSplits {
  explicit ThreadSplits(std::size_t size) : parts(size), sync(static_cast<std::ptrdiff_t>(size)) {}
  struct One final : RunSplit {
    ThreadSplits* all = nullptr;
    std::size_t me = 0;
    std::size_t rank() const override { return me; }
    std::size_t size() const override { return all->parts.size(); }
    std::vector<std::byte> all_gather(std::span<const std::byte> mine) override {
      all->parts[me].assign(mine.begin(), mine.end());
      all->sync.arrive_and_wait();
      std::vector<std::byte> out;
      for (const auto& p : all->parts) out.insert(out.end(), p.begin(), p.end());
      all->sync.arrive_and_wait();  // nobody returns (and may run again) before all have read
      return out;
    }
  };
  std::vector<std::vector<std::byte>> parts;
  std::barrier<> sync;
};
}  // namespace

TEST(Runner, RunsSharedBetweenProcessesGiveTheSingleProcessResults) {
  // good-sweep.yaml (16 runs: lossy, crashing and asynchronous points) shared by 3 processes: every
  // process ends with every record, equal to a single process's in everything but wall times, and
  // the runs that keep artifacts ran on process 0.
  const Scenario s = load_scenario(data_dir + "/good-sweep.yaml");
  RunnerOptions seq;
  seq.jobs = 1;
  const auto keep = [](const RunPlan& p) { return p.point == 1 && p.repetition == 0; };
  seq.keep_artifacts = keep;
  const ScenarioResults a = run_scenario(s, seq);
  ThreadSplits splits(3);
  std::vector<ThreadSplits::One> one(3);
  std::vector<ScenarioResults> b(3);
  std::vector<std::size_t> executed(3, 0);
  std::vector<std::thread> threads;
  for (std::size_t k = 0; k < 3; ++k) {
    one[k].all = &splits, one[k].me = k;
    threads.emplace_back([&, k] {
      RunnerOptions o;
      o.split = &one[k];
      o.keep_artifacts = keep;
      o.on_progress = [&, k](const RunProgress& p) { executed[k] = p.total; };
      b[k] = run_scenario(s, o);
    });
  }
  for (auto& t : threads) t.join();
  EXPECT_EQ(executed[0] + executed[1] + executed[2], a.records.size());  // each run ran once, somewhere
  EXPECT_EQ(executed[1], executed[2]);                                   // dealt round-robin after the kept one
  const std::string expected = results_csv(s, a.records);
  for (std::size_t k = 0; k < 3; ++k) {
    SCOPED_TRACE("process " + std::to_string(k));
    ASSERT_EQ(b[k].records.size(), a.records.size());
    EXPECT_EQ(results_csv(s, b[k].records), expected);
    for (std::size_t i = 0; i < a.records.size(); ++i) {
      EXPECT_EQ(b[k].records[i].plan.seed, a.records[i].plan.seed);
      EXPECT_EQ(b[k].artifacts[i].has_value(), k == 0 && a.artifacts[i].has_value()) << "run " << i;
    }
  }
}

TEST(Runner, RecordsRoundTripThroughTheirBytes) {
  // Every run of a sweep with every scheme (hyperbolic too), on a triangulation and on a field with
  // every sensor attached: decode(encode(r)) writes the same
  // results.json as r (every field users see, wall times included), and the bytes are used up.
  const Scenario s = from_text(
      "name: x\nrepetitions: 2\ntopology: {generator: delaunay, n: 20}\n"
      "routing: {schemes: [greedy-power, greedy-euclid, compass, gfg, hyperbolic], pairs: 50}\n"
      "sweep:\n  network.loss: [0, 0.2]\n"
      "  topology:\n    - {generator: delaunay, n: 20}\n"
      "    - {generator: field, n: 80, graph: local-delaunay, radius: 0.25, repair: three-connected-core, attach: true}\n");
  RunnerOptions o;
  o.jobs = 1;
  const ScenarioResults a = run_scenario(s, o);
  std::vector<std::byte> bytes;
  for (const RunRecord& r : a.records) encode_record(r, bytes);
  std::vector<RunRecord> back;
  std::size_t at = 0;
  for (std::size_t i = 0; i < a.records.size(); ++i) back.push_back(decode_record(bytes, at));
  EXPECT_EQ(at, bytes.size());
  EXPECT_EQ(results_json(s, back), results_json(s, a.records));
  EXPECT_EQ(results_csv(s, back), results_csv(s, a.records));
  bool all_pairs = false;  // the field's runs carry the all-sensor results too
  for (const RunRecord& r : back)
    for (const SchemeResult& x : r.routing) all_pairs = all_pairs || x.all_pairs.has_value();
  EXPECT_TRUE(all_pairs);
}

// On a packing that converged to LPD/GLPD greedy power routing delivers every pair (thesis Th. 5.2.5
// and 5.2.6); a lossy network changes the traffic but not that.
TEST(Runner, ConvergedRunsDeliverEveryPairByGreedyPower) {
  const Scenario s = load_scenario(data_dir + "/good-sweep.yaml");
  const ScenarioResults res = run_scenario(s, {});
  for (const RunRecord& r : res.records) {
    ASSERT_EQ(r.status, RunStatus::ok) << r.message;
    EXPECT_EQ(r.holds_nodes, r.nodes);
    ASSERT_EQ(r.routing.size(), 2u);
    EXPECT_EQ(r.routing[0].scheme, core::Scheme::greedy_power);
    EXPECT_EQ(r.routing[0].pairs, 30u);
    EXPECT_EQ(r.routing[0].delivered, 30u);
    EXPECT_EQ(r.routing[0].positions, "packing");
    EXPECT_EQ(r.routing[1].positions, "physical");  // both generators draw their graphs
    EXPECT_GT(r.messages_per_node, 0);
    const bool lossy = s.points[r.plan.point].config.network.loss > 0;
    if (!lossy) {
      EXPECT_EQ(r.retransmissions, 0u);
    }
  }
  // Same graph at loss 0 and 0.1 (paired topology seeds): same size, same iterations in sync mode.
  EXPECT_EQ(res.records[0].edges, res.records[2].edges);
  EXPECT_EQ(res.records[0].iterations, res.records[2].iterations);
  EXPECT_GT(res.records[2].messages, res.records[0].messages);  // acks and retransmissions
}

TEST(Runner, MultiGraphFileCyclesThroughRepetitions) {
  const Scenario s = load_scenario(data_dir + "/good-file.yaml");
  const ScenarioResults res = run_scenario(s, {});
  ASSERT_EQ(res.records.size(), 3u);
  std::set<std::string> names;
  for (const RunRecord& r : res.records) {
    EXPECT_EQ(r.status, RunStatus::ok) << r.message;
    EXPECT_EQ(r.kind, "three_connected");
    names.insert(r.topology);
    EXPECT_EQ(r.routing.at(0).pairs, r.nodes * (r.nodes - 1));
  }
  EXPECT_EQ(names.size(), 3u);
}

TEST(Runner, UnpackableTopologyIsRecordedNotThrown) {
  const Scenario s = load_scenario(data_dir + "/unpackable.yaml");
  const ScenarioResults res = run_scenario(s, {});
  ASSERT_EQ(res.records.size(), 1u);
  EXPECT_EQ(res.records[0].status, RunStatus::unsupported);
  EXPECT_NE(res.records[0].message.find("cannot be packed"), std::string::npos) << res.records[0].message;
  EXPECT_TRUE(res.records[0].routing.empty());
}

TEST(Runner, ExactReferenceCountsMoreIterationsThanLpd) {
  const Scenario s = from_text("name: x\nrepetitions: 2\ntopology: {generator: delaunay, n: 30}\n"
                               "protocol: {exact_reference: true}\nrouting: {schemes: [greedy-power], pairs: 10}\n");
  const ScenarioResults res = run_scenario(s, {});
  for (const RunRecord& r : res.records) {
    ASSERT_EQ(r.status, RunStatus::ok);
    // Synchronous protocol = core::pack bit for bit, so the core run sees LPD first at the same sweep.
    EXPECT_EQ(r.core_lpd_iterations, static_cast<int>(r.iterations));
    EXPECT_GE(r.exact_iterations, r.core_lpd_iterations);
  }
  EXPECT_NE(summary_table(s, res.records).find("to an exact packing"), std::string::npos);
}

TEST(Runner, ArtifactsForPictures) {
  const Scenario s = from_text("name: x\ntopology: {generator: delaunay, n: 25}\nrouting: {sample_routes: 4}\n");
  RunnerOptions o;
  o.keep_artifacts = [](const RunPlan&) { return true; };
  const ScenarioResults res = run_scenario(s, o);
  ASSERT_TRUE(res.artifacts.at(0).has_value());
  const RunArtifacts& a = *res.artifacts[0];
  EXPECT_EQ(a.circles.size(), 25u);
  EXPECT_EQ(a.topology.positions.size(), 25u);
  ASSERT_EQ(a.greedy_routes.size(), 4u);
  ASSERT_EQ(a.gfg_routes.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {  // same pair, both delivered
    EXPECT_EQ(a.greedy_routes[i].front(), a.gfg_routes[i].front());
    EXPECT_EQ(a.greedy_routes[i].back(), a.gfg_routes[i].back());
  }
}

// Statistics of the comparison.
TEST(Comparison, StudentQuantiles) {
  EXPECT_DOUBLE_EQ(student_t_975(1), 12.706);
  EXPECT_DOUBLE_EQ(student_t_975(4), 2.776);
  EXPECT_NEAR(student_t_975(40), 2.021, 1e-3);   // table value 2.0211
  EXPECT_NEAR(student_t_975(120), 1.980, 1e-3);  // table value 1.9799
  EXPECT_NEAR(student_t_975(1000000), 1.95996, 1e-4);
  EXPECT_TRUE(std::isinf(student_t_975(0)));
}

TEST(Comparison, WilsonInterval) {
  // 8 of 10: centre (0.8 + z²/20)/(1 + z²/10), known answer [0.4902, 0.9433].
  const Interval w = wilson_interval(8, 10);
  EXPECT_NEAR(w.low, 0.4902, 1e-4);
  EXPECT_NEAR(w.high, 0.9433, 1e-4);
  const Interval all = wilson_interval(50, 50);
  EXPECT_DOUBLE_EQ(all.high, 1.0);
  EXPECT_NEAR(all.low, 0.9287, 1e-4);
}

TEST(Comparison, TIntervalKnownAnswer) {
  // mean 0.9, s = 0.1, r = 3: 0.9 ± 4.303 · 0.1 / √3.
  const Interval t = t_interval({0.8, 0.9, 1.0});
  EXPECT_NEAR(t.low, 0.9 - 4.303 * 0.1 / std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(t.high, 0.9 + 4.303 * 0.1 / std::sqrt(3.0), 1e-12);
}

TEST(Comparison, RowsPerPointAndScheme) {
  const Scenario s = load_scenario(data_dir + "/good-sweep.yaml");
  const ScenarioResults res = run_scenario(s, {});
  const auto rows = compare_runs(s, res.records);
  ASSERT_EQ(rows.size(), 16u);  // 8 points × 2 schemes
  for (const auto& r : rows) {
    EXPECT_EQ(r.runs, 2u);
    EXPECT_EQ(r.routed, 2u);
    EXPECT_EQ(r.ci_method, "t");
    EXPECT_LE(r.delivery_ci.low, r.delivery_mean);
    EXPECT_GE(r.delivery_ci.high, r.delivery_mean);
    EXPECT_GE(r.delivery_ci.low, 0.0);
    EXPECT_LE(r.delivery_ci.high, 1.0);
    if (r.scheme == "greedy-power") {
      EXPECT_EQ(r.delivery_mean, 1.0);
    }
  }
  EXPECT_EQ(rows[0].family, "delaunay");
  EXPECT_EQ(rows[0].size, "20");
  EXPECT_EQ(rows[1].network, "uniform:1ms:2ms");
  EXPECT_EQ(rows[2].network, "uniform:1ms:2ms loss=0.1");
  // One repetition: the Wilson interval on that run's pairs.
  LoadOptions o;
  o.overrides = {"repetitions=1"};
  const Scenario s1 = load_scenario(data_dir + "/good-sweep.yaml", o);
  const auto rows1 = compare_runs(s1, run_scenario(s1, {}).records);
  EXPECT_EQ(rows1.at(0).ci_method, "wilson");
  EXPECT_NEAR(rows1[0].delivery_ci.low, wilson_interval(30, 30).low, 1e-12);
}

// Mode central runs core::pack instead of the simulated protocol: the synchronous protocol equals the
// centralized iteration bit for bit, so iterations and routing are the same, with no messages.
TEST(Runner, CentralModeEqualsTheSynchronousProtocol) {
  const std::string base = "name: c\nseed: 3\nrepetitions: 3\ntopology: {generator: delaunay, n: 60}\n"
                           "routing: {schemes: [greedy-power, gfg], pairs: 200}\n";
  const ScenarioResults sync = run_scenario(from_text(base + "protocol: {mode: sync}\n"), {});
  const ScenarioResults central = run_scenario(from_text(base + "protocol: {mode: central}\n"), {});
  ASSERT_EQ(sync.records.size(), central.records.size());
  for (std::size_t i = 0; i < sync.records.size(); ++i) {
    const RunRecord &a = sync.records[i], &b = central.records[i];
    ASSERT_EQ(a.status, RunStatus::ok) << a.message;
    ASSERT_EQ(b.status, RunStatus::ok) << b.message;
    EXPECT_EQ(a.iterations, b.iterations);
    EXPECT_EQ(b.messages, 0u);
    for (std::size_t k = 0; k < a.routing.size(); ++k) {
      EXPECT_EQ(a.routing[k].delivered, b.routing[k].delivered);
      EXPECT_EQ(a.routing[k].stretch_mean, b.routing[k].stretch_mean);
    }
  }
  // Anderson mixing needs fewer sweeps and still ends with LPD everywhere.
  const ScenarioResults fast =
      run_scenario(from_text(base + "protocol: {mode: central, acceleration: anderson}\n"), {});
  for (const RunRecord& r : fast.records) {
    ASSERT_EQ(r.status, RunStatus::ok) << r.message;
    EXPECT_EQ(r.holds_nodes, r.nodes);
  }
  EXPECT_THROW(from_text(base + "protocol: {mode: sync, acceleration: anderson}\n"), ScenarioError);
  // The local acceleration and Newton–Krylov run in the network: the same iterations as centrally,
  // with messages.
  for (const std::string a : {"chebyshev", "newton-krylov"}) {
    SCOPED_TRACE(a);
    const ScenarioResults local_sync = run_scenario(from_text(base + "protocol: {mode: sync, acceleration: " + a + "}\n"), {});
    const ScenarioResults local_central =
        run_scenario(from_text(base + "protocol: {mode: central, acceleration: " + a + "}\n"), {});
    ASSERT_EQ(local_sync.records.size(), local_central.records.size());
    for (std::size_t i = 0; i < local_sync.records.size(); ++i) {
      ASSERT_EQ(local_sync.records[i].status, RunStatus::ok) << local_sync.records[i].message;
      EXPECT_EQ(local_sync.records[i].iterations, local_central.records[i].iterations);
      EXPECT_EQ(local_sync.records[i].holds_nodes, local_sync.records[i].nodes);
      EXPECT_GT(local_sync.records[i].messages, 0u);
    }
    EXPECT_THROW(from_text(base + "protocol: {mode: async, acceleration: " + a + "}\n"), ScenarioError);
  }
}

// The bundled all-sensors comparison (scenarios/field-holes-comparison.yaml), small: every sensor is
// routed (nodes == sensors), greedy power with the attachment delivers every connected sensor pair,
// every scheme's stretch against BFS in the links is at least 1, no route uses a non-link, and the
// comparison rows carry the all-pairs columns; two runs give the same tables.
TEST(Runner, BundledFieldHolesComparisonRoutesEverySensor) {
  LoadOptions o;
  o.overrides = {"repetitions=1",
                 "sweep.topology=[{generator: field, n: 200, radius: 0.14, graph: local-delaunay, repair: "
                 "three-connected-core, attach: true}]",
                 "routing.pairs=1500"};
  const Scenario s = load_scenario(std::string(LAGUERRE_TEST_DATA) + "/../../scenarios/field-holes-comparison.yaml", o);
  ASSERT_EQ(s.points.size(), 6u);  // 3 domains × 2 link models
  const ScenarioResults a = run_scenario(s, {});
  for (const RunRecord& r : a.records) {
    ASSERT_EQ(r.status, RunStatus::ok) << r.message;
    EXPECT_EQ(r.sensors, 200u);
    EXPECT_EQ(r.nodes, r.sensors);
    EXPECT_LE(r.core_nodes, r.nodes);
    EXPECT_LT(r.unreachable_sensors, r.sensors - r.core_nodes + 1);
    ASSERT_EQ(r.routing.size(), 5u);  // the four schemes and the hyperbolic baseline
    for (const SchemeResult& sr : r.routing) {
      ASSERT_TRUE(sr.all_pairs) << scheme_name(sr.scheme);
      EXPECT_EQ(sr.all_pairs->pairs, 1500u);
      EXPECT_EQ(sr.all_pairs->invalid_routes, 0u);
      EXPECT_GE(sr.all_pairs->stretch_mean, 1.0) << scheme_name(sr.scheme);
      EXPECT_GE(sr.stretch_mean, 1.0);
    }
    EXPECT_EQ(r.routing[0].scheme, core::Scheme::greedy_power);
    EXPECT_EQ(r.routing[0].all_pairs->delivered, r.routing[0].all_pairs->pairs - r.routing[0].all_pairs->disconnected);
    EXPECT_EQ(r.routing[0].delivered, r.routing[0].pairs);  // the core pairs as before
  }
  const auto rows = compare_runs(s, a.records);
  ASSERT_EQ(rows.size(), 30u);
  for (const ComparisonRow& row : rows) {
    EXPECT_EQ(row.all_pairs_runs, 1u);
    EXPECT_EQ(row.sensors_mean, 200.0);
    EXPECT_EQ(row.nodes_mean, 200.0);
    EXPECT_LE(row.core_nodes_mean, row.nodes_mean);
  }
  EXPECT_EQ(rows[0].all_pairs.delivery_mean, 1.0);
  EXPECT_EQ(rows[0].family, "field:square-with-holes:unit-disk");  // the swept domain and links name the rows
  EXPECT_EQ(rows[5 * 5].family, "field:many-small-holes:quasi-unit-disk");
  const ScenarioResults b = run_scenario(s, {});
  EXPECT_EQ(results_csv(s, a.records), results_csv(s, b.records));
  EXPECT_EQ(comparison_csv(rows), comparison_csv(compare_runs(s, b.records)));
}

// protocol.termination: radius-only in the network equals radius-only centrally (same iterations),
// ends with LPD everywhere on its exact check, and stops no earlier than the layout termination (it
// checks a subset of the same iterates). On graphs this small it can send more messages: the rounds
// after LPD first holds, until the gap meets its tolerance, cost more than the waves saved.
TEST(Runner, RadiusOnlyTerminationInScenarioFiles) {
  const std::string base = "name: r\nseed: 5\nrepetitions: 2\ntopology: {generator: delaunay, n: 80}\n"
                           "routing: {schemes: [greedy-power], pairs: 100}\n";
  const ScenarioResults layout = run_scenario(from_text(base + "protocol: {mode: sync}\n"), {});
  const ScenarioResults sync = run_scenario(from_text(base + "protocol: {mode: sync, termination: radius-only}\n"), {});
  const ScenarioResults central =
      run_scenario(from_text(base + "protocol: {mode: central, termination: radius-only}\n"), {});
  ASSERT_EQ(sync.records.size(), central.records.size());
  for (std::size_t i = 0; i < sync.records.size(); ++i) {
    ASSERT_EQ(sync.records[i].status, RunStatus::ok) << sync.records[i].message;
    EXPECT_EQ(sync.records[i].iterations, central.records[i].iterations);
    EXPECT_EQ(sync.records[i].holds_nodes, sync.records[i].nodes);
    EXPECT_GE(sync.records[i].iterations, layout.records[i].iterations);
    EXPECT_GT(sync.records[i].messages, 0u);
  }
  try {
    from_text(base + "protocol: {mode: async, termination: radius-only}\n");
    ADD_FAILURE() << "async radius-only accepted";
  } catch (const ScenarioError& e) {
    EXPECT_NE(std::string(e.what()).find("protocol.termination"), std::string::npos) << e.what();
  }
  try {
    from_text(base + "protocol: {termination: soon}\n");
    ADD_FAILURE() << "an unknown termination accepted";
  } catch (const ScenarioError& e) {
    EXPECT_NE(std::string(e.what()).find("radius-only"), std::string::npos) << e.what();
  }
}
