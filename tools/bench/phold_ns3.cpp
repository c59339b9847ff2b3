// PHOLD on ns-3's core simulator (Debian's ns-3 3.37), with the very same workload and random
// numbers as phold_laguerre (see phold_common.hpp). Built only with -DLAGUERRE_BENCH_NS3=ON.
//   phold_ns3 --scheduler ns3::MapScheduler [--rng shared|ns3] [--lps 10000] [--events 10000000]
//             [--seed 1] [--repeat 1]
// Prints "ns3:<scheduler>[:ns3rng] <LPs> <events> <seconds> <events/s> <end time ns> <CPU seconds>
// <events per CPU second>", timing only
// Simulator::Run. With --rng shared (the default) both programs draw identical numbers, so the
// comparison isolates the event engines; --rng ns3 draws with ns-3's own RandomVariableStreams
// (MRG32k3a; one uniform and one exponential stream for the run), as an ns-3 user would write it. Events are scheduled the idiomatic ns-3 way, Simulator::Schedule with a member
// function and an argument. ns-3's Simulator is a process-wide singleton and its scheduler can only
// be chosen before the first event, hence one scheduler per process (phold.sh loops over them).
#include <chrono>
#include <cstdio>

#include "ns3/core-module.h"
#include "phold_common.hpp"

namespace {

struct Model {
  std::vector<phold::Lp> lps;
  std::uint32_t count = 0;
  std::uint64_t processed = 0;
  std::uint64_t limit = 0;
  ns3::Ptr<ns3::UniformRandomVariable> uniform;      // --rng ns3 only
  ns3::Ptr<ns3::ExponentialRandomVariable> exponential;
  void on_event(std::uint32_t target) {
    if (++processed == limit) ns3::Simulator::Stop();
    phold::Lp& lp = lps[target];
    const std::uint32_t to = lp.destination(count);
    ns3::Simulator::Schedule(ns3::NanoSeconds(lp.delay()), &Model::on_event, this, to);
  }
  void on_event_native(std::uint32_t) {
    if (++processed == limit) ns3::Simulator::Stop();
    const std::uint32_t to = uniform->GetInteger(0, count - 1);
    const auto delay = phold::lookahead_ns + static_cast<std::int64_t>(exponential->GetValue());
    ns3::Simulator::Schedule(ns3::NanoSeconds(delay), &Model::on_event_native, this, to);
  }
};

}  // namespace

int main(int argc, char** argv) {
  const phold::Options options = phold::parse(argc, argv);
  for (const std::uint32_t size : options.sizes) {
    for (int r = 0; r < options.repeat; ++r) {
      ns3::ObjectFactory factory;
      factory.SetTypeId(options.scheduler);
      ns3::Simulator::SetScheduler(factory);
      const bool native = options.rng == "ns3";
      Model model{phold::make_lps(size, options.seed), size, 0, options.events, nullptr, nullptr};
      if (native) {
        ns3::RngSeedManager::SetSeed(static_cast<std::uint32_t>(options.seed));
        model.uniform = ns3::CreateObject<ns3::UniformRandomVariable>();
        model.exponential = ns3::CreateObject<ns3::ExponentialRandomVariable>();
        model.exponential->SetAttribute("Mean", ns3::DoubleValue(phold::mean_ns));
        model.exponential->SetAttribute("Bound", ns3::DoubleValue(0.0));
      }
      for (std::uint32_t i = 0; i < size; ++i) {
        if (native) {
          const auto delay = phold::lookahead_ns + static_cast<std::int64_t>(model.exponential->GetValue());
          ns3::Simulator::Schedule(ns3::NanoSeconds(delay), &Model::on_event_native, &model, i);
        } else {
          ns3::Simulator::Schedule(ns3::NanoSeconds(model.lps[i].delay()), &Model::on_event, &model, i);
        }
      }
      const auto start = std::chrono::steady_clock::now();
      const double cpu_start = phold::cpu_seconds();
      ns3::Simulator::Run();
      const double cpu = phold::cpu_seconds() - cpu_start;
      const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const auto events = static_cast<double>(model.processed);
      std::printf("ns3:%s%s %u %llu %.3f %.0f %lld %.3f %.0f\n", options.scheduler.c_str(),
                  native ? ":ns3rng" : "", size, static_cast<unsigned long long>(model.processed), secs,
                  events / secs, static_cast<long long>(ns3::Simulator::Now().GetNanoSeconds()), cpu,
                  events / cpu);
      std::fflush(stdout);
      ns3::Simulator::Destroy();
    }
  }
  return 0;
}
