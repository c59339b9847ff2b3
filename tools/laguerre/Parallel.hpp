#pragma once
/// @file
/// The program under mpirun. Built with MPI (sim/mpi found) and launched by an MPI launcher
/// (OMPI_COMM_WORLD_SIZE, PMI_SIZE or PMIX_RANK set), the program initializes MPI, ranks other than
/// 0 stay quiet (stdout and stderr to /dev/null), and the protocol simulation of `simulate` runs on
/// the parallel kernel (same results as sequentially; see sim/mpi). Otherwise it is sequential and
/// host_runner() is null.

#include <cstddef>
#include <vector>

#include <nlohmann/json.hpp>

#include "laguerre/core/graph/PlanarGraph.hpp"
#include "laguerre/scenarios/Runner.hpp"
#include "laguerre/sim/HostRunner.hpp"

namespace laguerre::tools {

/// The MPI session of the program, for the lifetime of main.
class ParallelContext {
public:
  /// Initializes MPI if the program was built with it and launched by mpirun.
  ParallelContext(int& argc, char**& argv);
  ParallelContext(const ParallelContext&) = delete;
  ParallelContext& operator=(const ParallelContext&) = delete;
  /// Finalizes MPI if this object initialized it.
  ~ParallelContext();
  /// The number of ranks (1 when sequential).
  int ranks() const { return ranks_; }

private:
  int ranks_ = 1;
  bool active_ = false;
};

/// The number of MPI ranks the program runs on (1 when sequential).
int mpi_ranks();

/// The runner the simulation commands use: the MPI one on more than one rank, else nullptr.
sim::HostRunner* host_runner();

/// What the parallel kernel did in the runs of host_runner() so far: ranks, windows, lookahead, cut
/// links, copies and bytes sent between ranks, and per rank its nodes, events, seconds in events and
/// in synchronization and peak memory (sim::mpi::ParallelReport). Null when sequential.
nlohmann::json parallel_summary();

/// The sharing of a sweep's runs among the ranks (`run`, `compare`): every rank runs its share, each
/// run sequentially, and all get every record (scenarios::RunSplit); nullptr on one rank.
scenarios::RunSplit* run_split();

/// The worker of each vertex of `g` over `parts` workers by sim/mpi's METIS partition (what
/// `live --partition metis` uses). Throws core::InputError when the program was built without MPI.
std::vector<std::size_t> metis_workers(const core::PlanarGraph& g, std::size_t parts);

}  // namespace laguerre::tools
