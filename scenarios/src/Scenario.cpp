#include "laguerre/scenarios/Scenario.hpp"

namespace laguerre::scenarios {

std::string_view to_string(StopSpec stop) {
  switch (stop) {
    case StopSpec::lpd: return "lpd";
    case StopSpec::glpd: return "glpd";
    case StopSpec::exact: return "exact";
  }
  return "?";
}

std::string_view to_string(GeometricPositions positions) {
  switch (positions) {
    case GeometricPositions::automatic: return "auto";
    case GeometricPositions::packing: return "packing";
    case GeometricPositions::physical: return "physical";
  }
  return "?";
}

std::string scheme_name(core::Scheme scheme) {
  std::string s(core::to_string(scheme));
  for (char& c : s)
    if (c == '_') c = '-';
  return s;
}

}  // namespace laguerre::scenarios
