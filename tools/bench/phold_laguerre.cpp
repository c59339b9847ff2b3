// PHOLD on the laguerre::sim kernel (see phold_common.hpp for the workload).
//   phold_laguerre [--lps 10000,100000,1000000] [--events 10000000] [--seed 1] [--repeat 1]
//                  [--prefetch 1|0]
// Prints one line per run: "laguerre <LPs> <events> <seconds> <events/s> <end time ns> <CPU seconds>
// <events per CPU second>", timing
// only Kernel::run (the initial events are scheduled before the clock starts, as on the ns-3 side).
// With --prefetch 1 (the default) the model tells the kernel where its per-LP state lives
// (Kernel::set_prefetch), so the loop prefetches the state of the LP a few events ahead; the work per
// event is unchanged (phold.sh also reports --prefetch 0, which ns-3 has no equivalent for).
#include <chrono>
#include <cstdio>

#include "laguerre/sim/Kernel.hpp"
#include "phold_common.hpp"

namespace {

struct Model {
  std::vector<phold::Lp> lps;
  std::uint32_t count = 0;
  laguerre::sim::HandlerId handler = 0;
  void on_event(laguerre::sim::Kernel& kernel, const laguerre::sim::Event& event) {
    phold::Lp& lp = lps[event.target];
    const std::uint32_t to = lp.destination(count);
    kernel.schedule_after(lp.delay(), handler, to);
  }
};

}  // namespace

int main(int argc, char** argv) {
  const phold::Options options = phold::parse(argc, argv);
  for (const std::uint32_t size : options.sizes) {
    for (int r = 0; r < options.repeat; ++r) {
      laguerre::sim::Kernel kernel;
      Model model{phold::make_lps(size, options.seed), size, 0};
      model.handler = kernel.add_handler<&Model::on_event>("phold", model);
      if (options.prefetch) kernel.set_prefetch(model.handler, model.lps.data(), sizeof(phold::Lp));
      kernel.reserve(size);
      for (std::uint32_t i = 0; i < size; ++i) kernel.schedule_at(model.lps[i].delay(), model.handler, i);
      const auto start = std::chrono::steady_clock::now();
      const double cpu_start = phold::cpu_seconds();
      kernel.run({.max_events = options.events});
      const double cpu = phold::cpu_seconds() - cpu_start;
      const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const auto events = static_cast<double>(kernel.events_processed());
      std::printf("laguerre %u %llu %.3f %.0f %lld %.3f %.0f\n", size,
                  static_cast<unsigned long long>(kernel.events_processed()), secs, events / secs,
                  static_cast<long long>(kernel.now()), cpu, events / cpu);
      std::fflush(stdout);
    }
  }
  return 0;
}
