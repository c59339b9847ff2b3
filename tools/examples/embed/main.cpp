// Embedding laguerre's node runtime in another program: a host of its own (here a tiny round-robin
// message loop) implements laguerre::protocols::Runtime, builds one PackingNode per vertex and runs
// them until they stop; then the program checks the result with the core library.
#include <cstdio>
#include <deque>
#include <map>
#include <memory>
#include <vector>

#include "laguerre/core/graph/RandomGraphs.hpp"
#include "laguerre/core/graph/GraphKind.hpp"
#include "laguerre/core/power/LocalPowerDiagram.hpp"
#include "laguerre/protocols/PackingNode.hpp"

namespace lp = laguerre::protocols;
namespace lc = laguerre::core;

struct Message {
  lp::NodeId from, to;
  std::vector<std::byte> bytes;
};

// One Runtime per node; every send goes to the shared FIFO queue.
class LoopRuntime final : public lp::Runtime {
public:
  LoopRuntime(lp::NodeId self, std::vector<lp::NodeId> neighbours, std::deque<Message>& queue)
      : self_(self), neighbours_(std::move(neighbours)), queue_(queue) {}
  lp::NodeId self() const override { return self_; }
  lp::Time now() const override { return 0; }
  void send(lp::NodeId to, std::span<const std::byte> bytes) override {
    queue_.push_back({self_, to, {bytes.begin(), bytes.end()}});
  }
  void broadcast(std::span<const std::byte> bytes) override {
    for (lp::NodeId to : neighbours_) send(to, bytes);
  }
  lp::TimerHandle schedule(lp::Duration, lp::TimerId) override { return 0; }  // the sync protocol sets none
  bool cancel(lp::TimerHandle) override { return false; }
  std::uint64_t random_u64() override { return state_ = state_ * 6364136223846793005ull + 1442695040888963407ull; }

private:
  lp::NodeId self_;
  std::vector<lp::NodeId> neighbours_;
  std::deque<Message>& queue_;
  std::uint64_t state_ = 1;
};

int main() {
  const lc::PlanarGraph g = lc::prepare_for_packing(lc::random_delaunay_triangulation(40, 7));
  std::deque<Message> queue;
  std::vector<std::unique_ptr<LoopRuntime>> runtimes;
  std::vector<std::unique_ptr<lp::PackingNode>> nodes;
  std::map<lp::NodeId, std::size_t> index;
  for (lc::Vertex v = 0; v < g.num_vertices(); ++v) {
    std::vector<lp::NodeId> nb;
    for (lc::Vertex w : g.neighbours(v)) nb.push_back(g.id(w));
    runtimes.push_back(std::make_unique<LoopRuntime>(g.id(v), nb, queue));
    nodes.push_back(std::make_unique<lp::PackingNode>(*runtimes.back(), lp::local_knowledge(g, v), lp::PackingParams{}));
    index[g.id(v)] = v;
  }
  for (auto& node : nodes) node->on_start();
  std::size_t delivered = 0;
  while (!queue.empty()) {
    Message m = std::move(queue.front());
    queue.pop_front();
    nodes[index.at(m.to)]->on_message(m.from, m.bytes);
    ++delivered;
  }
  lc::CircleEmbedding phi;
  std::size_t converged = 0;
  for (const auto& node : nodes) {
    phi.push_back(node->placement().circle);
    converged += node->outcome() == lp::PackingOutcome::converged;
  }
  std::size_t holds = 0;
  for (auto c : lc::check_all(g, phi)) holds += c == lc::LocalCondition::holds;
  std::printf("%zu messages; %zu/%zu nodes converged after %u iterations; LPD holds at %zu/%zu\n", delivered,
              converged, nodes.size(), nodes[0]->steps(), holds, nodes.size());
  return converged == nodes.size() && holds == nodes.size() ? 0 : 1;
}
