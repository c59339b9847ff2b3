#pragma once
/// @file
/// `laguerre compare`: routing results aggregated over repetitions per family × size × network
/// condition × scheme, with 95% confidence intervals for the delivery rate.
///
/// ## Confidence interval of the delivery rate
/// With r ≥ 2 routed repetitions, the Student t-interval over repetitions: the per-run delivery rates
/// d_1 … d_r (each over that run's pairs) have mean m and sample standard deviation s, and the interval
/// is m ± t_{0.975, r−1} · s / √r, clipped to [0, 1]. Repetitions are the independent units (each has
/// its own graph); pairs routed on one graph are not independent, so pooling them would understate the
/// uncertainty. With a single routed repetition, the Wilson score interval on that run's pairs
/// (z = 1.96) is given instead and marked as such (`ci_method` "wilson" instead of "t").

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "laguerre/core/routing/Routing.hpp"
#include "laguerre/scenarios/Runner.hpp"
#include "laguerre/scenarios/Scenario.hpp"

namespace laguerre::scenarios {

/// A closed interval [low, high].
struct Interval {
  double low = 0;   ///< lower end
  double high = 0;  ///< upper end
};

/// The 97.5% quantile of Student's t distribution with `dof` ≥ 1 degrees of freedom: table values
/// (3 decimals) for dof ≤ 30, beyond that the Cornish–Fisher expansion z + (z³+z)/(4ν) +
/// (5z⁵+16z³+3z)/(96ν²) around z = 1.959964 (error below 0.001). dof 0 gives infinity.
double student_t_975(std::size_t dof);

/// Wilson score interval of a proportion `successes`/`trials` at normal quantile z (trials ≥ 1).
Interval wilson_interval(std::size_t successes, std::size_t trials, double z = 1.959963984540054);

/// Student t 95% interval of the mean of `samples` (at least 2), not clipped.
Interval t_interval(const std::vector<double>& samples);

/// Delivery and stretch of one population of pairs over the routed runs of a row.
struct PairSummary {
  double delivery_mean = std::numeric_limits<double>::quiet_NaN();  ///< mean per-run delivery rate
  Interval delivery_ci{std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};  ///< 95%
  std::string ci_method;  ///< "t", "wilson" or "" (no run)
  double stretch_mean = std::numeric_limits<double>::quiet_NaN();  ///< weighted by delivered pairs
  double stretch_p95 = std::numeric_limits<double>::quiet_NaN();   ///< mean of per-run 95th percentiles
  double stretch_max = std::numeric_limits<double>::quiet_NaN();   ///< largest over the runs
};

/// One line of the comparison.
struct ComparisonRow {
  std::string scenario;              ///< scenario name
  std::size_t point = 0;             ///< sweep point
  std::string family;                ///< generator, then the point's swept topology values but the size ("field:one-large-hole:unit-disk")
  std::string size;                  ///< topology.n (or "-")
  std::string network;               ///< network condition (network_label)
  std::string scheme;                ///< routing scheme (scenario spelling)
  std::size_t runs = 0;              ///< repetitions run
  std::size_t routed = 0;            ///< repetitions whose pairs were routed
  double nodes_mean = 0;             ///< mean node count of the routed runs
  double delivery_mean = 0;          ///< mean per-run delivery rate (NaN if none routed)
  Interval delivery_ci;              ///< 95% confidence interval (see the file comment)
  std::string ci_method;             ///< "t", "wilson" or "" (no routed run)
  double stretch_mean = 0;           ///< mean of per-run mean hop stretch, weighted by delivered pairs
  double stretch_p95 = 0;            ///< mean of per-run 95th percentiles
  double stretch_max = 0;            ///< largest over the runs
  double iterations_mean = 0;        ///< protocol iterations, mean over routed runs
  double rounds_mean = 0;            ///< protocol rounds
  double messages_per_node_mean = 0; ///< messages per node (the scheme's own set-up, else the protocol's)
  double bytes_per_node_mean = 0;    ///< their bytes per node
  double state_bytes_per_node_mean = 0;  ///< routing state per node, bytes (SchemeResult::state_bytes_per_node)
  double simulated_seconds_mean = 0; ///< simulated time of the protocol
  double sensors_mean = 0;           ///< mean sensors deployed (= nodes_mean unless a field drops sensors)
  double core_nodes_mean = 0;        ///< mean vertices packed (the 3-connected core of a field)
  /// Fields with attach: pairs of all sensors in one link component (Runner.hpp SchemeResult::all_pairs);
  /// the delivery and stretch fields above are then over the core's pairs.
  PairSummary all_pairs;
  std::size_t all_pairs_runs = 0;    ///< runs that measured all pairs (0: not a field with attach)
  double disconnected_mean = 0;      ///< mean share of sampled pairs in different link components (excluded)
};

/// The comparison rows of one scenario's records: one per sweep point and scheme, in point order then
/// the scenario's scheme order.
std::vector<ComparisonRow> compare_runs(const Scenario& scenario, const std::vector<RunRecord>& records);

/// The rows as a fixed-width text table (grouped as they come).
std::string comparison_table(const std::vector<ComparisonRow>& rows);
/// The rows as CSV (header first).
std::string comparison_csv(const std::vector<ComparisonRow>& rows);
/// The rows as a JSON array (NaN as null), with the interval method stated.
std::string comparison_json(const std::vector<ComparisonRow>& rows);

}  // namespace laguerre::scenarios
