#include <charconv>
#include <cmath>
#include <iomanip>
#include <ostream>

#include "kinematics/turn_measures.hpp"
#include "server/cli/args.hpp"
#include "server/cli/commands.hpp"
#include "server/cli/files.hpp"
#include "server/cli/sim_options.hpp"
#include "server/serialize/sim.hpp"
#include "sim/sim_config.hpp"
#include "sim/turn_scenario.hpp"
#include "sim/variability.hpp"

namespace avk::server {

namespace {

sim::TurnScenarioConfig scenario_from(const Args& a, const sim::SimSetup& setup) {
  sim::TurnScenarioConfig c;
  c.vehicle = setup.vehicle;
  c.scheduler = setup.scheduler;
  c.helm_hz = setup.helm_hz;
  const auto speed = a.number("speed");
  const auto dheading = a.number("dheading");
  if (!speed) throw UsageError("missing required option --speed (m/s)");
  if (!dheading) throw UsageError("missing required option --dheading (deg, + right, - left)");
  if (!(*speed > 0.0)) throw UsageError("--speed must be positive (m/s)");
  if (*speed > setup.vehicle_max_speed_mps()) {
    throw UsageError("--speed " + num(*speed) + " m/s is above the vehicle's maximum " +
                     num(setup.vehicle_max_speed_mps()) + " m/s");
  }
  if (!(std::abs(*dheading) > 0.0 && std::abs(*dheading) <= 180.0)) {
    throw UsageError("--dheading must be in [-180, 0) or (0, 180] degrees");
  }
  c.speed_mps = *speed;
  c.dheading_deg = *dheading;
  if (const auto th = a.number("threshold")) {
    if (!(*th > 0.0 && *th < 90.0)) throw UsageError("--threshold must be in (0, 90) degrees");
    c.completion.threshold_deg = *th;
  }
  return c;
}

int sim_turn(const std::vector<std::string>& rest, Io& io) {
  const Args a(rest,
               {"vehicle", "speed", "dheading", "seed", "ticks", "csv", "sim-config", "threshold",
                "realtime-factor"},
               {"jitter", "realtime"});
  const sim::SimSetup setup = sim_setup_from(a, io);
  const sim::TurnScenarioConfig c = scenario_from(a, setup);
  sim::TurnScenarioResult r;
  if (a.flag("realtime")) {
    sim::RealtimePacer pacer(realtime_factor_from(a));
    r = sim::run_turn_scenario(c, pacer);
  } else {
    r = sim::run_turn_scenario(c);
  }
  const std::string csv = sim_turn_csv(r);
  if (const auto path = a.get("csv"); path && *path != "-") {
    write_file_atomic(*path, csv);
  } else {
    io.out << csv;
  }
  io.err << "sim turn: " << vehicle::to_string(setup.vehicle.kind) << ", " << num(c.speed_mps)
         << " m/s, " << num(c.dheading_deg) << " deg, commanded at t=" << num(r.command_time_s)
         << " s, " << (r.completed ? "completed" : "NOT completed");
  if (r.turn.samples().size() >= 2) {
    const auto at = kinematics::advance_transfer(r.turn);
    io.err << " after " << num(r.turn.samples().back().t_s - r.command_time_s) << " s; advance "
           << num(at.advance_m) << " m, transfer " << num(at.transfer_m) << " m";
  }
  io.err << "\n";
  return r.completed ? 0 : 1;
}

int sim_variability(const std::vector<std::string>& rest, Io& io) {
  const Args a(
      rest, {"vehicle", "speed", "dheading", "seed", "ticks", "sim-config", "repeats", "threshold"},
      {"jitter", "sweep-ticks"});
  sim::SimSetup setup = sim_setup_from(a, io);
  sim::VariabilityConfig vc;
  vc.base = scenario_from(a, setup);
  vc.jitter = a.flag("jitter");
  vc.jitter_fraction = setup.scheduler.jitter_fraction > 0 ? setup.scheduler.jitter_fraction : 0.05;
  vc.first_seed = setup.scheduler.seed;
  const double repeats = a.number("repeats").value_or(77);
  if (!(repeats >= 1 && repeats <= 100000) || std::floor(repeats) != repeats) {
    throw UsageError("--repeats must be a whole number from 1 to 100000");
  }
  vc.repeats = static_cast<int>(repeats);
  if (!a.flag("sweep-ticks")) {
    io.out << variability_csv(sim::run_variability(vc));
    return 0;
  }
  // Thesis Figure 5-1: vary the AppTick of the plant and the helm together, 1..10 Hz.
  std::vector<TickSweepRow> rows;
  for (int hz = 1; hz <= 10; ++hz) {
    sim::VariabilityConfig swept = vc;
    swept.base.vehicle.plant_hz = hz;
    swept.base.helm_hz = hz;
    rows.push_back({hz, vc.repeats, sim::run_variability(swept)});
  }
  io.out << tick_sweep_csv(rows);
  return 0;
}

}  // namespace

int cmd_sim(const std::vector<std::string>& args, Io& io) {
  if (args.empty()) throw UsageError("expected 'sim turn' or 'sim variability'");
  const std::vector<std::string> rest(args.begin() + 1, args.end());
  if (args[0] == "turn") return sim_turn(rest, io);
  if (args[0] == "variability") return sim_variability(rest, io);
  throw UsageError("unknown subcommand 'sim " + args[0] + "'");
}

}  // namespace avk::server
