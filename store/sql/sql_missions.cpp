#include "store/sql/sql_missions.hpp"

#include <algorithm>

#include "store/sql/columns.hpp"

namespace avk::store::sql {

namespace {

constexpr auto kMission =
    columns("id", "vehicle_id", "name", "config_json", "status", "created_utc", "started_s",
            "ended_s", "status_reason", "runner_pid", "started_utc", "ended_utc", "station_id");

Mission read_mission(const Statement& s) {
  Mission m;
  m.id = s.column_int64(kMission["id"]);
  m.vehicle_id = s.column_text(kMission["vehicle_id"]);
  m.name = s.column_text(kMission["name"]);
  m.config_json = s.column_text(kMission["config_json"]);
  m.status = parse_stored("mission " + std::to_string(m.id), "status",
                          s.column_text(kMission["status"]), mission_status_from_string);
  m.created_utc = s.column_text(kMission["created_utc"]);
  m.started_s = s.column_optional_double(kMission["started_s"]);
  m.ended_s = s.column_optional_double(kMission["ended_s"]);
  m.status_reason = s.column_text(kMission["status_reason"]);
  m.runner_pid = s.column_optional_int64(kMission["runner_pid"]);
  if (!s.is_null(kMission["started_utc"])) m.started_utc = s.column_text(kMission["started_utc"]);
  if (!s.is_null(kMission["ended_utc"])) m.ended_utc = s.column_text(kMission["ended_utc"]);
  if (!s.is_null(kMission["station_id"])) m.station_id = s.column_text(kMission["station_id"]);
  return m;
}

constexpr auto kConditionSet = columns("start_s", "end_s", "target_speed_mps", "outcome");

ConditionSetTiming read_condition_set(const Statement& s) {
  return {s.column_double(kConditionSet["start_s"]), s.column_double(kConditionSet["end_s"]),
          s.column_double(kConditionSet["target_speed_mps"]),
          s.column_text(kConditionSet["outcome"])};
}

constexpr auto kEvent = columns("id", "mission_id", "t_s", "kind", "message");

MissionEvent read_event(const Statement& s) {
  return {s.column_int64(kEvent["id"]), s.column_int64(kEvent["mission_id"]),
          s.column_double(kEvent["t_s"]), s.column_text(kEvent["kind"]),
          s.column_text(kEvent["message"])};
}

}  // namespace

std::int64_t SqlMissions::create(const std::string& vehicle_id, const std::string& name,
                                 const std::string& config_json) {
  auto s = db_.prepare(
      "INSERT INTO missions (vehicle_id, name, config_json, status, station_id) "
      "VALUES (?, ?, ?, 'created', ?) RETURNING id");
  s.bind(1, vehicle_id).bind(2, name).bind(3, config_json);
  if (station_id_.empty())
    s.bind_null(4);
  else
    s.bind(4, station_id_);
  return inserted_id(s);
}

std::int64_t SqlMissions::insert(Database& db, const Mission& m) {
  auto s = db.prepare(
      "INSERT INTO missions (vehicle_id, name, config_json, status, created_utc, started_s, "
      "ended_s, status_reason) VALUES (?, ?, ?, ?, ?, ?, ?, ?) RETURNING id");
  s.bind(1, m.vehicle_id).bind(2, m.name).bind(3, m.config_json).bind(4, to_string(m.status));
  s.bind(5, m.created_utc).bind(6, m.started_s).bind(7, m.ended_s).bind(8, m.status_reason);
  return inserted_id(s);
}

void SqlMissions::expect_changed(std::int64_t mission_id) const {
  if (db_.changes() == 0) throw StoreError("no mission " + std::to_string(mission_id));
}

void SqlMissions::set_status(std::int64_t mission_id, MissionStatus status,
                             const std::string& reason, double t_s) {
  // Running again (a resume) has no end yet; an interruption ends the run that stopped, so the
  // mission's elapsed time is known until it is resumed.
  const bool starts = status == MissionStatus::running;
  const bool ends = status == MissionStatus::aborted || status == MissionStatus::halted ||
                    status == MissionStatus::done || status == MissionStatus::interrupted;
  const std::string now = db_.now_utc_sql();
  auto s = db_.prepare(
      "UPDATE missions SET status = ?1, status_reason = ?2, "
      "started_utc = CASE WHEN ?3 <> 0 AND started_s IS NULL THEN " +
      now +
      " ELSE started_utc END, "
      "started_s = CASE WHEN ?3 <> 0 AND started_s IS NULL THEN ?5 ELSE started_s END, "
      "ended_utc = CASE WHEN ?4 <> 0 THEN " +
      now +
      " WHEN ?3 <> 0 THEN NULL ELSE ended_utc END, "
      "ended_s = CASE WHEN ?4 <> 0 THEN ?5 WHEN ?3 <> 0 THEN NULL ELSE ended_s END WHERE id = ?6");
  s.bind(1, to_string(status)).bind(2, reason).bind(3, starts ? 1 : 0).bind(4, ends ? 1 : 0);
  s.bind(5, t_s).bind(6, mission_id);
  s.run();
  expect_changed(mission_id);
}

std::optional<Mission> SqlMissions::get(std::int64_t mission_id) {
  auto s = db_.prepare("SELECT " + kMission.list() + " FROM missions WHERE id = ?");
  s.bind(1, mission_id);
  if (!s.step()) return std::nullopt;
  return read_mission(s);
}

std::vector<Mission> SqlMissions::list() {
  auto s = db_.prepare("SELECT " + kMission.list() + " FROM missions ORDER BY id");
  std::vector<Mission> out;
  while (s.step())
    out.push_back(read_mission(s));
  return out;
}

void SqlMissions::close_orphaned(std::int64_t mission_id, const std::string& reason,
                                 std::optional<double> end_s) {
  auto s = db_.prepare(
      "UPDATE missions SET status = 'interrupted', status_reason = ?, ended_s = ?, "
      "ended_utc = NULL, runner_pid = NULL WHERE id = ?");
  s.bind(1, reason).bind(2, end_s).bind(3, mission_id);
  s.run();
  expect_changed(mission_id);
}

void SqlMissions::set_runner(std::int64_t mission_id, std::optional<std::int64_t> pid) {
  auto s = db_.prepare("UPDATE missions SET runner_pid = ? WHERE id = ?");
  s.bind(1, pid).bind(2, mission_id);
  s.run();
  expect_changed(mission_id);
}

void SqlMissions::append_condition_set(std::int64_t mission_id, const ConditionSetTiming& timing) {
  auto s = db_.prepare("INSERT INTO condition_sets (mission_id, " + kConditionSet.list() +
                       ") VALUES (?, " + kConditionSet.placeholders() + ")");
  // The mission is parameter 1; the list's columns follow it.
  s.bind(1, mission_id);
  s.bind(1 + kConditionSet.param("start_s"), timing.start_s);
  s.bind(1 + kConditionSet.param("end_s"), timing.end_s);
  s.bind(1 + kConditionSet.param("target_speed_mps"), timing.target_speed_mps);
  s.bind(1 + kConditionSet.param("outcome"), timing.outcome);
  s.run();
}

std::vector<ConditionSetTiming> SqlMissions::condition_sets(std::int64_t mission_id) {
  // id breaks ties between episodes that start at the same time: insertion order.
  auto s = db_.prepare("SELECT " + kConditionSet.list() +
                       " FROM condition_sets WHERE mission_id = ? ORDER BY start_s, id");
  s.bind(1, mission_id);
  std::vector<ConditionSetTiming> out;
  while (s.step())
    out.push_back(read_condition_set(s));
  return out;
}

std::int64_t SqlMissions::append_event(std::int64_t mission_id, double t_s, const std::string& kind,
                                       const std::string& message) {
  auto s = db_.prepare(
      "INSERT INTO mission_events (mission_id, t_s, kind, message) VALUES (?, ?, ?, ?) "
      "RETURNING id");
  s.bind(1, mission_id).bind(2, t_s).bind(3, kind).bind(4, message);
  return inserted_id(s);
}

std::vector<MissionEvent> SqlMissions::events(std::int64_t mission_id, std::int64_t after_id,
                                              int limit) {
  auto s = db_.prepare("SELECT " + kEvent.list() +
                       " FROM mission_events WHERE mission_id = ? AND id > ? ORDER BY id LIMIT ?");
  s.bind(1, mission_id).bind(2, after_id).bind(3, limit);
  std::vector<MissionEvent> out;
  while (s.step())
    out.push_back(read_event(s));
  return out;
}

std::optional<double> SqlMissions::clock_end_s(std::int64_t mission_id) {
  // The aggregate max skips the NULL of an empty source (the scalar max(a, b) would not), and
  // each inner max is one index probe for the large tables (nav, turns).
  auto s = db_.prepare(
      "SELECT max(t) FROM ("
      " SELECT max(t_s) AS t FROM nav_samples WHERE mission_id = ?1"
      " UNION ALL SELECT max(end_time_s) FROM turns WHERE mission_id = ?1"
      " UNION ALL SELECT max(t_s) FROM mission_events WHERE mission_id = ?1"
      " UNION ALL SELECT max(end_s) FROM condition_sets WHERE mission_id = ?1) AS recorded");
  s.bind(1, mission_id);
  s.step();
  return s.column_optional_double(0);
}

double SqlMissions::station_clock_end_s() {
  double end = 0.0;
  for (const auto& m : list())
    end = std::max(end, clock_end_s(m.id).value_or(0.0));
  return end;
}

std::map<std::int64_t, TurnCounts> SqlMissions::turn_counts() {
  auto s =
      db_.prepare("SELECT mission_id, status, count(*) FROM turns GROUP BY mission_id, status");
  std::map<std::int64_t, TurnCounts> out;
  while (s.step()) {
    const auto status = kinematics::turn_status_from_string(s.column_text(1));
    out[s.column_int64(0)].add(status.value_or(kinematics::TurnStatus::ok), s.column_int64(2));
  }
  return out;
}

std::vector<CellStats> SqlMissions::cell_stats(std::int64_t mission_id) {
  constexpr auto kCell = columns("cell_speed_mps", "cell_dheading_deg", "status", "advance_m",
                                 "transfer_m", "condition_set_time_s", "speed_after_mps");
  auto s = db_.prepare("SELECT " + kCell.list() +
                       " FROM turns WHERE mission_id = ? "
                       "ORDER BY cell_speed_mps, coalesce(speed_after_mps, -1), "
                       "cell_dheading_deg, id");
  s.bind(1, mission_id);
  std::vector<CellStats> out;
  std::vector<double> advances, transfers, condition_set_times;
  // The standard deviation needs every value, which SQL cannot aggregate; the rows arrive
  // grouped by cell, so each cell is closed when the next begins.
  const auto close_cell = [&] {
    if (out.empty()) return;
    CellStats& c = out.back();
    if (!advances.empty()) c.advance_m = kinematics::mean_sd(advances);
    if (!transfers.empty()) c.transfer_m = kinematics::mean_sd(transfers);
    if (!condition_set_times.empty())
      c.condition_set_time_s = kinematics::mean_sd(condition_set_times);
    advances.clear();
    transfers.clear();
    condition_set_times.clear();
  };
  while (s.step()) {
    const double speed = s.column_double(kCell["cell_speed_mps"]);
    const double dheading = s.column_double(kCell["cell_dheading_deg"]);
    const std::optional<double> speed_after = s.column_optional_double(kCell["speed_after_mps"]);
    if (out.empty() || out.back().speed_mps != speed || out.back().dheading_deg != dheading ||
        out.back().speed_after_mps != speed_after) {
      close_cell();
      out.push_back({});
      out.back().speed_mps = speed;
      out.back().dheading_deg = dheading;
      out.back().speed_after_mps = speed_after;
    }
    CellStats& c = out.back();
    const std::string status = s.column_text(kCell["status"]);
    if (status == "aborted") {
      ++c.n_aborted;
    } else if (status == "rejected") {
      ++c.n_rejected;
    } else {
      ++c.n_ok;
      if (auto v = s.column_optional_double(kCell["advance_m"])) advances.push_back(*v);
      if (auto v = s.column_optional_double(kCell["transfer_m"])) transfers.push_back(*v);
      if (auto v = s.column_optional_double(kCell["condition_set_time_s"]))
        condition_set_times.push_back(*v);
    }
  }
  close_cell();
  return out;
}

}  // namespace avk::store::sql
