#include "store/sql/sql_turns.hpp"

#include <cmath>
#include <exception>
#include <utility>

#include <nlohmann/json.hpp>

#include "kinematics/turn_json.hpp"
#include "kinematics/turn_measures.hpp"
#include "store/sql/columns.hpp"

namespace avk::store::sql {

namespace {

// The summary columns of a turn (TurnRow), then its documents.
// The id is the database's: an insert leaves it out and reads it back.
constexpr auto kTurnFields = columns(
    "mission_id", "vehicle_id", "cell_speed_mps", "cell_dheading_deg", "status", "reason",
    "commanded_speed_mps", "goal_dheading_deg", "observed_dheading_deg", "start_time_s",
    "end_time_s", "advance_m", "transfer_m", "condition_set_time_s", "start_heading_error_deg",
    "start_yaw_rate_dps", "source", "quality", "speed_after_mps", "record_key");
constexpr auto kTurnRow = columns("id") + kTurnFields;
constexpr auto kTurnDocuments = columns("raw_json", "normalized_json");
constexpr auto kTurnPacked = columns("normalized_meta_json", "normalized_samples");
constexpr auto kTurnRead = kTurnRow + kTurnDocuments;
constexpr auto kTurnWrite = kTurnFields + kTurnDocuments + kTurnPacked;

TurnRow read_turn_row(const Statement& s) {
  TurnRow r;
  r.id = s.column_int64(kTurnRow["id"]);
  r.mission_id = s.column_int64(kTurnRow["mission_id"]);
  r.vehicle_id = s.column_text(kTurnRow["vehicle_id"]);
  r.cell_speed_mps = s.column_double(kTurnRow["cell_speed_mps"]);
  r.cell_dheading_deg = s.column_double(kTurnRow["cell_dheading_deg"]);
  const std::string row = "turn " + std::to_string(r.id);
  r.status = parse_stored(row, "status", s.column_text(kTurnRow["status"]),
                          kinematics::turn_status_from_string);
  r.reason = s.column_text(kTurnRow["reason"]);
  r.commanded_speed_mps = s.column_double(kTurnRow["commanded_speed_mps"]);
  r.goal_dheading_deg = s.column_double(kTurnRow["goal_dheading_deg"]);
  r.observed_dheading_deg = s.column_double(kTurnRow["observed_dheading_deg"]);
  r.start_time_s = s.column_double(kTurnRow["start_time_s"]);
  r.end_time_s = s.column_double(kTurnRow["end_time_s"]);
  r.advance_m = s.column_optional_double(kTurnRow["advance_m"]);
  r.transfer_m = s.column_optional_double(kTurnRow["transfer_m"]);
  r.condition_set_time_s = s.column_optional_double(kTurnRow["condition_set_time_s"]);
  r.start_heading_error_deg = s.column_optional_double(kTurnRow["start_heading_error_deg"]);
  r.start_yaw_rate_dps = s.column_optional_double(kTurnRow["start_yaw_rate_dps"]);
  r.source = parse_stored(row, "source", s.column_text(kTurnRow["source"]),
                          kinematics::turn_source_from_string);
  r.quality = s.column_optional_double(kTurnRow["quality"]);
  r.speed_after_mps = s.column_optional_double(kTurnRow["speed_after_mps"]);
  if (!s.is_null(kTurnRow["record_key"])) r.record_key = s.column_text(kTurnRow["record_key"]);
  return r;
}

// What add stores of a turn whose status and reason are already in its metadata.
TurnRow row_of(const kinematics::TurnSequence& turn, const TurnStart& start) {
  const auto& m = turn.meta();
  TurnRow row;
  row.vehicle_id = m.vehicle_id;
  row.cell_speed_mps = m.commanded_speed_mps;
  row.cell_dheading_deg = std::abs(m.goal_dheading_deg);
  row.status = m.status;
  row.reason = m.status_reason;
  row.commanded_speed_mps = m.commanded_speed_mps;
  row.goal_dheading_deg = m.goal_dheading_deg;
  row.observed_dheading_deg = m.observed_dheading_deg;
  row.start_time_s = m.start_time_s;
  row.end_time_s = m.end_time_s;
  row.condition_set_time_s = start.condition_set_time_s;
  row.start_heading_error_deg = start.heading_error_deg;
  row.start_yaw_rate_dps = start.yaw_rate_dps;
  row.source = m.source;
  row.quality = m.quality;
  row.speed_after_mps = m.speed_after_mps;
  return row;
}

}  // namespace

std::int64_t insert_turn(Database& db, std::int64_t mission_id, const TurnRow& r,
                         const TurnDocuments& d) {
  auto s = db.prepare("INSERT INTO turns (" + kTurnWrite.list() + ") VALUES (" +
                      kTurnWrite.placeholders() + ") RETURNING id");
  s.bind(kTurnWrite.param("mission_id"), mission_id);
  s.bind(kTurnWrite.param("vehicle_id"), r.vehicle_id);
  s.bind(kTurnWrite.param("cell_speed_mps"), r.cell_speed_mps);
  s.bind(kTurnWrite.param("cell_dheading_deg"), r.cell_dheading_deg);
  s.bind(kTurnWrite.param("status"), kinematics::to_string(r.status));
  s.bind(kTurnWrite.param("reason"), r.reason);
  s.bind(kTurnWrite.param("commanded_speed_mps"), r.commanded_speed_mps);
  s.bind(kTurnWrite.param("goal_dheading_deg"), r.goal_dheading_deg);
  s.bind(kTurnWrite.param("observed_dheading_deg"), r.observed_dheading_deg);
  s.bind(kTurnWrite.param("start_time_s"), r.start_time_s);
  s.bind(kTurnWrite.param("end_time_s"), r.end_time_s);
  s.bind(kTurnWrite.param("advance_m"), r.advance_m);
  s.bind(kTurnWrite.param("transfer_m"), r.transfer_m);
  s.bind(kTurnWrite.param("condition_set_time_s"), r.condition_set_time_s);
  s.bind(kTurnWrite.param("start_heading_error_deg"), r.start_heading_error_deg);
  s.bind(kTurnWrite.param("start_yaw_rate_dps"), r.start_yaw_rate_dps);
  s.bind(kTurnWrite.param("source"), kinematics::to_string(r.source));
  s.bind(kTurnWrite.param("quality"), r.quality);
  s.bind(kTurnWrite.param("speed_after_mps"), r.speed_after_mps);
  s.bind(kTurnWrite.param("record_key"), r.record_key);
  s.bind(kTurnWrite.param("raw_json"), d.raw_json);
  if (d.normalized_json) {
    s.bind(kTurnWrite.param("normalized_json"), *d.normalized_json);
    s.bind(kTurnWrite.param("normalized_meta_json"), *d.normalized_meta);
    s.bind_blob(kTurnWrite.param("normalized_samples"), d.normalized_samples);
  } else {
    s.bind_null(kTurnWrite.param("normalized_json"));
    s.bind_null(kTurnWrite.param("normalized_meta_json"));
    s.bind_null(kTurnWrite.param("normalized_samples"));
  }
  return inserted_id(s);
}

std::int64_t SqlTurns::add(std::int64_t mission_id, const kinematics::TurnSequence& raw,
                           kinematics::TurnStatus status, const std::string& reason,
                           const TurnStart& start, const std::string& record_key) {
  kinematics::TurnSequence turn = raw;
  turn.meta().status = status;
  turn.meta().status_reason = reason;
  TurnRow row = row_of(turn, start);
  if (!record_key.empty()) row.record_key = record_key;
  // Serialise and measure before taking the write lock: a turn JSON cannot hold (NaN) fails
  // here without touching the database, and the lock is held only for the inserts.
  TurnDocuments docs{kinematics::to_json_string(turn), std::nullopt, std::nullopt, {}};
  try {
    const kinematics::TurnSequence norm = turn.meta().normalized ? turn : turn.normalized();
    const auto at = kinematics::advance_transfer(norm.points());
    docs = normalized_documents(std::move(docs.raw_json), norm);
    row.advance_m = at.advance_m;
    row.transfer_m = at.transfer_m;
  } catch (const std::exception&) {
    // A rejected or aborted turn may be unusable (too short, empty); it is still worth keeping
    // with its reason. An ok turn must normalise.
    if (status == kinematics::TurnStatus::ok) throw;
  }
  Transaction tx(db_);
  if (row.record_key) {
    auto known = db_.prepare("SELECT id FROM turns WHERE record_key = ?");
    known.bind(1, *row.record_key);
    if (known.step()) return known.column_int64(0);
  }
  const std::int64_t id = insert_turn(db_, mission_id, row, docs);
  if (hook_) hook_("turn_inserted");
  tx.commit();
  return id;
}

std::int64_t SqlTurns::newest_ok_id(const std::string& vehicle_id, bool include_harvested) {
  auto s = db_.prepare(
      "SELECT coalesce(max(id), 0) FROM turns WHERE vehicle_id = ?1 AND status = 'ok' "
      "AND (?2 <> 0 OR source = 'collection')");
  s.bind(1, vehicle_id).bind(2, static_cast<std::int64_t>(include_harvested));
  s.step();
  return s.column_int64(0);
}

std::vector<TurnRow> SqlTurns::list(const TurnFilter& filter) {
  // Every filter is always bound; a NULL parameter switches its condition off, so one fixed
  // statement serves all combinations. Ranges keep the (speed, goal) index usable.
  auto s = db_.prepare("SELECT " + kTurnRow.list() +
                       " FROM turns WHERE id > ?1"
                       " AND (?2 IS NULL OR mission_id = ?2)"
                       " AND (?3 IS NULL OR commanded_speed_mps BETWEEN ?3 AND ?4)"
                       " AND (?5 IS NULL OR goal_dheading_deg BETWEEN ?5 AND ?6)"
                       " AND (?7 IS NULL OR status = ?7)"
                       " ORDER BY id LIMIT ?8");
  // Unset filters are NULLs of their column's type (PostgreSQL must know it).
  const auto around = [](std::optional<double> v, double d) {
    return v ? std::optional<double>(*v + d) : std::nullopt;
  };
  s.bind(1, filter.after_id);
  s.bind(2, filter.mission_id);
  s.bind(3, around(filter.speed_mps, -filter.speed_tolerance_mps));
  s.bind(4, around(filter.speed_mps, filter.speed_tolerance_mps));
  s.bind(5, around(filter.dheading_deg, -filter.dheading_tolerance_deg));
  s.bind(6, around(filter.dheading_deg, filter.dheading_tolerance_deg));
  s.bind(7, filter.status ? std::optional<std::string>(kinematics::to_string(*filter.status))
                          : std::nullopt);
  s.bind(8, filter.limit);
  std::vector<TurnRow> out;
  while (s.step())
    out.push_back(read_turn_row(s));
  return out;
}

std::optional<TurnRow> SqlTurns::get_row(std::int64_t turn_id) {
  auto s = db_.prepare("SELECT " + kTurnRow.list() + " FROM turns WHERE id = ?");
  s.bind(1, turn_id);
  if (!s.step()) return std::nullopt;
  return read_turn_row(s);
}

std::optional<StoredTurn> SqlTurns::get(std::int64_t turn_id) {
  auto s = db_.prepare("SELECT " + kTurnRead.list() + " FROM turns WHERE id = ?");
  s.bind(1, turn_id);
  if (!s.step()) return std::nullopt;
  StoredTurn t{read_turn_row(s),
               parse_stored_turn(turn_id, "raw_json", s.column_text(kTurnRead["raw_json"])),
               std::nullopt};
  if (!s.is_null(kTurnRead["normalized_json"]))
    t.normalized =
        parse_stored_turn(turn_id, "normalized_json", s.column_text(kTurnRead["normalized_json"]));
  return t;
}

std::vector<kinematics::TurnSequence> SqlTurns::load_normalized(
    const std::vector<std::int64_t>& mission_ids, const std::optional<std::string>& vehicle_id,
    bool include_harvested, TurnFrameChoice frame, const TurnsLeftOut& left_out) {
  // The mission list travels as one bound JSON array, so the statement text stays fixed
  // whatever the number of missions. The water form, when asked for, replaces the normalised
  // form column for column.
  const std::string columns =
      frame == TurnFrameChoice::water_where_known
          ? "SELECT id, coalesce(water_meta_json, normalized_meta_json), CASE WHEN water_meta_json "
            "IS NULL THEN normalized_samples ELSE water_samples END, normalized_json FROM turns "
          : "SELECT id, normalized_meta_json, normalized_samples, normalized_json FROM turns ";
  const std::string where =
      "WHERE status = 'ok' AND (?1 IS NULL OR vehicle_id = ?1) "
      "AND (?3 <> 0 OR source = 'collection') AND (?4 IS NULL OR id != ?4) "
      "AND (?5 IS NULL OR mission_id != ?5) ";
  auto s = db_.prepare(columns + where +
                       (mission_ids.empty() ? "ORDER BY id"
                                            : "AND mission_id IN (" + db_.json_integers_sql("?2") +
                                                  ") ORDER BY id"));
  s.bind(1, vehicle_id);
  s.bind(4, left_out.turn_id);
  s.bind(5, left_out.mission_id);
  s.bind(3, static_cast<std::int64_t>(include_harvested));
  if (!mission_ids.empty()) s.bind(2, nlohmann::json(mission_ids).dump());
  std::vector<kinematics::TurnSequence> out;
  while (s.step()) {
    const std::int64_t id = s.column_int64(0);
    if (!s.is_null(1) && !s.is_null(2)) {
      // The blob is read last: it stays valid only until the next column access.
      const std::string meta = s.column_text(1);
      out.push_back(unpack_turn(id, meta, s.column_blob(2)));
    } else if (!s.is_null(3)) {
      out.push_back(parse_stored_turn(id, "normalized_json", s.column_text(3)));
    } else {
      // add never writes an ok turn without its normalised form.
      throw StoreError("turn " + std::to_string(id) + " is ok but has no normalised form");
    }
  }
  return out;
}

std::vector<double> SqlTurns::start_times(std::int64_t mission_id) {
  auto s = db_.prepare("SELECT start_time_s FROM turns WHERE mission_id = ? ORDER BY start_time_s");
  s.bind(1, mission_id);
  std::vector<double> out;
  while (s.step())
    out.push_back(s.column_double(0));
  return out;
}

}  // namespace avk::store::sql
