#pragma once
// The options every `avk` command that drives an M200 shares: --m200 HOST:PORT, --datum LAT,LON,
// --pid thesis_sim|m200_in_water, --controller-hz, --vehicle-id.

#include <optional>
#include <string>

#include "server/cli/args.hpp"
#include "vehicle/local_grid.hpp"
#include "vehicle/m200.hpp"

namespace avk::server {

// --datum LAT,LON in decimal degrees, when given. Throws UsageError naming the option.
std::optional<vehicle::LatLon> datum_from(const Args& a);

// The yaw controller preset by name (thesis_sim, m200_in_water); none for another name.
std::optional<vehicle::MarinePidConfig> pid_preset(const std::string& name);

// The driver options when --m200 is given, nullopt otherwise. Throws UsageError naming the
// option that is wrong.
std::optional<vehicle::M200Options> m200_options_from(const Args& a);

}  // namespace avk::server
