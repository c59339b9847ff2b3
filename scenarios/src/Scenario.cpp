#include "laguerre/scenarios/Scenario.hpp"

namespace laguerre::scenarios {

std::string_view to_string(StopSpec stop) { return core::name_of(stop_spec_names, stop); }

std::string_view to_string(GeometricPositions positions) { return core::name_of(positions_names, positions); }

std::string scheme_name(core::Scheme scheme) { return std::string(core::name_of(scheme_names, scheme)); }

}  // namespace laguerre::scenarios
