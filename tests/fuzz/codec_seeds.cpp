// Writes the seed corpus of codec_fuzz: one encoded message of each type (small payloads), into the
// folder given (tests/fuzz/corpus/codec). Target codec_fuzz_seeds, built on demand only.
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "laguerre/protocols/Codec.hpp"

int main(int argc, char** argv) {
  namespace p = laguerre::protocols;
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s FOLDER\n", argv[0]);
    return 2;
  }
  const std::vector<std::byte> placed = p::encode(p::PlacedMsg{3, 0.5, 0.25, -0.125, 1.5, -2.0, 0.75});
  const std::vector<p::Message> messages = {
      p::DepthMsg{true, 7, 3},
      p::ElectionMsg{p::ElectionStage::ring, 2, 42},
      p::StartMsg{1, 9},
      p::WaveMsg{4, 2, 17},
      p::RadiusMsg{12, 0.693},
      p::PlacedMsg{3, 0.5, 0.25, -0.125, 1.5, -2.0, 0.75},
      p::ReportMsg{5, true},
      p::DecisionMsg{6, p::Verdict::converged},
      p::ShapeMsg{true, false},
      p::FaceCirclesMsg{8, {{0, 0, 1}, {2, 0, 1}, {1, 1.5, 0.5}}},
      p::RelayMsg{10, 11, 12, true, placed},
      p::DataMsg{1, 2, 3, 0.5, 0.5, 0.1, 64, 1},
      p::FrameMsg{5, {3, 0x5}, placed},
      p::FrameMsg{6, {4, 0}, {}},
      p::AckMsg{{9, 0xff}},
      p::FailureMsg{13},
      p::RouteMsg{4, 1, 2, p::RouteScheme::gfg, 0.75, 0.25, 32, 3, true, 0.1, 0.2, true, 0.3, 0.4, 0.5, 0.6, 7, 8},
      p::KrylovValueMsg{9, -0.5},
      p::KrylovSumMsg{9, 1, 2, 3, 0.5},
      p::KrylovDecisionMsg{9, 0, 0.25, 0.75},
      p::GateRadiusMsg{9, 0.5, 0x3},
      p::HeightMsg{true, 12},
      p::HyperbolicSweepMsg{1, 6, 21},
      p::HyperbolicEchoMsg{0, 11, 4},
      p::HyperbolicRootMsg{1, 2},
      p::HyperbolicAddressMsg{8, 0, 5, p::pack_hyperbolic_address(std::vector<std::uint32_t>{7, 1, 3, 6, 2}, 8)},
  };
  for (std::size_t i = 0; i < messages.size(); ++i) {
    const std::vector<std::byte> bytes = p::encode(messages[i]);
    std::ofstream out(std::string(argv[1]) + "/" + std::to_string(static_cast<int>(p::type_of(messages[i]))) + "-" +
                          std::to_string(i) + ".bin",
                      std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  }
  return 0;
}
