// Fuzz harness: domain files (core/meshing/Domain.hpp, read_domain). read_domain takes a path, so the
// input goes through a scratch file. On success the boundary vertices must locate on the boundary
// (exact predicates) and the constraints must split into pieces.
#include <filesystem>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <string>

#include <unistd.h>

#include "FuzzTarget.hpp"
#include "laguerre/core/Error.hpp"
#include "laguerre/core/meshing/Domain.hpp"

namespace {

// A scratch file of this process (in memory where /dev/shm exists), removed at exit.
struct ScratchFile {
  std::filesystem::path path = folder() / ("laguerre-domain-fuzz-" + std::to_string(::getpid()) + ".txt");
  static std::filesystem::path folder() {
    std::error_code ec;
    return std::filesystem::is_directory("/dev/shm", ec) ? "/dev/shm" : std::filesystem::temp_directory_path();
  }
  ~ScratchFile() {
    std::error_code ec;
    std::filesystem::remove(path, ec);
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace core = laguerre::core;
  static const ScratchFile scratch;
  {
    std::ofstream out(scratch.path, std::ios::binary | std::ios::trunc);
    out << laguerre::fuzz::as_text(data, size);
  }
  std::optional<core::Domain> domain;
  if (!laguerre::fuzz::parses<core::DomainError, core::InputError, std::invalid_argument>(
          [&] { domain = core::read_domain(scratch.path.string()); }))
    return 0;
  LAGUERRE_FUZZ_CHECK(domain->outer().size() >= 3);
  for (const core::Point2& p : domain->outer()) LAGUERRE_FUZZ_CHECK(domain->locate(p) == core::DomainSide::boundary);
  for (const auto& hole : domain->holes()) {
    LAGUERRE_FUZZ_CHECK(hole.size() >= 3);
    for (const core::Point2& p : hole) LAGUERRE_FUZZ_CHECK(domain->locate(p) == core::DomainSide::boundary);
  }
  const auto pieces = domain->constraint_pieces();
  LAGUERRE_FUZZ_CHECK(pieces.size() >= domain->constraints().size());
  const auto box = domain->bounding_box();
  LAGUERRE_FUZZ_CHECK(box[0] < box[2] && box[1] < box[3]);
  return 0;
}
