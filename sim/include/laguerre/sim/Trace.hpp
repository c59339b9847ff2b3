#pragma once
/// @file
/// An optional trace of delivered messages and its stable 64-bit hash, for golden and determinism
/// tests.
///
/// Canonical encoding (what the hash covers, and what `write_binary` writes after its header): per
/// delivered copy, in delivery order, the little-endian bytes of
///     time (int64) · from id (uint64) · to id (uint64) · phase (uint16) · size (uint32) · digest (uint64)
/// where ids are the network's user ids and `digest` is the FNV-1a 64 hash of the message bytes.
/// The trace hash is FNV-1a 64 over the concatenated encodings: it depends on nothing but the
/// delivered messages and their order, so it is stable across builds, platforms and hosts.

#include <array>
#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <span>
#include <vector>

#include "laguerre/core/random/Random.hpp"
#include "laguerre/sim/Metrics.hpp"
#include "laguerre/sim/Time.hpp"

namespace laguerre::sim {

using core::fnv1a_basis;

/// Continues an FNV-1a 64 hash `h` over `bytes` (core::fnv1a64).
constexpr std::uint64_t fnv1a(std::span<const std::byte> bytes, std::uint64_t h = fnv1a_basis) {
  return core::fnv1a64(bytes, h);
}

/// How much of the trace a Simulator keeps.
enum class TraceMode {
  off,        ///< nothing (the hash stays at fnv1a_basis)
  hash_only,  ///< the running hash only
  records,    ///< the hash and every record
};

/// One delivered copy of a message.
struct TraceRecord {
  Time time = 0;             ///< delivery time
  std::uint64_t from = 0;    ///< sender's user id
  std::uint64_t to = 0;      ///< receiver's user id
  std::uint64_t digest = 0;  ///< FNV-1a 64 of the message bytes
  std::uint32_t size = 0;    ///< message size in bytes
  Phase phase = 0;           ///< the sender's phase tag
  /// Field-by-field equality.
  friend bool operator==(const TraceRecord&, const TraceRecord&) = default;
};

/// The trace: a running hash and, in `records` mode, the records.
class Trace {
public:
  /// An empty trace in the given mode.
  explicit Trace(TraceMode mode = TraceMode::off) : mode_(mode) {}
  /// The mode.
  TraceMode mode() const { return mode_; }
  /// Appends one record (no-op when off).
  void add(const TraceRecord& record);
  /// The stable hash of everything added so far (see the file comment).
  std::uint64_t hash() const { return hash_; }
  /// Number of records added (counted in every mode but off).
  std::uint64_t count() const { return count_; }
  /// The records (empty unless mode is records).
  std::span<const TraceRecord> records() const { return records_; }
  /// Writes the records as CSV with a header line: time_ns,from,to,phase,size,digest.
  void write_csv(std::ostream& out) const;
  /// Writes "LGTRACE1", the record count (uint64 LE), then the canonical encoding of each record.
  void write_binary(std::ostream& out) const;
  /// The canonical 38-byte encoding of one record.
  static std::array<std::byte, 38> encode(const TraceRecord& record);

private:
  TraceMode mode_;
  std::uint64_t hash_ = fnv1a_basis;
  std::uint64_t count_ = 0;
  std::vector<TraceRecord> records_;
};

}  // namespace laguerre::sim
