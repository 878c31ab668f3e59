#pragma once
// The options every `avk` command that drives an M200 shares: --m200 HOST:PORT, --datum LAT,LON,
// --pid thesis_sim|m200_in_water, --controller-hz, --vehicle-id.

#include <optional>
#include <string>

#include "server/cli/args.hpp"
#include "vehicle/local_grid.hpp"
#include "vehicle/m200.hpp"

namespace avk::server {

// "LAT,LON" in decimal degrees. Throws UsageError naming the option.
vehicle::LatLon parse_datum(const std::string& text, const std::string& option = "--datum");

// The driver options when --m200 is given, nullopt otherwise. Throws UsageError naming the
// option that is wrong.
std::optional<vehicle::M200Options> m200_options_from(const Args& a);

}  // namespace avk::server
