#pragma once
// The simulator options every `avk` command that runs a simulated vehicle shares:
// --vehicle, --sim-config, --ticks, --seed, --jitter.

#include <nlohmann/json.hpp>
#include <string>

#include "server/cli/args.hpp"
#include "server/cli/commands.hpp"
#include "server/serialize.hpp"
#include "sim/sim_config.hpp"

namespace avk::server {

// --vehicle (default_kind when absent), --sim-config, --ticks, --seed, --jitter. Throws
// UsageError naming the option.
sim::SimSetup sim_setup_from(const Args& a, Io& io, const std::string& default_kind = "usim");

// --realtime-factor K (default 1): the clock of a paced simulator, an emulator or a driver runs
// at K x the wall clock. Throws UsageError outside (0, 10000].
double realtime_factor_from(const Args& a);

}  // namespace avk::server
