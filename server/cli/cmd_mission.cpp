#include <cerrno>
#include <chrono>
#include <csignal>
#include <fstream>
#include <iomanip>
#include <map>
#include <ostream>
#include <sstream>
#include <thread>

#include "app/context.hpp"
#include "app/mission_plans.hpp"
#include "app/mission_run.hpp"
#include "app/missions.hpp"
#include "kinematics/angles.hpp"
#include "mission/mission_config.hpp"
#include "mission/mission_runner.hpp"
#include "mission/turn_plan.hpp"
#include "server/cli/app_error.hpp"
#include "server/cli/args.hpp"
#include "server/cli/commands.hpp"
#include "server/cli/db_selection.hpp"
#include "server/cli/files.hpp"
#include "server/cli/m200_options.hpp"
#include "server/cli/sim_options.hpp"
#include "server/cli/station_options.hpp"
#include "server/serialize.hpp"
#include "sim/sim_config.hpp"
#include "vehicle/vehicle_kind.hpp"

namespace avk::server {

namespace {

std::atomic<bool> g_stop{false};
extern "C" void on_stop_signal(int) {
  g_stop.store(true);
}

// SIGINT/SIGTERM ask the running mission to stop at its next helm tick (stored as interrupted,
// resumable) instead of killing the process mid-write.
class StopSignals {
 public:
  StopSignals() {
    g_stop.store(false);
    previous_int_ = std::signal(SIGINT, on_stop_signal);
    previous_term_ = std::signal(SIGTERM, on_stop_signal);
  }
  ~StopSignals() {
    std::signal(SIGINT, previous_int_);
    std::signal(SIGTERM, previous_term_);
  }

 private:
  void (*previous_int_)(int);
  void (*previous_term_)(int);
};

// A heading change with its side: + right, - left.
std::string signed_goal(double goal_deg) {
  std::string out = goal_deg > 0 ? "+" : "";
  out += fixed(goal_deg, 0);
  return out;
}

std::string signed_deg(const mission::TurnTask& t, const kinematics::TurnSequence& raw) {
  const double d =
      raw.meta().goal_dheading_deg != 0.0 ? raw.meta().goal_dheading_deg : t.dheading_deg;
  return signed_goal(d) + " deg";
}

// One line per turn and the events an operator must read.
class ProgressPrinter final : public mission::MissionObserver {
 public:
  ProgressPrinter(std::ostream& out, bool quiet) : out_(out), quiet_(quiet) {}

  // The run's plan: the turns of the whole mission, and those done before this run.
  void start(int planned, int done_before) {
    planned_ = planned;
    ok_ = done_before;
  }

  void on_turn(mission::TurnOutcome& t) override {
    if (t.status == kinematics::TurnStatus::ok) ++ok_;
    if (quiet_) return;
    const std::string count = t.status == kinematics::TurnStatus::ok
                                  ? std::to_string(ok_) + "/" + std::to_string(planned_)
                                  : "-";
    out_ << "turn " << std::setw(7) << count << "  " << fixed(t.task.speed_mps, 2) << " m/s "
         << std::setw(9) << signed_deg(t.task, t.raw) << "  " << std::left << std::setw(8)
         << kinematics::to_string(t.status) << std::right;
    if (t.status == kinematics::TurnStatus::ok) {
      out_ << " advance " << fixed(*t.advance_m, 2) << " m, transfer " << fixed(*t.transfer_m, 2)
           << " m";
    } else {
      out_ << " " << t.reason << (t.requeued ? " (re-queued)" : t.given_up ? " (given up)" : "");
    }
    if (t.condition_set_time_s)
      out_ << ", conditions set in " << fixed(*t.condition_set_time_s, 1) << " s";
    if (t.start_heading_error_deg && t.start_yaw_rate_dps)
      out_ << " (" << fixed(*t.start_heading_error_deg, 1) << "° off course, "
           << fixed(*t.start_yaw_rate_dps, 2) << " °/s)";
    // One numbering of turns (the mission's k/N); the database id is named as what it is.
    out_ << "  [t=" << fixed(t.raw.meta().end_time_s, 1) << " s";
    if (t.stored_id) out_ << ", id " << *t.stored_id;
    out_ << "]" << std::endl;  // flushed: an operator may be watching a pipe or a log file
  }

  void on_event(const mission::MissionEventRecord& e) override {
    if (quiet_ || !shown(e.kind)) return;
    out_ << "  " << mission::to_string(e.kind) << " at t=" << fixed(e.t_s, 1) << " s: " << e.message
         << std::endl;
  }

 private:
  // The warnings, less those a turn line already reports and the containment a turn mission
  // passes through after most turns; and the return leg, the sign that the mission is ending.
  static bool shown(mission::EventKind k) {
    switch (k) {
      case mission::EventKind::turn_aborted:
      case mission::EventKind::turn_rejected:
      case mission::EventKind::containment:
        return false;
      case mission::EventKind::returning:
        return true;
      default:
        return mission::severity(k) == mission::Severity::warning;
    }
  }

  std::ostream& out_;
  int planned_ = 0;
  int ok_ = 0;
  bool quiet_;
};

// The vehicle the options name: --m200 HOST:PORT for a real M200, the simulator (--vehicle,
// --sim-config, ...) otherwise, with default_kind when --vehicle is not given.
app::VehicleSourceOptions vehicle_from(const Args& a, Io& io, const std::string& default_kind) {
  app::VehicleSourceOptions v;
  v.m200 = m200_options_from(a);
  if (v.m200) {
    v.kind = vehicle::VehicleKind::m200;
    v.realtime_factor = realtime_factor_from(a);
  } else {
    v.setup = sim_setup_from(a, io, default_kind);
    v.realtime = a.flag("realtime");
    v.realtime_factor = v.realtime ? realtime_factor_from(a) : 1.0;
  }
  return v;
}

app::MissionRunOptions run_options(const Args& a, Io& io, ProgressPrinter& printer) {
  app::MissionRunOptions options;
  if (const auto limit = a.number("max-sim-time")) {
    if (!(*limit > 0.0)) throw UsageError("--max-sim-time must be positive (s)");
    options.max_duration_s = *limit;
  }
  options.observers.push_back(&printer);
  options.stop = &g_stop;
  options.on_connecting = [&io](const std::string& what) {
    io.out << "connecting to " << what << std::endl;
  };
  options.on_start = [&io, &printer](const app::MissionPlan& plan, int planned) {
    printer.start(planned, plan.done_before);
    io.out << "mission " << plan.mission_id << " '" << plan.config.name
           << "': " << plan.tasks.size() << " turns to do"
           << (plan.done_before ? " (" + std::to_string(plan.done_before) + " done before)" : "")
           << "\n";
  };
  return options;
}

void print_config_errors(const app::Error& e, const std::string& name, Io& io);

// Runs (or resumes) through the use case and prints its outcome; the exit code.
int execute(const std::function<app::Result<app::MissionRunOutcome>()>& run,
            const std::string& what, Io& io) {
  app::Result<app::MissionRunOutcome> result = app::internal_error("not run");
  {
    StopSignals signals;
    result = run();
  }
  if (!result) {
    // A vehicle the options cannot give (a mission of another kind) is a mistake of the options.
    if (result.error().code == app::ErrorCode::invalid_argument &&
        result.error().field == "vehicle")
      throw UsageError(result.error().message);
    if (!result.error().fields.empty()) {
      print_config_errors(result.error(), what, io);
      return 1;
    }
    value_or_fail(std::move(result));
  }
  const app::MissionRunOutcome& r = *result;
  const app::MissionView& m = r.summary.mission;
  const double run_s = r.end_time_s - r.start_time_s;
  io.out << "mission " << m.id << " " << app::to_string(m.status);
  if (!m.status_reason.empty()) io.out << " (" << m.status_reason << ")";
  io.out << ": " << r.summary.turns.ok << "/" << r.planned << " turns ok, "
         << r.summary.turns.aborted << " aborted, " << r.summary.turns.rejected << " rejected";
  if (r.turns_given_up) io.out << ", " << r.turns_given_up << " given up";
  io.out << "; " << r.turns_finished << " turns finished this run";
  io.out << "; " << (r.simulated ? "simulated " : "ran ") << fixed(run_s, 1) << " s in "
         << fixed(r.wall_s, 3) << " s of wall time (" << fixed(run_s / std::max(r.wall_s, 1e-9), 0)
         << "x)\n";
  if (!r.link_report.empty()) io.out << r.link_report << "\n";
  if (r.stopped) return 130;
  return m.status == app::MissionStatus::done ? 0 : 1;
}

void print_config_errors(const app::Error& e, const std::string& name, Io& io) {
  for (const auto& f : e.fields)
    io.err << name << ": " << f.field << ": " << f.message << "\n";
  if (e.fields.empty()) io.err << name << ": " << e.message << "\n";
}

void require_vehicle(const Args& a) {
  if (a.flag("sim") == a.get("m200").has_value()) {
    throw UsageError(
        "give the vehicle: --sim runs the simulator, --m200 HOST:PORT drives an M200 (one of "
        "them)");
  }
}

const std::set<std::string> kRunValues = {
    "config",          "db",         "vehicle",      "sim-config", "ticks", "seed",
    "realtime-factor", "vehicle-id", "max-sim-time", "m200",       "datum", "pid",
    "controller-hz",   "station-id", "spool"};
const std::set<std::string> kRunFlags = {"sim", "realtime", "jitter", "quiet"};

int run(const std::vector<std::string>& rest, Io& io) {
  const Args a(rest, kRunValues, kRunFlags);
  require_vehicle(a);
  const std::string path = a.require("config");
  const std::string db_path = a.require("db");
  app::VehicleSourceOptions vehicle = vehicle_from(a, io, "usim");
  if (!vehicle.m200) {
    vehicle.setup.vehicle.id =
        vehicle_id_option(a, std::string("sim-") + vehicle::to_string(vehicle.setup.vehicle.kind));
  }
  const std::string text = read_file(path, io.in);
  apply_station_options(a);
  app::Context ctx(db_path);
  ProgressPrinter printer(io.out, a.flag("quiet"));
  const app::MissionRunOptions options = run_options(a, io, printer);
  return execute([&] { return app::run_new_mission(ctx, text, vehicle, options); }, path, io);
}

std::int64_t mission_id_arg(const Args& a) {
  if (a.positional().size() != 1) throw UsageError("expected one mission id");
  return parse_id(a.positional()[0], "the mission id");
}

int resume(const std::vector<std::string>& rest, Io& io) {
  const Args a(rest, kRunValues, kRunFlags);
  require_vehicle(a);
  apply_station_options(a);
  app::Context ctx(a.require("db"));
  const std::int64_t id = mission_id_arg(a);
  // A simulated mission resumes on the simulator of its own kind unless --vehicle names one.
  const app::MissionSummary s = value_or_fail(app::mission_summary(ctx, id));
  const app::VehicleStatus stored = value_or_fail(app::get_vehicle(ctx, s.mission.vehicle_id));
  const auto stored_kind = vehicle::vehicle_kind_from_string(stored.info.kind);
  const bool simulated_kind = stored_kind && vehicle::is_simulated(*stored_kind);
  const app::VehicleSourceOptions vehicle =
      vehicle_from(a, io, simulated_kind ? stored.info.kind : "usim");
  ProgressPrinter printer(io.out, a.flag("quiet"));
  const app::MissionRunOptions options = run_options(a, io, printer);
  return execute([&] { return app::resume_mission_run(ctx, id, vehicle, options); },
                 "mission " + std::to_string(id), io);
}

int list(const std::vector<std::string>& rest, Io& io) {
  const Args a(rest, {"db", "format"});
  app::Context ctx(a.require("db"));
  const std::string format = a.get("format").value_or("table");
  if (format != "table" && format != "json" && format != "csv")
    throw UsageError("--format must be table, json or csv");
  const auto missions = app::list_missions(ctx, std::nullopt);
  if (format == "csv") {
    io.out << missions_csv(missions);
    return 0;
  }
  if (format == "json") {
    io.out << missions_json(missions).dump() << "\n";
    return 0;
  }
  io.out << std::left << std::setw(5) << "id" << std::setw(13) << "status" << std::setw(22)
         << "vehicle" << std::setw(12) << "turns ok" << std::setw(26) << "created (UTC)"
         << "name\n";
  for (const auto& s : missions)
    io.out << std::setw(5) << s.mission.id << std::setw(13) << app::to_string(s.status)
           << std::setw(22) << s.mission.vehicle_id << std::setw(12) << s.turns.ok << std::setw(26)
           << s.mission.created_utc << s.mission.name << "\n";
  io.out << std::right;
  return 0;
}

// A mean of one value has no spread to show: "± 0.00" would claim one.
std::string pm(const std::optional<kinematics::MeanSd>& v, int decimals, std::int64_t n = 2) {
  if (!v) return "-";
  return n == 1 ? fixed(v->mean, decimals)
                : fixed(v->mean, decimals) + " ± " + fixed(v->sd, decimals);
}

// A stored turn as `mission run` prints it live, for `mission wait`.
void print_stored_turn(std::ostream& out, const app::TurnView& t, int ok, int planned) {
  const bool done = t.status == kinematics::TurnStatus::ok;
  const std::string count = done ? std::to_string(ok) + "/" + std::to_string(planned) : "-";
  out << "turn " << std::setw(7) << count << "  " << fixed(t.commanded_speed_mps, 2) << " m/s "
      << std::setw(9) << signed_goal(t.goal_dheading_deg) + " deg"
      << "  " << std::left << std::setw(8) << kinematics::to_string(t.status) << std::right;
  if (done && t.advance_m && t.transfer_m)
    out << " advance " << fixed(*t.advance_m, 2) << " m, transfer " << fixed(*t.transfer_m, 2)
        << " m";
  else if (!done)
    out << " " << t.reason;
  out << "  [t=" << fixed(t.end_time_s, 1) << " s, id " << t.id << "]" << std::endl;
}

int report(const std::vector<std::string>& rest, Io& io) {
  const Args a(rest, {"db", "format"});
  app::Context ctx(a.require("db"));
  const std::string format = a.get("format").value_or("table");
  if (format != "table" && format != "json" && format != "csv")
    throw UsageError("--format must be table, json or csv");
  const app::MissionReport r = value_or_fail(app::mission_report(ctx, mission_id_arg(a)));
  if (format == "csv") {
    io.out << report_cells_csv(r);
    return 0;
  }
  if (format == "json") {
    io.out << report_json(r, false).dump(2) << "\n";
    return 0;
  }
  const app::MissionView& m = r.summary.mission;
  io.out << "mission " << m.id << " '" << m.name << "' on " << m.vehicle_id << ": "
         << app::status_text(r);
  if (!m.status_reason.empty()) io.out << " (" << m.status_reason << ")";
  io.out << "\n";
  if (r.duration_s) io.out << "mission time " << fixed(*r.duration_s, 1) << " s\n";
  const auto& t = r.summary.turns;
  const auto episodes = [&](const char* outcome) {
    const auto it = r.condition_set_episodes.find(outcome);
    return it == r.condition_set_episodes.end() ? 0 : it->second;
  };
  io.out << "turns: " << t.ok << " ok, " << t.aborted << " aborted, " << t.rejected
         << " rejected\n";
  io.out << "time to set conditions (thesis Table 5.2): " << pm(r.condition_set_time_s, 2)
         << " s over " << r.condition_set_count << " turn starts; " << episodes("timeout")
         << " timeouts, " << episodes("interrupted") << " interrupted\n\n";
  io.out << std::setw(9) << "speed" << std::setw(10) << "dheading" << std::setw(9) << "planned"
         << std::setw(5) << "ok" << std::setw(9) << "aborted" << std::setw(10) << "rejected"
         << std::setw(18) << "advance m" << std::setw(18) << "transfer m" << std::setw(18)
         << "conditions s"
         << "\n";
  for (const auto& c : r.cells)
    io.out << std::setw(9) << fixed(c.speed_mps, 2) << std::setw(10) << fixed(c.dheading_deg, 0)
           << std::setw(9) << c.planned << std::setw(5) << c.ok << std::setw(9) << c.aborted
           << std::setw(10) << c.rejected << std::setw(18) << pm(c.advance_m, 2, c.ok)
           << std::setw(18) << pm(c.transfer_m, 2, c.ok) << std::setw(18)
           << pm(c.condition_set_time_s, 2, c.ok) << "\n";
  if (r.turns.empty()) return 0;
  // How steady each turn began: a turn started in the middle of a swing shows here.
  const auto opt = [](const std::optional<double>& v, int digits) {
    return v ? fixed(*v, digits) : std::string("-");
  };
  io.out << "\n"
         << std::setw(7) << "id" << std::setw(9) << "speed" << std::setw(10) << "goal"
         << std::setw(10) << "status" << std::setw(14) << "conditions s" << std::setw(18)
         << "start heading err" << std::setw(16) << "start yaw rate"
         << "\n";
  for (const auto& t : r.turns)
    io.out << std::setw(7) << t.id << std::setw(9) << fixed(t.commanded_speed_mps, 2)
           << std::setw(10) << signed_goal(t.goal_dheading_deg) << std::setw(10)
           << kinematics::to_string(t.status) << std::setw(14) << opt(t.condition_set_time_s, 1)
           << std::setw(16) << opt(t.start_heading_error_deg, 2) << " °" << std::setw(12)
           << opt(t.start_yaw_rate_dps, 2) << " °/s\n";
  return 0;
}

// Follows a mission another process runs (avk serve): each turn as it is stored, then how the
// mission ended. Reads the database only, so it works beside a running server.
int wait(const std::vector<std::string>& rest, Io& io) {
  const Args a(rest, {"db", "poll"});
  app::Context ctx(a.require("db"));
  const double poll_s = a.number("poll").value_or(1.0);
  if (!(poll_s >= 0.1 && poll_s <= 60.0)) throw UsageError("--poll must be in [0.1, 60] seconds");
  const std::int64_t id = mission_id_arg(a);
  std::int64_t last_turn = 0;
  int ok = 0;
  for (;;) {
    const app::MissionReport r = value_or_fail(app::mission_report(ctx, id));
    int planned = 0;
    for (const auto& c : r.cells)
      planned += static_cast<int>(c.planned);
    for (const auto& t : r.turns) {
      if (t.id <= last_turn) continue;
      last_turn = t.id;
      if (t.status == kinematics::TurnStatus::ok) ++ok;
      print_stored_turn(io.out, t, ok, planned);
    }
    const auto status = r.summary.status;
    if (status != app::MissionStatus::running && status != app::MissionStatus::paused &&
        status != app::MissionStatus::created) {
      const app::MissionView& m = r.summary.mission;
      io.out << "mission " << m.id << " '" << m.name << "' finished: " << app::status_text(r);
      if (!m.status_reason.empty()) io.out << " (" << m.status_reason << ")";
      io.out << "; " << r.summary.turns.ok << "/" << planned << " turns ok, "
             << r.summary.turns.aborted << " aborted, " << r.summary.turns.rejected << " rejected"
             << std::endl;
      return status == app::MissionStatus::done ? 0 : 1;
    }
    std::this_thread::sleep_for(std::chrono::duration<double>(poll_s));
  }
}

int validate(const std::vector<std::string>& rest, Io& io) {
  const Args a(rest, {"config", "vehicle"});
  const std::string path = a.require("config");
  double max_speed = 0.0;
  try {
    max_speed = sim::default_sim_setup(a.get("vehicle").value_or("usim")).vehicle_max_speed_mps();
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--vehicle: ") + e.what());
  }
  const auto checked = app::validate_mission(read_file(path, io.in), max_speed);
  if (!checked) {
    print_config_errors(checked.error(), path, io);
    return 1;
  }
  const mission::MissionConfig& c = *checked;
  io.out << path << ": mission '" << c.name << "' is valid";
  if (c.kind == mission::MissionKind::turns)
    io.out << " (" << mission::plan_turns(c).size() << " turns)";
  io.out << "\n";
  return 0;
}

}  // namespace

int cmd_mission(const std::vector<std::string>& args, Io& io) {
  if (args.empty())
    throw UsageError("expected 'mission validate|run|resume|list|report|wait|export'");
  const std::vector<std::string> rest(args.begin() + 1, args.end());
  if (args[0] == "validate") return validate(rest, io);
  if (args[0] == "run") return run(rest, io);
  if (args[0] == "resume") return resume(rest, io);
  if (args[0] == "list") return list(rest, io);
  if (args[0] == "report") return report(rest, io);
  if (args[0] == "wait") return wait(rest, io);
  if (args[0] == "export") return mission_export(rest, io);
  throw UsageError("unknown subcommand 'mission " + args[0] + "'");
}

}  // namespace avk::server
