// avk current estimate|show: the current a mission flew in, from its steady legs.
#include <iomanip>
#include <ostream>

#include "app/context.hpp"
#include "app/current.hpp"
#include "app/current_compensation.hpp"
#include "server/cli/app_error.hpp"
#include "server/cli/args.hpp"
#include "server/cli/commands.hpp"
#include "server/cli/db_selection.hpp"
#include "server/serialize.hpp"

namespace avk::server {

namespace {

std::string format_of(const Args& a) {
  const std::string f = a.get("format").value_or("text");
  if (f != "text" && f != "json") throw UsageError("--format must be text or json");
  return f;
}

int estimate(const std::vector<std::string>& rest, Io& io) {
  const Args a(rest, {"db", "mission", "format", "leg", "from"}, {"store"});
  const std::string from = a.get("from").value_or("legs");
  if (from != "legs" && from != "turns") throw UsageError("--from must be legs or turns");
  if (from == "turns" && a.flag("store"))
    throw UsageError("--store keeps the steady-leg estimate; --from turns is its check");
  const std::string format = format_of(a);
  const std::int64_t id = parse_id(a.require("mission"), "--mission");
  const double leg_s = a.number("leg").value_or(app::kSteadyLegS);
  if (!(leg_s >= app::kMinSteadyLegS && leg_s <= 120.0))
    throw UsageError("--leg must be within 3..120 s");
  app::Context ctx(a.require("db"));
  app::MissionCurrent c;
  std::optional<app::CurrentView> stored;
  std::optional<app::AppliedCurrent> applied;
  if (a.flag("store")) {
    applied = value_or_fail(app::apply_mission_current(ctx, id, leg_s));
    c = applied->current;
    stored = applied->stored;
  } else if (from == "turns") {
    c = value_or_fail(app::estimate_mission_current_from_turns(ctx, id));
  } else {
    c = value_or_fail(app::estimate_mission_current(ctx, id, leg_s));
    stored = value_or_fail(app::stored_mission_current(ctx, id));
  }
  if (format == "json") {
    io.out << (applied ? applied_current_json(*applied) : mission_current_json(c, stored)).dump()
           << "\n";
    return c.result.estimate ? 0 : 1;
  }
  if (from == "turns")
    io.out << "mission " << id << ": " << c.legs_used << " of " << c.turns
           << " turns against the table of the vehicle's other missions\n";
  else
    io.out << "mission " << id << ": " << c.legs_used << " steady legs before " << c.turns
           << " turns\n";
  if (!c.result.estimate) {
    io.out << "no estimate: " << c.result.why_not << "\n";
    return 1;
  }
  io.out << "current ";
  print_current_estimate(*c.result.estimate, io.out);
  io.out << "\n"
         << (app::current_is_significant(*c.result.estimate)
                 ? "told apart from still water\n"
                 : "not told apart from still water: the turns stay over ground\n");
  if (from == "legs") {
    io.out << c.motion_legs << " steady stretches: the speed loop holds ";
    if (c.speed_reference)
      print_speed_reference(*c.speed_reference, io.out);
    else
      io.out << "(not judged)";
    io.out << "\ndrift scatter: ";
    if (c.drift_scatter)
      print_drift_scatter(*c.drift_scatter, io.out);
    else
      io.out << "fewer than 3 steady stretches";
    io.out << "\n";
  }
  if (applied) io.out << "stored; " << applied->water_turns << " turns in the water frame\n";
  return 0;
}

// The table of some missions predicting the turns of others, with and without the current.
int compare(const std::vector<std::string>& rest, Io& io) {
  const Args a(rest, {"db", "vehicle", "format"}, {}, {"mission", "test-mission"});
  const std::string format = format_of(a);
  app::Context ctx(a.require("db"));
  const std::vector<std::int64_t> table = mission_ids(a);
  std::vector<std::int64_t> test;
  for (const std::string& s : a.all("test-mission"))
    test.push_back(parse_id(s, "--test-mission"));
  if (table.empty() || test.empty())
    throw UsageError(
        "name the table's missions (--mission) and the test missions (--test-mission)");
  const std::string vid = vehicle_of(a, ctx, table);
  const app::CompensationComparison c =
      value_or_fail(app::compare_current_compensation(ctx, vid, table, test));
  if (format == "json") {
    io.out << compensation_comparison_json(vid, c).dump() << "\n";
    return 0;
  }
  io.out << "table: " << c.table_turns << " turns (" << c.table_water_turns
         << " in the water frame); test: " << c.turns.size() << " turns";
  if (c.turns_outside_table) io.out << " (" << c.turns_outside_table << " outside the table)";
  io.out << "\n";
  for (const auto& [mission, e] : c.test_currents) {
    io.out << "test mission " << mission << " current ";
    print_current_estimate(e, io.out);
    io.out << "\n";
  }
  io.out << std::fixed << std::setprecision(2) << "path error (mean distance at equal clock "
         << "stations): uncompensated " << c.uncompensated_mean_m << " m, compensated "
         << c.compensated_mean_m << " m (" << std::setprecision(0) << 100.0 * c.improvement()
         << " % less)\n";
  return 0;
}

int show(const std::vector<std::string>& rest, Io& io) {
  const Args a(rest, {"db", "vehicle", "format"});
  const std::string format = format_of(a);
  app::Context ctx(a.require("db"));
  const std::string vid = vehicle_of(a, ctx, {});
  const app::CurrentView c = value_or_fail(app::vehicle_current(ctx, vid));
  if (format == "json") {
    io.out << current_json(vid, c).dump() << "\n";
    return 0;
  }
  io.out << "vehicle " << vid << ", mission " << c.mission_id << " at " << std::fixed
         << std::setprecision(1) << c.t_s << " s: ";
  print_current_estimate(c.estimate, io.out);
  io.out << "\n";
  return 0;
}

}  // namespace

void print_current_estimate(const kinematics::CurrentEstimate& e, std::ostream& out) {
  out << std::fixed << std::setprecision(3) << e.speed_mps() << " ± " << e.speed_sd_mps()
      << " m/s toward " << std::setprecision(1) << e.toward_deg() << " ± " << e.toward_sd_deg()
      << "° (east " << std::setprecision(3) << e.east_mps << ", north " << e.north_mps << " m/s; "
      << e.legs << " pieces of evidence, residual " << e.residual_rms_mps << " m/s)";
}

int cmd_current(const std::vector<std::string>& args, Io& io) {
  if (args.empty())
    throw UsageError("expected 'current estimate', 'current show' or 'current compare'");
  const std::vector<std::string> rest(args.begin() + 1, args.end());
  if (args[0] == "estimate") return estimate(rest, io);
  if (args[0] == "show") return show(rest, io);
  if (args[0] == "compare") return compare(rest, io);
  throw UsageError("unknown subcommand 'current " + args[0] + "'");
}

}  // namespace avk::server
