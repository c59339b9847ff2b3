#include <metis.h>

#include <string>

#include "laguerre/core/Error.hpp"
#include "laguerre/sim/mpi/Parallel.hpp"

namespace laguerre::sim::mpi {

std::vector<int> metis_partition(const Network& network, int parts) {
  LAGUERRE_PRECONDITION(parts >= 1, "A partition needs at least one part, got " + std::to_string(parts) + ".");
  const std::size_t n = network.node_count();
  std::vector<int> owner(n, 0);
  if (parts == 1 || n == 0 || network.link_count() == 0) return owner;
  if (n <= static_cast<std::size_t>(parts)) {  // METIS wants more vertices than parts
    for (std::size_t v = 0; v < n; ++v) owner[v] = static_cast<int>(v);
    return owner;
  }
  std::vector<idx_t> xadj(n + 1), adjncy, vwgt(n), adjwgt;
  adjncy.reserve(network.link_count());
  for (NodeIndex v = 0; v < n; ++v) {
    const auto nbrs = network.neighbours(v);
    xadj[v] = static_cast<idx_t>(adjncy.size());
    vwgt[v] = static_cast<idx_t>(1 + nbrs.size());
    for (const NodeIndex w : nbrs) adjncy.push_back(static_cast<idx_t>(w));
  }
  xadj[n] = static_cast<idx_t>(adjncy.size());
  adjwgt.assign(adjncy.size(), 1);
  idx_t nvtxs = static_cast<idx_t>(n), ncon = 1, nparts = parts, cut = 0;
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_SEED] = 1;
  options[METIS_OPTION_NUMBERING] = 0;
  std::vector<idx_t> part(n);
  const int status = METIS_PartGraphKway(&nvtxs, &ncon, xadj.data(), adjncy.data(), vwgt.data(), nullptr,
                                         adjwgt.data(), &nparts, nullptr, nullptr, options, &cut, part.data());
  if (status != METIS_OK) {
    throw core::InternalError("METIS_PartGraphKway failed (status " + std::to_string(status) + ") on " +
                              std::to_string(n) + " nodes into " + std::to_string(parts) + " parts.");
  }
  for (std::size_t v = 0; v < n; ++v) owner[v] = static_cast<int>(part[v]);
  return owner;
}

}  // namespace laguerre::sim::mpi
