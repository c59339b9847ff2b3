// Fuzz harness: metric field specifications (core/meshing/MetricField.hpp, parse_metric_field).
// `mesh:FILE` specifications are skipped (they name files; the Medit reader is not this harness's
// subject). On success the field's value at a few points is a metric or a FieldError, and its
// description parses back to a field of the same value (bit for bit for uniform fields, to 1e-9 for the
// others, whose descriptions have 12 digits).
#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

#include "FuzzTarget.hpp"
#include "laguerre/core/Error.hpp"
#include "laguerre/core/geometry/Predicates.hpp"
#include "laguerre/core/meshing/MetricField.hpp"

namespace {

namespace core = laguerre::core;

std::unique_ptr<core::MetricField> parse(const std::string& spec) {
  std::unique_ptr<core::MetricField> field;
  if (!laguerre::fuzz::parses<core::FieldError, core::InputError, std::invalid_argument>(
          [&] { field = core::parse_metric_field(spec); }))
    return nullptr;
  return field;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string spec(laguerre::fuzz::as_text(data, size));
  if (spec.rfind("mesh", 0) == 0) return 0;
  const std::unique_ptr<core::MetricField> field = parse(spec);
  if (!field) return 0;
  for (const core::Point2 p : {core::Point2{0.0, 0.0}, {0.5, 0.5}, {1.0, 0.25}, {-3.0, 7.0}}) {
    core::Metric m;
    if (laguerre::fuzz::parses<core::FieldError>([&] { m = field->at(p.x, p.y); }))
      LAGUERRE_FUZZ_CHECK(core::is_metric(m));
  }
  const std::string description = field->describe();
  const std::unique_ptr<core::MetricField> again = parse(description);
  if (!again) laguerre::fuzz::fail("the description '" + description + "' of '" + spec + "' does not parse");
  // Not `again->describe() == description` for every field: shock and thesis fields print their
  // parameters with 12 digits, so the fields must agree to that precision instead.
  core::Metric m, n;
  if (laguerre::fuzz::parses<core::FieldError>([&] { m = field->at(0.5, 0.5); }) &&
      laguerre::fuzz::parses<core::FieldError>([&] { n = again->at(0.5, 0.5); }) && core::is_metric(m)) {
    const double scale = std::max(std::abs(m.a), std::abs(m.c));
    const double tolerance = spec.rfind("uniform", 0) == 0 ? 0 : 1e-9 * scale;
    if (!(std::abs(m.a - n.a) <= tolerance && std::abs(m.b - n.b) <= tolerance && std::abs(m.c - n.c) <= tolerance))
      laguerre::fuzz::fail("'" + spec + "' and its description '" + description + "' differ at (0.5, 0.5)");
  }
  return 0;
}
