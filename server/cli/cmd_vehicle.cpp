// avk vehicle motion: what the station has learned of how a vehicle moves on a held heading.
#include <iomanip>
#include <nlohmann/json.hpp>
#include <ostream>

#include "app/context.hpp"
#include "app/vehicle_motion.hpp"
#include "server/cli/app_error.hpp"
#include "server/cli/args.hpp"
#include "server/cli/commands.hpp"
#include "server/cli/db_selection.hpp"
#include "server/serialize.hpp"

namespace avk::server {

void print_speed_reference(const kinematics::SpeedReferenceEvidence& e, std::ostream& out) {
  out << (e.identified ? kinematics::to_string(*e.identified) : "undetermined") << std::fixed
      << std::setprecision(3) << " (rms over ground " << e.rms_over_ground_mps
      << ", through the water " << e.rms_through_water_mps << ", separation " << e.separation_mps
      << " m/s over " << e.legs << " legs)";
}

void print_drift_scatter(const kinematics::DriftScatter& d, std::ostream& out) {
  out << std::fixed << std::setprecision(3) << "along " << d.along_mps << " m/s, across "
      << d.cross_mps << " m/s (" << d.legs << " legs of " << std::setprecision(1) << d.mean_leg_s
      << " s on average)";
}

namespace {

int motion(const std::vector<std::string>& rest, Io& io) {
  const Args a(rest, {"db", "vehicle", "format"});
  const std::string format = a.get("format").value_or("text");
  if (format != "text" && format != "json") throw UsageError("--format must be text or json");
  app::Context ctx(a.require("db"));
  const std::string vid = vehicle_of(a, ctx, {});
  const app::VehicleMotion m = value_or_fail(app::vehicle_motion(ctx, vid));
  if (format == "json") {
    io.out << vehicle_motion_json(m).dump() << "\n";
    return 0;
  }
  const app::MotionSpeedReference& r = m.speed_reference;
  io.out << "vehicle " << vid << "\nspeed reference: " << kinematics::to_string(r.value) << ", "
         << r.source;
  if (r.mission_id && r.evidence) {
    io.out << (r.source == "identified" ? " by mission " : "; mission ") << *r.mission_id << ": ";
    print_speed_reference(*r.evidence, io.out);
  }
  io.out << "\n  missions: " << r.missions_over_ground << " over ground, "
         << r.missions_through_water << " through the water, " << r.missions_undetermined
         << " undetermined\ndrift scatter (" << m.drift_scatter.source;
  if (m.drift_scatter.missions) io.out << ", " << m.drift_scatter.missions << " missions";
  io.out << "): ";
  print_drift_scatter(m.drift_scatter.scatter, io.out);
  io.out << "\n  a straight-line prediction's error grows as this rate times the time ahead\n"
         << "current: ";
  if (m.current) {
    print_current_estimate(m.current->estimate, io.out);
    io.out << ", mission " << m.current->mission_id << "\n";
  } else {
    io.out << "none told apart from still water\n";
  }
  return 0;
}

}  // namespace

int cmd_vehicle(const std::vector<std::string>& args, Io& io) {
  if (args.empty()) throw UsageError("expected 'vehicle motion'");
  const std::vector<std::string> rest(args.begin() + 1, args.end());
  if (args[0] == "motion") return motion(rest, io);
  throw UsageError("unknown subcommand 'vehicle " + args[0] + "'");
}

}  // namespace avk::server
