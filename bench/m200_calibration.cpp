// The M200 calibration figures (docs/sim-config.md, "The vehicle kinds and where their parameters
// come from"): how catamaran:heron (the plant catamaran:m200 used to be, "before") and the
// waterjet catamaran:m200 ("after") turn on calm water, next to the thesis' in-water evidence:
// the instantaneous-turn MSE at 1 m/s, 70° computed the thesis' way (§5.2, Figure 5-7: 16.8 m²),
// the time spent establishing initial conditions (Table 5.2: means 3.8–7.6 s) and turns of
// Δψ ≤ 90° lasting tens of seconds (line 654: ~30 s for avoidance maneuvers).
//
// A printout, not a timed benchmark: every figure is simulated time or distance, and the program
// takes the time it takes. The same figures with examples/sim-choppy.json follow for information.
//
// Options, for calibrating: --calm-only, and overrides of the M200's calibrated numbers
// (--nr-per-speed N·m·s per m/s, --jet-lag s, --jet-reverse fraction) applied to catamaran:m200.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "kinematics/angles.hpp"
#include "kinematics/ckt.hpp"
#include "kinematics/turn_measures.hpp"
#include "kinematics/turn_metrics.hpp"
#include "mission/mission_config.hpp"
#include "mission/mission_observer.hpp"
#include "mission/mission_runner.hpp"
#include "mission/turn_plan.hpp"
#include "sim/scheduler.hpp"
#include "sim/sim_config.hpp"
#include "sim/sim_mission.hpp"
#include "sim/sim_vehicle.hpp"

namespace {

using avk::kinematics::angle180_deg;

// Overrides of the M200's calibrated numbers from the command line; empty: the built-in ones.
struct Overrides {
  std::optional<double> nr_per_speed, jet_lag_s, jet_reverse_fraction, yaw_ki, yaw_integral_limit;
} g_overrides;
bool g_print_events = false;  // --events: every mission event, for diagnosis

void apply_overrides(avk::sim::SimSetup& s) {
  if (s.vehicle.kind != avk::vehicle::VehicleKind::catamaran_m200 || !s.vehicle.catamaran) return;
  if (g_overrides.yaw_ki) s.vehicle.pid.yaw.ki = *g_overrides.yaw_ki;
  if (g_overrides.yaw_integral_limit)
    s.vehicle.pid.yaw.integral_limit = *g_overrides.yaw_integral_limit;
  auto& p = *s.vehicle.catamaran;
  if (g_overrides.nr_per_speed) p.nr_per_speed = *g_overrides.nr_per_speed;
  if (g_overrides.jet_lag_s) p.lag_s = *g_overrides.jet_lag_s;
  if (g_overrides.jet_reverse_fraction) p.jet_reverse_fraction = *g_overrides.jet_reverse_fraction;
}

std::string example(const std::string& name) {
  std::ifstream f(std::string(AVK_SOURCE_DIR) + "/examples/" + name);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

void replace_all(std::string& text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at)) {
    text.replace(at, from.size(), to);
    at += to.size();
  }
}

// The setup of a kind on calm water, or with examples/sim-choppy.json (whose vehicle is swapped
// for the kind, so "before" is the Heron plant with the example's other settings).
avk::sim::SimSetup setup_for(const std::string& kind, bool choppy, std::uint64_t seed) {
  avk::sim::SimSetup s;
  if (choppy) {
    std::string text = example("sim-choppy.json");
    replace_all(text, "\"catamaran:m200\"", "\"" + kind + "\"");
    s = avk::sim::parse_sim_config(text, kind);
  } else {
    s = avk::sim::default_sim_setup(kind);
  }
  s.scheduler.seed = seed;
  apply_overrides(s);
  return s;
}

struct StepResponse {
  double peak_yaw_rate_dps = 0.0;
  double t90_s = NAN;          // to 90 % of the commanded change
  double overshoot_deg = 0.0;  // beyond the goal, 0 when none
  double duration_s = NAN;     // to within 5° of the goal (the missions' completion threshold)
  double settled_s = NAN;      // from then on within 2° of the goal: the whole maneuver
  double min_speed_mps = INFINITY, max_speed_mps = 0.0;  // after the command
};

// Holds course 0 at speed_mps until steady, then commands a change of dheading_deg, all on
// ground truth of a noise-free navigation so the figures are the plant's and controller's, not
// the sensors'. The helm runs at the setup's rate.
StepResponse step_response(const std::string& kind, bool choppy, double speed_mps,
                           double dheading_deg) {
  avk::sim::SimSetup setup = setup_for(kind, choppy, 1);
  setup.vehicle.sensors.gnss_sigma_m = 0.0;
  setup.vehicle.sensors.compass_sigma_deg = 0.0;
  setup.vehicle.seed = 1;
  avk::sim::Scheduler scheduler(setup.scheduler);
  avk::sim::SimVehicle v(setup.vehicle, scheduler);
  constexpr double kSettle_s = 60.0, kAfter_s = 120.0;
  double goal = 0.0, heading0 = 0.0;
  StepResponse r;
  double max_change = -1e9, last_outside_s = 0.0;
  scheduler.add("helm", setup.helm_hz, [&](double now) {
    const auto t = v.truth();
    if (now < kSettle_s) {
      heading0 = t.heading_deg;
      goal = 0.0;
    } else {
      if (goal == 0.0) goal = dheading_deg;
      const double change = angle180_deg(t.heading_deg - heading0);
      r.peak_yaw_rate_dps = std::max(r.peak_yaw_rate_dps, std::abs(t.yaw_rate_dps));
      if (std::isnan(r.t90_s) && change >= 0.9 * dheading_deg) r.t90_s = now - kSettle_s;
      if (std::isnan(r.duration_s) && std::abs(dheading_deg - change) <= 5.0) {
        r.duration_s = now - kSettle_s;
      }
      max_change = std::max(max_change, change);
      r.min_speed_mps = std::min(r.min_speed_mps, t.speed_over_ground_mps);
      r.max_speed_mps = std::max(r.max_speed_mps, t.speed_over_ground_mps);
      if (std::abs(dheading_deg - change) > 2.0) last_outside_s = now - kSettle_s;
    }
    v.command({now, avk::kinematics::wrap360_deg(heading0 + goal), speed_mps});
  });
  scheduler.run_until(kSettle_s + kAfter_s);
  r.overshoot_deg = std::max(0.0, max_change - dheading_deg);
  // Still outside 2° near the end of the run: not settled.
  if (last_outside_s < kAfter_s - 10.0) r.settled_s = last_outside_s;
  return r;
}

// Every turn and ConditionSet episode a mission ends, and how long it took.
struct Collector final : avk::mission::MissionObserver {
  std::vector<avk::mission::TurnOutcome> turns;
  int interrupted = 0, timeouts = 0, turn_backs = 0;
  void on_turn(avk::mission::TurnOutcome& t) override { turns.push_back(t); }
  void on_condition_set(const avk::mission::ConditionSetEpisode& e) override {
    if (e.outcome == avk::mission::ConditionSetEpisode::Outcome::interrupted) ++interrupted;
    if (e.outcome == avk::mission::ConditionSetEpisode::Outcome::timeout) ++timeouts;
  }
  void on_event(const avk::mission::MissionEventRecord& e) override {
    if (g_print_events)
      std::printf("      %.1f %s %s\n", e.t_s, std::string(avk::mission::to_string(e.kind)).c_str(),
                  e.message.c_str());
    if (e.kind == avk::mission::EventKind::turning_back) ++turn_backs;
  }
};

struct MissionRun {
  Collector c;
  double duration_s = 0.0;
  bool done = false;
};

MissionRun run_mission(const std::string& kind, bool choppy, std::uint64_t seed,
                       const std::string& text) {
  const avk::sim::SimSetup setup = setup_for(kind, choppy, seed);
  const auto config = avk::mission::parse_mission_config(text, setup.vehicle_max_speed_mps());
  avk::sim::SimMissionOptions so;
  so.setup = setup;
  so.start = {config.region.return_point.x_m, config.region.return_point.y_m, 0.0};
  avk::sim::SimMission sim(so);
  avk::mission::MissionRunner runner(config, sim.vehicle(), avk::mission::plan_turns(config),
                                     {"calibration", std::to_string(seed)});
  MissionRun out;
  runner.add_observer(out.c);
  avk::sim::FastPacer pacer;
  const auto r = sim.run(runner, pacer);
  out.duration_s = r.end_time_s - r.start_time_s;
  out.done = runner.state() == avk::mission::MissionState::done;
  if (!out.done) {
    std::printf("  (%s seed %llu: mission ended %s)\n", kind.c_str(),
                static_cast<unsigned long long>(seed),
                runner.state() ? avk::mission::to_string(*runner.state()) : "never started");
  }
  return out;
}

struct MeanSd {
  double mean = NAN, sd = NAN;
  std::size_t n = 0;
};

MeanSd mean_sd(const std::vector<double>& v) {
  MeanSd m;
  m.n = v.size();
  if (v.empty()) return m;
  double s = 0.0;
  for (double x : v)
    s += x;
  m.mean = s / static_cast<double>(v.size());
  double q = 0.0;
  for (double x : v)
    q += (x - m.mean) * (x - m.mean);
  m.sd = v.size() > 1 ? std::sqrt(q / static_cast<double>(v.size() - 1)) : 0.0;
  return m;
}

// The thesis' Figure 4-1 mission with a speed tolerance, under the mission's steady-course rule
// (least-squares yaw rate, heading within 2° of the held course) or the thesis' own (eq. 4.2's
// moving average of five differenced headings, no heading test).
std::string figure41(double speed_tolerance_mps, bool thesis_rule) {
  std::string text = example("thesis-fig4-1.json");
  char cs[256];
  std::snprintf(
      cs, sizeof cs, "\"speed_tolerance_mps\": %.2f%s", speed_tolerance_mps,
      thesis_rule ? ", \"yaw_rate\": \"moving_average\", \"max_heading_error_deg\": 180" : "");
  replace_all(text, "\"speed_tolerance_mps\": 0.1", cs);
  return text;
}

// One cell repeated: `repeats` turns of 70° at 1 m/s, alternating sides, in Figure 4-1's region.
std::string seventy_degree_cell(int repeats) {
  return R"({"name": "calibration-70", "kind": "turns",
    "turn_array": {"speeds_mps": [1.0], "dheadings_deg": [70], "direction": "alternate",
                   "repeats": )" +
         std::to_string(repeats) + R"(},
    "condition_set": {"speed_tolerance_mps": 0.1, "max_yaw_rate_dps": 1.0, "window": 5},
    "constant_heading": {"completion_threshold_deg": 5},
    "operating_region": {"polygon_m": [[-100, -100], [100, -100], [100, 100], [-100, 100]],
                         "buffer_m": 25, "return_point_m": [0, -70]}})";
}

void report(const std::string& label, const std::string& kind, bool choppy) {
  std::printf("\n== %s: %s, %s ==\n", label.c_str(), kind.c_str(),
              choppy ? "examples/sim-choppy.json" : "calm water");
  std::printf("  step response to a 90 deg change (noise-free navigation)\n");
  std::printf(
      "    speed   peak yaw rate   t to 90 %%   overshoot   speed range after the command\n");
  for (double u : {0.5, 1.0, 1.5}) {
    const StepResponse r = step_response(kind, choppy, u, 90.0);
    std::printf("    %.1f m/s  %6.1f deg/s    %6.2f s    %5.1f deg   %.2f-%.2f m/s\n", u,
                r.peak_yaw_rate_dps, r.t90_s, r.overshoot_deg, r.min_speed_mps, r.max_speed_mps);
  }
  std::printf(
      "  turn duration: command to within 5 deg of the goal (completion) / to staying "
      "within 2 deg (settled)\n");
  std::printf("    speed         40 deg          70 deg          90 deg\n");
  for (double u : {0.5, 1.0, 1.5}) {
    std::printf("    %.1f m/s", u);
    for (double d : {40.0, 70.0, 90.0}) {
      const StepResponse r = step_response(kind, choppy, u, d);
      // Not settled within the run (a wind that holds the heading off): shown as "  -  ".
      if (std::isnan(r.settled_s)) {
        std::printf("   %5.1f /   -   s", r.duration_s);
      } else {
        std::printf("   %5.1f / %5.1f s", r.duration_s, r.settled_s);
      }
    }
    std::printf("\n");
  }

  // The thesis' Figure 5-7 figure: the cell's turns from several missions (seeds).
  std::vector<avk::kinematics::Polyline> turns;
  std::vector<double> advance, transfer, duration;
  for (std::uint64_t seed = 1; seed <= 2; ++seed) {
    for (const auto& t : run_mission(kind, choppy, seed, seventy_degree_cell(4)).c.turns) {
      if (t.status != avk::kinematics::TurnStatus::ok) continue;
      const auto n = t.raw.normalized();
      turns.push_back(n.points());
      const auto at = avk::kinematics::advance_transfer(n);
      advance.push_back(at.advance_m);
      transfer.push_back(at.transfer_m);
      duration.push_back(t.raw.meta().end_time_s - t.raw.meta().start_time_s);
    }
  }
  const MeanSd a = mean_sd(advance), tr = mean_sd(transfer), d = mean_sd(duration);
  std::printf(
      "  70 deg, 1 m/s, %zu recorded turns: advance %.2f ± %.2f m, transfer %.2f ± %.2f m,"
      " recorded duration %.1f ± %.1f s\n",
      a.n, a.mean, a.sd, tr.mean, tr.sd, d.mean, d.sd);
  if (turns.size() >= 2) {
    const auto e = avk::kinematics::cell_errors(turns, 70.0);
    std::printf(
        "  instantaneous-turn MSE vs the cell's mean turn (thesis way): %.2f m^2 "
        "(thesis in water 16.8 m^2, target 12.6-21.0); AVK spread %.3f m^2\n",
        e.instantaneous_mse_m2, e.avk_error_m2);
  }

  std::printf(
      "  Figure 4-1, seeds 1-5: ConditionSet time per turn (thesis Table 5.2: means 3.8-7.6 s, "
      "sd 3.9-7.6 s), mission time (target calm <= 1200 s, choppy <= 1500 s), interrupted "
      "conditioning episodes (target <= 5 a mission)\n");
  for (const bool thesis_rule : {true, false}) {
    for (double tol : {0.1, 0.2}) {
      std::vector<double> cs, duration;
      std::size_t ok = 0, total = 0;
      int interrupted_max = 0, timeouts = 0, turn_backs = 0, not_done = 0;
      for (std::uint64_t seed = 1; seed <= 5; ++seed) {
        const MissionRun m = run_mission(kind, choppy, seed, figure41(tol, thesis_rule));
        for (const auto& t : m.c.turns) {
          ++total;
          if (t.status == avk::kinematics::TurnStatus::ok) ++ok;
          if (t.condition_set_time_s) cs.push_back(*t.condition_set_time_s);
        }
        duration.push_back(m.duration_s);
        interrupted_max = std::max(interrupted_max, m.c.interrupted);
        timeouts += m.c.timeouts;
        turn_backs += m.c.turn_backs;
        not_done += m.done ? 0 : 1;
      }
      const MeanSd m = mean_sd(cs);
      std::printf(
          "    %s rule, tolerance %.1f m/s: ConditionSet %.2f ± %.2f s over %zu turns (%zu/%zu "
          "ok); mission %.0f-%.0f s; interrupted <= %d a mission; %d timeouts, %d turn-backs in "
          "all%s\n",
          thesis_rule ? "thesis " : "mission", tol, m.mean, m.sd, m.n, ok, total,
          *std::min_element(duration.begin(), duration.end()),
          *std::max_element(duration.begin(), duration.end()), interrupted_max, timeouts,
          turn_backs, not_done ? " (a mission not done)" : "");
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  bool calm_only = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    if (a == "--calm-only") {
      calm_only = true;
    } else if (a == "--nr-per-speed" && has_value) {
      g_overrides.nr_per_speed = std::stod(argv[++i]);
    } else if (a == "--jet-lag" && has_value) {
      g_overrides.jet_lag_s = std::stod(argv[++i]);
    } else if (a == "--jet-reverse" && has_value) {
      g_overrides.jet_reverse_fraction = std::stod(argv[++i]);
    } else if (a == "--events") {
      g_print_events = true;
    } else if (a == "--yaw-ki" && has_value) {
      g_overrides.yaw_ki = std::stod(argv[++i]);
    } else if (a == "--yaw-integral-limit" && has_value) {
      g_overrides.yaw_integral_limit = std::stod(argv[++i]);
    } else {
      std::fprintf(stderr,
                   "usage: bench_m200_calibration [--calm-only] [--nr-per-speed N] [--jet-lag S] "
                   "[--jet-reverse F] [--yaw-ki K] [--yaw-integral-limit L] [--events]\n");
      return 2;
    }
  }
  std::printf("M200 calibration: catamaran:heron (before) and catamaran:m200 (after)\n");
  report("before", "catamaran:heron", false);
  report("after", "catamaran:m200", false);
  if (!calm_only) {
    report("before", "catamaran:heron", true);
    report("after", "catamaran:m200", true);
  }
  return 0;
}
