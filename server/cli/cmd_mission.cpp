#include <ostream>

#include "mission/mission_config.hpp"
#include "server/cli/args.hpp"
#include "server/cli/commands.hpp"
#include "server/cli/files.hpp"
#include "sim/sim_config.hpp"

namespace avk::server {

int cmd_mission(const std::vector<std::string>& args, Io& io) {
  if (args.empty() || args[0] != "validate") {
    throw UsageError("expected 'mission validate --config FILE [--vehicle KIND]'");
  }
  const Args a({args.begin() + 1, args.end()}, {"config", "vehicle"});
  const std::string path = a.require("config");
  double max_speed = 0.0;
  try {
    max_speed = sim::default_sim_setup(a.get("vehicle").value_or("usim")).vehicle_max_speed_mps();
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--vehicle: ") + e.what());
  }
  try {
    const mission::MissionConfig c =
        mission::parse_mission_config(read_file(path, io.in), max_speed);
    io.out << path << ": mission '" << c.name << "' is valid";
    if (c.kind == mission::MissionKind::turns) {
      io.out << " ("
             << c.turn_array.speeds_mps.size() * c.turn_array.dheadings_deg.size() *
                    static_cast<std::size_t>(c.turn_array.repeats)
             << " turns)";
    }
    io.out << "\n";
    return 0;
  } catch (const mission::MissionConfigError& e) {
    for (const auto& f : e.errors())
      io.err << path << ": " << f.field << ": " << f.message << "\n";
    return 1;
  }
}

}  // namespace avk::server
