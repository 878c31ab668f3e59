#include "app/missions.hpp"

#include <algorithm>
#include <chrono>
#include <set>

#include "app/context.hpp"
#include "app/mission_liveness.hpp"
#include "app/mission_plans.hpp"
#include "app/mission_recorder.hpp"
#include "app/store_access.hpp"
#include "mission/turn_plan.hpp"

namespace avk::app {

namespace {

// How long a control request waits for the helm to apply it: the report then shows its effect.
constexpr std::chrono::milliseconds kCommandWait{2000};

store::TurnCounts totals_of(const std::vector<store::CellStats>& stats) {
  store::TurnCounts t;
  for (const auto& c : stats) {
    t.ok += c.n_ok;
    t.aborted += c.n_aborted;
    t.rejected += c.n_rejected;
  }
  return t;
}

// Planned cells of the mission's turn array, in plan order, with their repeat counts. An imported
// log has no turn array: none.
std::vector<CellReport> planned_cells(const store::Mission& m) {
  std::vector<CellReport> planned;
  mission::MissionConfig config;
  try {
    // Stored missions were validated against their vehicle when they started; the speed bound
    // is not re-checked here, so a report never fails on a vehicle that has changed since.
    config = mission::parse_mission_config(m.config_json, 1e9);
  } catch (const std::exception&) {
    return planned;
  }
  if (config.kind != mission::MissionKind::turns) return planned;
  for (const auto& t : mission::plan_turns(config)) {
    auto it = std::find_if(planned.begin(), planned.end(), [&](const CellReport& c) {
      return mission::same_cell(c.speed_mps, c.speed_after_mps, c.dheading_deg, t.speed_mps,
                                t.speed_after_mps, t.dheading_deg);
    });
    if (it == planned.end()) {
      CellReport c;
      c.speed_mps = t.speed_mps;
      c.speed_after_mps = t.speed_after_mps;
      c.dheading_deg = t.dheading_deg;
      it = planned.insert(planned.end(), c);
    }
    ++it->planned;
  }
  return planned;
}

CellReport* find_cell(std::vector<CellReport>& cells, double speed_mps,
                      std::optional<double> speed_after_mps, double dheading_deg) {
  for (auto& c : cells)
    if (mission::same_cell(c.speed_mps, c.speed_after_mps, c.dheading_deg, speed_mps,
                           speed_after_mps, dheading_deg))
      return &c;
  return nullptr;
}

MissionSummary summary_of(const store::Mission& m, const store::TurnCounts& turns) {
  MissionSummary s;
  s.status = view_of(effective_status(m));
  s.turns = view_of(turns);
  s.mission = view_of(m);
  return s;
}

}  // namespace

Result<mission::MissionConfig> validate_mission(const std::string& config_text,
                                                double max_speed_mps) {
  try {
    return mission::parse_mission_config(config_text, max_speed_mps);
  } catch (const mission::MissionConfigError& e) {
    return mission_config_error(e);
  }
}

std::vector<CellReport> cell_reports(const std::vector<mission::CellProgress>& cells) {
  std::vector<CellReport> out;
  out.reserve(cells.size());
  for (const auto& p : cells) {
    CellReport c;
    c.speed_mps = p.speed_mps;
    c.speed_after_mps = p.speed_after_mps;
    c.dheading_deg = p.dheading_deg;
    c.planned = p.planned;
    c.ok = p.ok;
    c.aborted = p.aborted;
    c.rejected = p.rejected;
    c.given_up = p.given_up;
    c.running = p.running;
    out.push_back(c);
  }
  return out;
}

std::string status_text(const MissionReport& r) {
  if (r.live) return r.live_state ? mission::to_string(*r.live_state) : "created";
  return to_string(r.summary.status);
}

std::vector<MissionSummary> list_missions(Context& ctx,
                                          const std::optional<std::string>& vehicle_id) {
  store::Store& db = store_of(ctx);
  const auto counts = db.missions().turn_counts();
  std::vector<MissionSummary> out;
  for (auto& m : db.missions().list()) {
    if (vehicle_id && m.vehicle_id != *vehicle_id) continue;
    const auto it = counts.find(m.id);
    out.push_back(summary_of(m, it == counts.end() ? store::TurnCounts{} : it->second));
  }
  return out;
}

Result<MissionSummary> mission_summary(Context& ctx, std::int64_t mission_id) {
  auto m = store_of(ctx).missions().get(mission_id);
  if (!m) return not_found("no mission " + std::to_string(mission_id));
  return summary_of(*m, totals_of(store_of(ctx).missions().cell_stats(mission_id)));
}

Result<MissionReport> mission_report(Context& ctx, std::int64_t mission_id) {
  store::Store& db = store_of(ctx);
  auto m = db.missions().get(mission_id);
  if (!m) return not_found("no mission " + std::to_string(mission_id));
  MissionReport r;
  const auto stats = db.missions().cell_stats(mission_id);
  VehicleLoop* loop = ctx.vehicle_loop(m->vehicle_id);
  const auto live = loop ? loop->live(mission_id) : std::nullopt;
  if (live && loop->attached_mission() == mission_id) {
    // State, helm and cells from one live snapshot: the store may be a step ahead or behind.
    r.live = true;
    r.live_state = live->state;
    r.helm_mode = live->helm_mode;
    r.cells = cell_reports(live->cells);
    r.running_turn = live->turn;
  } else {
    r.cells = planned_cells(*m);
  }
  for (const auto& s : stats) {
    CellReport* c = find_cell(r.cells, s.speed_mps, s.speed_after_mps, s.dheading_deg);
    if (!c) {
      CellReport extra;
      extra.speed_mps = s.speed_mps;
      extra.speed_after_mps = s.speed_after_mps;
      extra.dheading_deg = s.dheading_deg;
      r.cells.push_back(extra);
      c = &r.cells.back();
    }
    if (!r.live) {
      c->ok = s.n_ok;
      c->aborted = s.n_aborted;
      c->rejected = s.n_rejected;
    }
    c->advance_m = s.advance_m;
    c->transfer_m = s.transfer_m;
    c->condition_set_time_s = s.condition_set_time_s;
  }
  std::vector<double> set;
  for (const auto& cs : db.missions().condition_sets(mission_id)) {
    ++r.condition_set_episodes[cs.outcome];
    if (cs.outcome == "set") set.push_back(cs.duration_s());
  }
  r.condition_set_count = set.size();
  if (!set.empty()) r.condition_set_time_s = kinematics::mean_sd(set);
  if (m->started_s && m->ended_s) r.duration_s = *m->ended_s - *m->started_s;
  store::TurnFilter filter;
  filter.mission_id = mission_id;
  filter.limit = 1000;
  for (;;) {
    auto page = db.turns().list(filter);
    const bool last = static_cast<int>(page.size()) < filter.limit;
    if (!page.empty()) filter.after_id = page.back().id;
    for (const auto& t : page)
      r.turns.push_back(view_of(t));
    if (last) break;
  }
  r.summary = summary_of(*m, totals_of(stats));
  return r;
}

Result<std::int64_t> start_mission(Context& ctx, const std::string& vehicle_id,
                                   const std::string& config_text) {
  VehicleLoop* loop = ctx.vehicle_loop(vehicle_id);
  if (!loop) return conflict("vehicle '" + vehicle_id + "' is not connected to this station");
  if (const auto busy = loop->attached_mission())
    return conflict("mission " + std::to_string(*busy) + " is running", *busy);
  auto plan = create_mission_plan(ctx, config_text, loop->info());
  if (!plan) return plan.error();
  const std::int64_t id = plan->mission_id;
  if (!loop->attach(std::move(*plan))) {
    store_of(ctx).missions().set_status(id, store::MissionStatus::aborted,
                                        "another mission started first", 0.0);
    return conflict("another mission is running");
  }
  return id;
}

const char* to_string(MissionCommand c) {
  switch (c) {
    case MissionCommand::pause:
      return "pause";
    case MissionCommand::resume:
      return "resume";
    case MissionCommand::abort:
      return "abort";
  }
  return "pause";
}

Result<std::string> vehicle_of_missions(Context& ctx,
                                        const std::vector<std::int64_t>& mission_ids) {
  store::Store& db = store_of(ctx);
  for (const auto id : mission_ids)
    if (!db.missions().get(id)) return not_found("no mission " + std::to_string(id));
  std::set<std::string> vehicles;
  for (const auto& m : db.missions().list()) {
    if (mission_ids.empty() || std::ranges::find(mission_ids, m.id) != mission_ids.end())
      vehicles.insert(m.vehicle_id);
  }
  if (vehicles.empty()) return not_found("the database holds no missions");
  if (vehicles.size() > 1) {
    std::string names;
    for (const auto& v : vehicles)
      names += (names.empty() ? "" : ", ") + v;
    return invalid_argument("vehicle",
                            "the missions are of several vehicles (" + names + "): choose one");
  }
  return *vehicles.begin();
}

double station_clock_start_s(Context& ctx) {
  return store_of(ctx).missions().station_clock_end_s() + 1.0;
}

Result<MissionReport> command_mission(Context& ctx, std::int64_t mission_id, MissionCommand c) {
  store::Store& db = store_of(ctx);
  const auto m = db.missions().get(mission_id);
  if (!m) return not_found("no mission " + std::to_string(mission_id));
  VehicleLoop* loop = ctx.vehicle_loop(m->vehicle_id);
  if (loop && loop->attached_mission() == mission_id) {
    const auto command = c == MissionCommand::pause    ? VehicleLoop::Command::pause
                         : c == MissionCommand::resume ? VehicleLoop::Command::resume
                                                       : VehicleLoop::Command::abort;
    loop->command(mission_id, command);
    loop->wait_for_tick(kCommandWait);
    return mission_report(ctx, mission_id);
  }
  if (c != MissionCommand::resume)
    return conflict("mission " + std::to_string(mission_id) + " is not running (" +
                    store::to_string(effective_status(*m)) + ")");
  if (!loop) return conflict("vehicle '" + m->vehicle_id + "' is not connected to this station");
  if (const auto busy = loop->attached_mission())
    return conflict("mission " + std::to_string(*busy) + " is running", *busy);
  auto plan = resume_mission_plan(ctx, mission_id, loop->info().max_speed_mps);
  if (!plan) return plan.error();
  if (!loop->attach(std::move(*plan))) return conflict("another mission is running");
  loop->wait_for_tick(kCommandWait);
  return mission_report(ctx, mission_id);
}

namespace {

// A keyset page of a mission's rows: read(after, limit) gives them, cursor(row) is a row's key.
template <class T, class Read, class Cursor>
Result<Page<T>> mission_page(Context& ctx, std::int64_t mission_id, int limit, Read read,
                             Cursor cursor) {
  if (limit < 1) return invalid_argument("limit", "must be at least 1");
  if (!store_of(ctx).missions().get(mission_id))
    return not_found("no mission " + std::to_string(mission_id));
  return make_page<T>(read(), limit, cursor);
}

}  // namespace

Result<Page<MissionEventView>> mission_events(Context& ctx, std::int64_t mission_id,
                                              std::int64_t after, int limit) {
  return mission_page<MissionEventView>(
      ctx, mission_id, limit,
      [&] { return views_of(store_of(ctx).missions().events(mission_id, after, limit)); },
      [](const MissionEventView& e) { return e.id; });
}

Result<Page<TrackPoint>> mission_track(Context& ctx, std::int64_t mission_id, std::int64_t after,
                                       int limit) {
  return mission_page<TrackPoint>(
      ctx, mission_id, limit,
      [&] { return views_of(store_of(ctx).navigation().page(mission_id, after, limit)); },
      [](const TrackPoint& r) { return r.rowid; });
}

Result<TrackPoint> mission_last_position(Context& ctx, std::int64_t mission_id) {
  store::Store& db = store_of(ctx);
  if (!db.missions().get(mission_id)) return not_found("no mission " + std::to_string(mission_id));
  const auto last = db.navigation().last(mission_id);
  if (!last) return not_found("mission " + std::to_string(mission_id) + " recorded no navigation");
  return view_of(*last);
}

}  // namespace avk::app
