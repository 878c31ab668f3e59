#include "store/store.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <span>
#include <stdexcept>
#include <tuple>

#include <nlohmann/json.hpp>

#include "kinematics/ckt_file.hpp"
#include "kinematics/turn_json.hpp"
#include "kinematics/turn_measures.hpp"
#include "kinematics/yaw_model_json.hpp"

namespace avk::store {

namespace {

// Each step moves the schema from version i to i + 1. Steps are append-only: a released step is
// never edited, because databases in the field have already run it.
constexpr std::array<const char*, 12> kMigrations = {
    R"sql(
CREATE TABLE vehicles (
  id            TEXT PRIMARY KEY,
  kind          TEXT NOT NULL,
  max_speed_mps REAL NOT NULL,
  length_m      REAL
);
CREATE TABLE missions (
  id            INTEGER PRIMARY KEY,
  vehicle_id    TEXT NOT NULL REFERENCES vehicles(id),
  name          TEXT NOT NULL,
  config_json   TEXT NOT NULL,
  status        TEXT NOT NULL CHECK (status IN ('created', 'running', 'paused', 'interrupted',
                                                'aborted', 'halted', 'done')),
  created_utc   TEXT NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now')),
  started_s     REAL,
  ended_s       REAL,
  status_reason TEXT NOT NULL DEFAULT ''
);
CREATE TABLE turns (
  id                    INTEGER PRIMARY KEY,
  mission_id            INTEGER NOT NULL REFERENCES missions(id),
  vehicle_id            TEXT NOT NULL,
  cell_speed_mps        REAL NOT NULL,
  cell_dheading_deg     REAL NOT NULL,
  status                TEXT NOT NULL CHECK (status IN ('ok', 'aborted', 'rejected')),
  reason                TEXT NOT NULL,
  commanded_speed_mps   REAL NOT NULL,
  goal_dheading_deg     REAL NOT NULL,
  observed_dheading_deg REAL NOT NULL,
  start_time_s          REAL NOT NULL,
  end_time_s            REAL NOT NULL,
  advance_m             REAL,
  transfer_m            REAL,
  condition_set_time_s  REAL,
  raw_json              TEXT NOT NULL,
  normalized_json       TEXT
);
CREATE INDEX turns_by_mission ON turns (mission_id, id);
CREATE INDEX turns_by_cell ON turns (commanded_speed_mps, goal_dheading_deg, id);
CREATE TABLE nav_samples (
  mission_id          INTEGER NOT NULL REFERENCES missions(id),
  t_s                 REAL NOT NULL,
  x_m                 REAL NOT NULL,
  y_m                 REAL NOT NULL,
  heading_deg         REAL NOT NULL,
  speed_mps           REAL NOT NULL,
  desired_heading_deg REAL,
  desired_speed_mps   REAL,
  helm_mode           TEXT NOT NULL
);
CREATE INDEX nav_by_mission_time ON nav_samples (mission_id, t_s);
CREATE TABLE ckt_snapshots (
  id          INTEGER PRIMARY KEY,
  created_utc TEXT NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now')),
  mission_ids TEXT NOT NULL,
  document    TEXT NOT NULL
);
)sql",
    // normalized_samples (packed float64, see pack_samples) and normalized_meta_json (the
    // normalised turn's JSON without samples) let the CKT load thousands of turns without
    // parsing their full JSON; normalized_json stays the turn's document of record.
    R"sql(
ALTER TABLE missions ADD COLUMN runner_pid INTEGER;
ALTER TABLE turns ADD COLUMN normalized_samples BLOB;
ALTER TABLE turns ADD COLUMN normalized_meta_json TEXT;
CREATE INDEX turns_by_mission_end ON turns (mission_id, end_time_s);
CREATE TABLE condition_sets (
  id               INTEGER PRIMARY KEY,
  mission_id       INTEGER NOT NULL REFERENCES missions(id),
  start_s          REAL NOT NULL,
  end_s            REAL NOT NULL,
  target_speed_mps REAL NOT NULL,
  outcome          TEXT NOT NULL CHECK (outcome IN ('set', 'timeout', 'interrupted')),
  CHECK (end_s >= start_s)
);
CREATE INDEX condition_sets_by_mission ON condition_sets (mission_id, start_s);
CREATE TABLE mission_events (
  id         INTEGER PRIMARY KEY,
  mission_id INTEGER NOT NULL REFERENCES missions(id),
  t_s        REAL NOT NULL,
  kind       TEXT NOT NULL,
  message    TEXT NOT NULL
);
CREATE INDEX mission_events_by_mission ON mission_events (mission_id, id);
)sql",
    // Identified yaw models: the model document (kinematics/yaw_model_json.hpp), what it was
    // trained on, and how well it did on data it did not see.
    R"sql(
CREATE TABLE yaw_models (
  id                      INTEGER PRIMARY KEY,
  created_utc             TEXT NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now')),
  vehicle_id              TEXT NOT NULL,
  form                    TEXT NOT NULL,
  history                 INTEGER NOT NULL,
  rate_hz                 REAL NOT NULL,
  refined                 INTEGER NOT NULL,
  training_missions       TEXT NOT NULL,
  train_one_step_rms_deg  REAL,
  validation_mse_m2       REAL,
  validation_heading_rms_deg REAL,
  document                TEXT NOT NULL
);
CREATE INDEX yaw_models_by_vehicle ON yaw_models (vehicle_id, id);
)sql",
    // The server asks every second whether a vehicle's table changed: its newest ok turn.
    R"sql(
CREATE INDEX turns_by_vehicle_status ON turns (vehicle_id, status, id);
)sql",
    // Navigation pages by (mission, rowid): an index on mission_id holds the rowid in order, so
    // a page is a range scan, not a sort of the whole mission.
    R"sql(
CREATE INDEX nav_by_mission ON nav_samples (mission_id);
)sql",
    // A vehicle's latest imported table is looked up by vehicle: a database holding several
    // vehicles must not answer one vehicle's question with another's table.
    R"sql(
ALTER TABLE ckt_snapshots ADD COLUMN vehicle_id TEXT;
UPDATE ckt_snapshots SET vehicle_id = json_extract(document, '$.vehicle.id')
  WHERE json_valid(document);
CREATE INDEX ckt_snapshots_by_vehicle ON ckt_snapshots (vehicle_id, id);
)sql",
    // How steady each turn began (the ConditionSet's heading error and yaw rate): a turn begun
    // in the middle of a swing is visible in the report. Older turns have none.
    R"sql(
ALTER TABLE turns ADD COLUMN start_heading_error_deg REAL;
ALTER TABLE turns ADD COLUMN start_yaw_rate_dps REAL;
)sql",
    // Turns harvested from ordinary navigation logs: each turn's source and
    // quality, and a record of every harvest run with its counts. Older turns are collection.
    R"sql(
ALTER TABLE turns ADD COLUMN source TEXT NOT NULL DEFAULT 'collection'
  CHECK (source IN ('collection', 'harvested'));
ALTER TABLE turns ADD COLUMN quality REAL;
CREATE TABLE harvests (
  id               INTEGER PRIMARY KEY,
  mission_id       INTEGER NOT NULL REFERENCES missions(id),
  created_utc      TEXT NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now')),
  steps            INTEGER NOT NULL,
  harvested        INTEGER NOT NULL,
  already_recorded INTEGER NOT NULL,
  rejected_json    TEXT NOT NULL
);
CREATE INDEX harvests_by_mission ON harvests (mission_id, id);
)sql",
    // The speed commanded with the new heading when a turn changes speed (u1;
    // commanded_speed_mps stays u0). NULL for a constant-speed turn and every older turn.
    R"sql(
ALTER TABLE turns ADD COLUMN speed_after_mps REAL;
)sql",
    // The current each mission flew in (app/current.hpp) and its turns in the water frame, the
    // drift of that current removed (kinematics/water_frame.hpp), packed like the normalised
    // form: a table learned in one current then predicts turns in another.
    R"sql(
CREATE TABLE mission_currents (
  mission_id       INTEGER PRIMARY KEY REFERENCES missions(id),
  t_s              REAL NOT NULL,
  method           TEXT NOT NULL CHECK (method IN ('legs', 'turns')),
  east_mps         REAL NOT NULL,
  north_mps        REAL NOT NULL,
  cov_ee           REAL NOT NULL,
  cov_en           REAL NOT NULL,
  cov_nn           REAL NOT NULL,
  speed_scale      REAL NOT NULL,
  residual_rms_mps REAL NOT NULL,
  evidence         INTEGER NOT NULL,
  revision         INTEGER NOT NULL,
  estimated_utc    TEXT NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now'))
);
ALTER TABLE turns ADD COLUMN water_samples BLOB;
ALTER TABLE turns ADD COLUMN water_meta_json TEXT;
)sql",
    // The wall-clock moments a mission started and ended, so a mission of an earlier
    // server session (whose station clock no longer maps to wall time) still shows when it ran.
    // NULL for every mission stored before.
    R"sql(
ALTER TABLE missions ADD COLUMN started_utc TEXT;
ALTER TABLE missions ADD COLUMN ended_utc TEXT;
)sql",
    // Which speed the vehicle's loop holds (over ground or through the water) and how fast a
    // straight-line prediction's error grows, from the mission's steady legs
    // (kinematics/speed_reference.hpp, kinematics/drift_scatter.hpp), kept with the current they
    // were judged in. NULL where not evaluated (every estimate stored before); reference_legs set
    // with speed_reference NULL: evaluated and undetermined.
    R"sql(
ALTER TABLE mission_currents ADD COLUMN reference_legs INTEGER;
ALTER TABLE mission_currents ADD COLUMN rms_over_ground_mps REAL;
ALTER TABLE mission_currents ADD COLUMN rms_through_water_mps REAL;
ALTER TABLE mission_currents ADD COLUMN reference_separation_mps REAL;
ALTER TABLE mission_currents ADD COLUMN speed_reference TEXT
  CHECK (speed_reference IN ('over_ground', 'through_water'));
ALTER TABLE mission_currents ADD COLUMN drift_legs INTEGER;
ALTER TABLE mission_currents ADD COLUMN drift_along_mps REAL;
ALTER TABLE mission_currents ADD COLUMN drift_cross_mps REAL;
ALTER TABLE mission_currents ADD COLUMN drift_mean_leg_s REAL;
)sql",
};

constexpr const char* kMissionStatusNames[] = {"created", "running", "paused", "interrupted",
                                               "aborted", "halted",  "done"};

constexpr const char* kTurnColumns =
    "id, mission_id, vehicle_id, cell_speed_mps, cell_dheading_deg, status, reason, "
    "commanded_speed_mps, goal_dheading_deg, observed_dheading_deg, start_time_s, end_time_s, "
    "advance_m, transfer_m, condition_set_time_s, start_heading_error_deg, start_yaw_rate_dps, "
    "source, quality, speed_after_mps";
constexpr int kTurnRowColumns = 20;

TurnRow read_turn_row(const Statement& s) {
  TurnRow r;
  r.id = s.column_int64(0);
  r.mission_id = s.column_int64(1);
  r.vehicle_id = s.column_text(2);
  r.cell_speed_mps = s.column_double(3);
  r.cell_dheading_deg = s.column_double(4);
  const std::string status = s.column_text(5);
  const auto parsed = kinematics::turn_status_from_string(status);
  if (!parsed)
    throw StoreError("turn " + std::to_string(r.id) + " has unknown status '" + status + "'");
  r.status = *parsed;
  r.reason = s.column_text(6);
  r.commanded_speed_mps = s.column_double(7);
  r.goal_dheading_deg = s.column_double(8);
  r.observed_dheading_deg = s.column_double(9);
  r.start_time_s = s.column_double(10);
  r.end_time_s = s.column_double(11);
  r.advance_m = s.column_optional_double(12);
  r.transfer_m = s.column_optional_double(13);
  r.condition_set_time_s = s.column_optional_double(14);
  r.start_heading_error_deg = s.column_optional_double(15);
  r.start_yaw_rate_dps = s.column_optional_double(16);
  const std::string source = s.column_text(17);
  const auto parsed_source = kinematics::turn_source_from_string(source);
  if (!parsed_source)
    throw StoreError("turn " + std::to_string(r.id) + " has unknown source '" + source + "'");
  r.source = *parsed_source;
  r.quality = s.column_optional_double(18);
  r.speed_after_mps = s.column_optional_double(19);
  return r;
}

Mission read_mission(const Statement& s) {
  Mission m;
  m.id = s.column_int64(0);
  m.vehicle_id = s.column_text(1);
  m.name = s.column_text(2);
  m.config_json = s.column_text(3);
  const std::string status = s.column_text(4);
  const auto parsed = mission_status_from_string(status);
  if (!parsed)
    throw StoreError("mission " + std::to_string(m.id) + " has unknown status '" + status + "'");
  m.status = *parsed;
  m.created_utc = s.column_text(5);
  m.started_s = s.column_optional_double(6);
  m.ended_s = s.column_optional_double(7);
  m.status_reason = s.column_text(8);
  m.runner_pid = s.column_optional_int64(9);
  if (!s.is_null(10)) m.started_utc = s.column_text(10);
  if (!s.is_null(11)) m.ended_utc = s.column_text(11);
  return m;
}

constexpr const char* kMissionColumns =
    "id, vehicle_id, name, config_json, status, created_utc, started_s, ended_s, status_reason, "
    "runner_pid, started_utc, ended_utc";

// A sample is 5 doubles (t_s, x_m, y_m, heading_deg, speed_mps), each 8 bytes little-endian
// whatever the host, so a database file moves between machines.
constexpr std::size_t kPackedSampleBytes = 5 * sizeof(std::uint64_t);
static_assert(sizeof(double) == sizeof(std::uint64_t) && std::numeric_limits<double>::is_iec559);

std::vector<unsigned char> pack_samples(const std::vector<kinematics::TurnSample>& samples) {
  std::vector<unsigned char> out(samples.size() * kPackedSampleBytes);
  unsigned char* p = out.data();
  const auto put = [&p](double v) {
    const auto bits = std::bit_cast<std::uint64_t>(v);
    for (int b = 0; b < 8; ++b)
      *p++ = static_cast<unsigned char>(bits >> (8 * b));
  };
  for (const auto& s : samples) {
    put(s.t_s);
    put(s.x_m);
    put(s.y_m);
    put(s.heading_deg);
    put(s.speed_mps);
  }
  return out;
}

std::vector<kinematics::TurnSample> unpack_samples(std::int64_t turn_id,
                                                   std::span<const unsigned char> bytes) {
  if (bytes.size() % kPackedSampleBytes != 0)
    throw StoreError("turn " + std::to_string(turn_id) +
                     ": stored normalized_samples is corrupt (" + std::to_string(bytes.size()) +
                     " bytes, not whole samples)");
  const unsigned char* p = bytes.data();
  const auto get = [&p] {
    std::uint64_t bits = 0;
    for (int b = 0; b < 8; ++b)
      bits |= static_cast<std::uint64_t>(*p++) << (8 * b);
    return std::bit_cast<double>(bits);
  };
  std::vector<kinematics::TurnSample> out(bytes.size() / kPackedSampleBytes);
  for (auto& s : out) {
    s.t_s = get();
    s.x_m = get();
    s.y_m = get();
    s.heading_deg = get();
    s.speed_mps = get();
  }
  return out;
}

// The turn without its samples: metadata and warnings through the same serialiser as the full
// document, so whatever TurnMeta holds survives the packed path too.
std::string meta_json(const kinematics::TurnSequence& turn) {
  kinematics::TurnSequence head(turn.meta(), {});
  for (const auto& w : turn.warnings())
    head.add_warning(w);
  return kinematics::to_json_string(head);
}

kinematics::TurnSequence parse_stored_turn(std::int64_t id, const std::string& column,
                                           const std::string& text) {
  try {
    return kinematics::parse_turn_json(text);
  } catch (const std::exception& e) {
    throw StoreError("turn " + std::to_string(id) + ": stored " + column +
                     " is corrupt: " + e.what());
  }
}

}  // namespace

int schema_version() {
  return static_cast<int>(kMigrations.size());
}

std::string_view migration_step_sql(int index) {
  if (index < 0 || index >= schema_version())
    throw std::out_of_range("no migration step " + std::to_string(index));
  return kMigrations[static_cast<std::size_t>(index)];
}

const char* to_string(MissionStatus s) {
  return kMissionStatusNames[static_cast<int>(s)];
}

std::optional<MissionStatus> mission_status_from_string(std::string_view s) {
  for (int i = 0; i < static_cast<int>(std::size(kMissionStatusNames)); ++i)
    if (s == kMissionStatusNames[i]) return static_cast<MissionStatus>(i);
  return std::nullopt;
}

Store::Store(const std::string& path) : db_(path) {
  // Waiting up to 5 s for a lock rides out another writer's commit instead of failing at once.
  db_.exec("PRAGMA busy_timeout = 5000");
  db_.exec("PRAGMA foreign_keys = ON");
  // WAL: readers never block the writer nor see its uncommitted work. NORMAL synchronous is
  // durable against process crashes (only a power cut may lose the last commits) and avoids an
  // fsync per transaction, which nav ingest could not afford.
  db_.exec("PRAGMA journal_mode = WAL");
  db_.exec("PRAGMA synchronous = NORMAL");
  migrate();
}

int Store::user_version() {
  auto s = db_.prepare("PRAGMA user_version");
  s.step();
  return static_cast<int>(s.column_int64(0));
}

std::string Store::journal_mode() {
  auto s = db_.prepare("PRAGMA journal_mode");
  s.step();
  return s.column_text(0);
}

bool Store::integrity_check() {
  auto s = db_.prepare("PRAGMA integrity_check");
  // A healthy database answers a single row "ok"; anything else lists problems.
  if (!s.step()) return false;
  const bool ok = s.column_text(0) == "ok";
  return ok && !s.step();
}

void Store::migrate() {
  // The version check and the steps share one write transaction, so two processes opening a
  // fresh file cannot both run step 1.
  Transaction tx(db_);
  const int current = user_version();
  const int latest = schema_version();
  if (current > latest)
    throw StoreError("database schema version " + std::to_string(current) +
                     " is newer than this program supports (" + std::to_string(latest) +
                     "); upgrade AVK Station to open it");
  for (int v = current; v < latest; ++v)
    db_.exec(kMigrations[static_cast<std::size_t>(v)]);
  if (current != latest) {
    // PRAGMA takes no bound parameters; the value is our own integer, not outside input.
    const std::string set = "PRAGMA user_version = " + std::to_string(latest);
    db_.exec(set.c_str());
  }
  tx.commit();
}

void Store::upsert_vehicle(const vehicle::VehicleInfo& info) {
  auto s = db_.prepare(
      "INSERT INTO vehicles (id, kind, max_speed_mps, length_m) VALUES (?, ?, ?, ?) "
      "ON CONFLICT (id) DO UPDATE SET kind = excluded.kind, "
      "max_speed_mps = excluded.max_speed_mps, length_m = excluded.length_m");
  s.bind(1, info.id).bind(2, info.kind).bind(3, info.max_speed_mps).bind(4, info.length_m);
  s.run();
}

std::optional<vehicle::VehicleInfo> Store::get_vehicle(const std::string& id) {
  auto s = db_.prepare("SELECT id, kind, max_speed_mps, length_m FROM vehicles WHERE id = ?");
  s.bind(1, id);
  if (!s.step()) return std::nullopt;
  return vehicle::VehicleInfo{s.column_text(0), s.column_text(1), s.column_double(2),
                              s.column_optional_double(3)};
}

std::int64_t Store::create_mission(const std::string& vehicle_id, const std::string& name,
                                   const std::string& config_json) {
  auto s = db_.prepare(
      "INSERT INTO missions (vehicle_id, name, config_json, status) VALUES (?, ?, ?, 'created')");
  s.bind(1, vehicle_id).bind(2, name).bind(3, config_json);
  s.run();
  return db_.last_insert_rowid();
}

void Store::set_mission_status(std::int64_t mission_id, MissionStatus status,
                               const std::string& reason, double t_s) {
  // Running again (a resume) has no end yet; an interruption ends the run that stopped, so the
  // mission's elapsed time is known until it is resumed.
  const bool starts = status == MissionStatus::running;
  const bool ends = status == MissionStatus::aborted || status == MissionStatus::halted ||
                    status == MissionStatus::done || status == MissionStatus::interrupted;
  auto s = db_.prepare(
      "UPDATE missions SET status = ?1, status_reason = ?2, "
      "started_utc = CASE WHEN ?3 AND started_s IS NULL "
      "THEN strftime('%Y-%m-%dT%H:%M:%fZ', 'now') ELSE started_utc END, "
      "started_s = CASE WHEN ?3 AND started_s IS NULL THEN ?5 ELSE started_s END, "
      "ended_utc = CASE WHEN ?4 THEN strftime('%Y-%m-%dT%H:%M:%fZ', 'now') "
      "WHEN ?3 THEN NULL ELSE ended_utc END, "
      "ended_s = CASE WHEN ?4 THEN ?5 WHEN ?3 THEN NULL ELSE ended_s END WHERE id = ?6");
  s.bind(1, to_string(status)).bind(2, reason).bind(3, starts ? 1 : 0).bind(4, ends ? 1 : 0);
  s.bind(5, t_s).bind(6, mission_id);
  s.run();
  if (db_.changes() == 0) throw StoreError("no mission " + std::to_string(mission_id));
}

std::optional<Mission> Store::get_mission(std::int64_t mission_id) {
  auto s = db_.prepare(std::string("SELECT ") + kMissionColumns + " FROM missions WHERE id = ?");
  s.bind(1, mission_id);
  if (!s.step()) return std::nullopt;
  return read_mission(s);
}

std::vector<Mission> Store::list_missions() {
  auto s = db_.prepare(std::string("SELECT ") + kMissionColumns + " FROM missions ORDER BY id");
  std::vector<Mission> out;
  while (s.step())
    out.push_back(read_mission(s));
  return out;
}

namespace {

// A turn's documents as stored: the raw JSON and, when it has one, the normalised JSON with its
// packed samples (the CKT's fast path).
struct TurnDocuments {
  std::string raw_json;
  std::optional<std::string> normalized_json, normalized_meta;
  std::vector<unsigned char> normalized_samples;
};

TurnDocuments normalized_documents(std::string raw_json, const kinematics::TurnSequence& norm) {
  return {std::move(raw_json), kinematics::to_json_string(norm), meta_json(norm),
          pack_samples(norm.samples())};
}

// The row's columns as given (row.id and row.mission_id aside); the new turn id.
std::int64_t insert_turn(Connection& db, std::int64_t mission_id, const TurnRow& r,
                         const TurnDocuments& d) {
  auto s = db.prepare(
      "INSERT INTO turns (mission_id, vehicle_id, cell_speed_mps, cell_dheading_deg, status, "
      "reason, commanded_speed_mps, goal_dheading_deg, observed_dheading_deg, start_time_s, "
      "end_time_s, advance_m, transfer_m, condition_set_time_s, raw_json, normalized_json, "
      "normalized_meta_json, normalized_samples, start_heading_error_deg, start_yaw_rate_dps, "
      "source, quality, speed_after_mps) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, "
      "?, ?, ?, ?, ?, ?, ?)");
  s.bind(1, mission_id).bind(2, r.vehicle_id).bind(3, r.cell_speed_mps);
  s.bind(4, r.cell_dheading_deg).bind(5, kinematics::to_string(r.status)).bind(6, r.reason);
  s.bind(7, r.commanded_speed_mps).bind(8, r.goal_dheading_deg).bind(9, r.observed_dheading_deg);
  s.bind(10, r.start_time_s).bind(11, r.end_time_s).bind(12, r.advance_m).bind(13, r.transfer_m);
  s.bind(14, r.condition_set_time_s).bind(15, d.raw_json);
  s.bind(19, r.start_heading_error_deg).bind(20, r.start_yaw_rate_dps);
  s.bind(21, kinematics::to_string(r.source)).bind(22, r.quality);
  s.bind(23, r.speed_after_mps);
  if (d.normalized_json) {
    s.bind(16, *d.normalized_json).bind(17, *d.normalized_meta).bind_blob(18, d.normalized_samples);
  } else {
    s.bind_null(16).bind_null(17).bind_null(18);
  }
  s.run();
  return db.last_insert_rowid();
}

void insert_nav(Connection& db, std::int64_t mission_id, std::span<const NavRow> rows) {
  auto s = db.prepare(
      "INSERT INTO nav_samples (mission_id, t_s, x_m, y_m, heading_deg, speed_mps, "
      "desired_heading_deg, desired_speed_mps, helm_mode) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?)");
  for (const NavRow& r : rows) {
    s.bind(1, mission_id).bind(2, r.t_s).bind(3, r.x_m).bind(4, r.y_m).bind(5, r.heading_deg);
    s.bind(6, r.speed_mps).bind(7, r.desired_heading_deg).bind(8, r.desired_speed_mps);
    s.bind(9, r.helm_mode);
    s.run();
    s.reset();
  }
}

// The water-frame form of one turn, packed like the normalised form.
using PackedWaterTurn = std::tuple<std::int64_t, std::string, std::vector<unsigned char>>;

PackedWaterTurn pack_water_turn(std::int64_t id, const kinematics::TurnSequence& turn) {
  return {id, meta_json(turn), pack_samples(turn.samples())};
}

// Inside the caller's transaction; the new revision.
std::int64_t write_current(Connection& db, const StoredCurrent& current,
                           const std::vector<PackedWaterTurn>& packed) {
  const kinematics::CurrentEstimate& e = current.estimate;
  auto rev = db.prepare("SELECT coalesce(max(revision), 0) + 1 FROM mission_currents");
  rev.step();
  const std::int64_t revision = rev.column_int64(0);
  auto s = db.prepare(
      "INSERT OR REPLACE INTO mission_currents (mission_id, t_s, method, east_mps, north_mps, "
      "cov_ee, cov_en, cov_nn, speed_scale, residual_rms_mps, evidence, revision, "
      "reference_legs, rms_over_ground_mps, rms_through_water_mps, reference_separation_mps, "
      "speed_reference, drift_legs, drift_along_mps, drift_cross_mps, drift_mean_leg_s) "
      "VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
  s.bind(1, current.mission_id).bind(2, current.t_s).bind(3, current.method);
  s.bind(4, e.east_mps).bind(5, e.north_mps).bind(6, e.covariance[0]).bind(7, e.covariance[1]);
  s.bind(8, e.covariance[2]).bind(9, e.speed_scale).bind(10, e.residual_rms_mps);
  s.bind(11, static_cast<std::int64_t>(e.legs)).bind(12, revision);
  for (int i = 13; i <= 21; ++i)
    s.bind_null(i);
  if (const auto& r = current.speed_reference) {
    s.bind(13, static_cast<std::int64_t>(r->legs)).bind(14, r->rms_over_ground_mps);
    s.bind(15, r->rms_through_water_mps).bind(16, r->separation_mps);
    if (r->identified) s.bind(17, kinematics::to_string(*r->identified));
  }
  if (const auto& d = current.drift_scatter) {
    s.bind(18, static_cast<std::int64_t>(d->legs)).bind(19, d->along_mps);
    s.bind(20, d->cross_mps).bind(21, d->mean_leg_s);
  }
  s.run();
  auto clear = db.prepare(
      "UPDATE turns SET water_samples = NULL, water_meta_json = NULL WHERE mission_id = ?");
  clear.bind(1, current.mission_id);
  clear.run();
  auto put = db.prepare(
      "UPDATE turns SET water_meta_json = ?, water_samples = ? WHERE id = ? AND mission_id = ?");
  for (const auto& [id, meta, samples] : packed) {
    put.bind(1, meta).bind_blob(2, samples).bind(3, id).bind(4, current.mission_id);
    put.run();
    if (db.changes() != 1)
      throw StoreError("turn " + std::to_string(id) + " is not a turn of mission " +
                       std::to_string(current.mission_id));
    put.reset();
  }
  return revision;
}

}  // namespace

std::int64_t Store::store_turn(std::int64_t mission_id, const kinematics::TurnSequence& raw,
                               kinematics::TurnStatus status, const std::string& reason,
                               const TurnStart& start) {
  kinematics::TurnSequence turn = raw;
  turn.meta().status = status;
  turn.meta().status_reason = reason;
  const auto& m = turn.meta();
  TurnRow row;
  row.vehicle_id = m.vehicle_id;
  row.cell_speed_mps = m.commanded_speed_mps;
  row.cell_dheading_deg = std::abs(m.goal_dheading_deg);
  row.status = status;
  row.reason = reason;
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
  // Serialise and measure before taking the write lock: a turn JSON cannot hold (NaN) fails
  // here without touching the database, and the lock is held only for the inserts.
  TurnDocuments docs{kinematics::to_json_string(turn), std::nullopt, std::nullopt, {}};
  try {
    const kinematics::TurnSequence norm = m.normalized ? turn : turn.normalized();
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
  const std::int64_t id = insert_turn(db_, mission_id, row, docs);
  if (store_turn_hook_) store_turn_hook_("turn_inserted");
  tx.commit();
  return id;
}

std::int64_t Store::newest_ok_turn_id(const std::string& vehicle_id, bool include_harvested) {
  auto s = db_.prepare(
      "SELECT coalesce(max(id), 0) FROM turns WHERE vehicle_id = ?1 AND status = 'ok' "
      "AND (?2 OR source = 'collection')");
  s.bind(1, vehicle_id).bind(2, static_cast<std::int64_t>(include_harvested));
  s.step();
  return s.column_int64(0);
}

std::vector<TurnRow> Store::list_turns(const TurnFilter& filter) {
  // Every filter is always bound; a NULL parameter switches its condition off, so one fixed
  // statement serves all combinations. Ranges keep the (speed, goal) index usable.
  auto s = db_.prepare(std::string("SELECT ") + kTurnColumns +
                       " FROM turns WHERE id > ?1"
                       " AND (?2 IS NULL OR mission_id = ?2)"
                       " AND (?3 IS NULL OR commanded_speed_mps BETWEEN ?3 AND ?4)"
                       " AND (?5 IS NULL OR goal_dheading_deg BETWEEN ?5 AND ?6)"
                       " AND (?7 IS NULL OR status = ?7)"
                       " ORDER BY id LIMIT ?8");
  s.bind(1, filter.after_id);
  if (filter.mission_id) s.bind(2, *filter.mission_id);
  if (filter.speed_mps) {
    s.bind(3, *filter.speed_mps - filter.speed_tolerance_mps);
    s.bind(4, *filter.speed_mps + filter.speed_tolerance_mps);
  }
  if (filter.dheading_deg) {
    s.bind(5, *filter.dheading_deg - filter.dheading_tolerance_deg);
    s.bind(6, *filter.dheading_deg + filter.dheading_tolerance_deg);
  }
  if (filter.status) s.bind(7, kinematics::to_string(*filter.status));
  s.bind(8, filter.limit);
  std::vector<TurnRow> out;
  while (s.step())
    out.push_back(read_turn_row(s));
  return out;
}

std::optional<TurnRow> Store::get_turn_row(std::int64_t turn_id) {
  auto s = db_.prepare(std::string("SELECT ") + kTurnColumns + " FROM turns WHERE id = ?");
  s.bind(1, turn_id);
  if (!s.step()) return std::nullopt;
  return read_turn_row(s);
}

std::optional<StoredTurn> Store::get_turn(std::int64_t turn_id) {
  auto s = db_.prepare(std::string("SELECT ") + kTurnColumns +
                       ", raw_json, normalized_json FROM turns WHERE id = ?");
  s.bind(1, turn_id);
  if (!s.step()) return std::nullopt;
  // The two documents follow the kTurnRowColumns row columns.
  StoredTurn t{read_turn_row(s),
               parse_stored_turn(turn_id, "raw_json", s.column_text(kTurnRowColumns)),
               std::nullopt};
  if (!s.is_null(kTurnRowColumns + 1))
    t.normalized =
        parse_stored_turn(turn_id, "normalized_json", s.column_text(kTurnRowColumns + 1));
  return t;
}

void Store::close_orphaned_mission(std::int64_t mission_id, const std::string& reason,
                                   std::optional<double> end_s) {
  auto s = db_.prepare(
      "UPDATE missions SET status = 'interrupted', status_reason = ?, ended_s = ?, "
      "ended_utc = NULL, runner_pid = NULL WHERE id = ?");
  s.bind(1, reason).bind(2, end_s).bind(3, mission_id);
  s.run();
  if (db_.changes() == 0) throw StoreError("no mission " + std::to_string(mission_id));
}

void Store::set_mission_runner(std::int64_t mission_id, std::optional<std::int64_t> pid) {
  auto s = db_.prepare("UPDATE missions SET runner_pid = ? WHERE id = ?");
  s.bind(1, pid).bind(2, mission_id);
  s.run();
  if (db_.changes() == 0) throw StoreError("no mission " + std::to_string(mission_id));
}

void Store::append_condition_set(std::int64_t mission_id, const ConditionSetTiming& timing) {
  auto s = db_.prepare(
      "INSERT INTO condition_sets (mission_id, start_s, end_s, target_speed_mps, outcome) "
      "VALUES (?, ?, ?, ?, ?)");
  s.bind(1, mission_id).bind(2, timing.start_s).bind(3, timing.end_s);
  s.bind(4, timing.target_speed_mps).bind(5, timing.outcome);
  s.run();
}

std::vector<ConditionSetTiming> Store::condition_sets(std::int64_t mission_id) {
  // id breaks ties between episodes that start at the same time: insertion order.
  auto s = db_.prepare(
      "SELECT start_s, end_s, target_speed_mps, outcome FROM condition_sets WHERE mission_id = ? "
      "ORDER BY start_s, id");
  s.bind(1, mission_id);
  std::vector<ConditionSetTiming> out;
  while (s.step())
    out.push_back({s.column_double(0), s.column_double(1), s.column_double(2), s.column_text(3)});
  return out;
}

std::int64_t Store::append_event(std::int64_t mission_id, double t_s, const std::string& kind,
                                 const std::string& message) {
  auto s = db_.prepare(
      "INSERT INTO mission_events (mission_id, t_s, kind, message) VALUES (?, ?, ?, ?)");
  s.bind(1, mission_id).bind(2, t_s).bind(3, kind).bind(4, message);
  s.run();
  return db_.last_insert_rowid();
}

std::vector<MissionEvent> Store::list_events(std::int64_t mission_id, std::int64_t after_id,
                                             int limit) {
  auto s = db_.prepare(
      "SELECT id, mission_id, t_s, kind, message FROM mission_events "
      "WHERE mission_id = ? AND id > ? ORDER BY id LIMIT ?");
  s.bind(1, mission_id).bind(2, after_id).bind(3, limit);
  std::vector<MissionEvent> out;
  while (s.step())
    out.push_back({s.column_int64(0), s.column_int64(1), s.column_double(2), s.column_text(3),
                   s.column_text(4)});
  return out;
}

std::optional<double> Store::mission_clock_end_s(std::int64_t mission_id) {
  // The aggregate max skips the NULL of an empty source (the scalar max(a, b) would not), and
  // each inner max is one index probe for the large tables (nav, turns).
  auto s = db_.prepare(
      "SELECT max(t) FROM ("
      " SELECT max(t_s) AS t FROM nav_samples WHERE mission_id = ?1"
      " UNION ALL SELECT max(end_time_s) FROM turns WHERE mission_id = ?1"
      " UNION ALL SELECT max(t_s) FROM mission_events WHERE mission_id = ?1"
      " UNION ALL SELECT max(end_s) FROM condition_sets WHERE mission_id = ?1)");
  s.bind(1, mission_id);
  s.step();
  return s.column_optional_double(0);
}

double Store::station_clock_end_s() {
  double end = 0.0;
  for (const auto& m : list_missions())
    end = std::max(end, mission_clock_end_s(m.id).value_or(0.0));
  return end;
}

std::map<std::int64_t, TurnCounts> Store::turn_counts_by_mission() {
  auto s =
      db_.prepare("SELECT mission_id, status, count(*) FROM turns GROUP BY mission_id, status");
  std::map<std::int64_t, TurnCounts> out;
  while (s.step()) {
    const auto status = kinematics::turn_status_from_string(s.column_text(1));
    out[s.column_int64(0)].add(status.value_or(kinematics::TurnStatus::ok), s.column_int64(2));
  }
  return out;
}

std::vector<CellStats> Store::mission_cell_stats(std::int64_t mission_id) {
  auto s = db_.prepare(
      "SELECT cell_speed_mps, cell_dheading_deg, status, advance_m, transfer_m, "
      "condition_set_time_s, speed_after_mps FROM turns WHERE mission_id = ? "
      "ORDER BY cell_speed_mps, coalesce(speed_after_mps, -1), cell_dheading_deg, id");
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
    const double speed = s.column_double(0);
    const double dheading = s.column_double(1);
    const std::optional<double> speed_after = s.column_optional_double(6);
    if (out.empty() || out.back().speed_mps != speed || out.back().dheading_deg != dheading ||
        out.back().speed_after_mps != speed_after) {
      close_cell();
      out.push_back({});
      out.back().speed_mps = speed;
      out.back().dheading_deg = dheading;
      out.back().speed_after_mps = speed_after;
    }
    CellStats& c = out.back();
    const std::string status = s.column_text(2);
    if (status == "aborted") {
      ++c.n_aborted;
    } else if (status == "rejected") {
      ++c.n_rejected;
    } else {
      ++c.n_ok;
      if (auto v = s.column_optional_double(3)) advances.push_back(*v);
      if (auto v = s.column_optional_double(4)) transfers.push_back(*v);
      if (auto v = s.column_optional_double(5)) condition_set_times.push_back(*v);
    }
  }
  close_cell();
  return out;
}

std::vector<kinematics::TurnSequence> Store::load_normalized_turns(
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
  auto s = db_.prepare(mission_ids.empty()
                           ? columns +
                                 "WHERE status = 'ok' AND (?1 IS NULL OR vehicle_id = ?1) "
                                 "AND (?3 OR source = 'collection') AND (?4 IS NULL OR id != ?4) "
                                 "AND (?5 IS NULL OR mission_id != ?5) ORDER BY id"
                           : columns +
                                 "WHERE status = 'ok' AND (?1 IS NULL OR vehicle_id = ?1) "
                                 "AND (?3 OR source = 'collection') AND (?4 IS NULL OR id != ?4) "
                                 "AND (?5 IS NULL OR mission_id != ?5) "
                                 "AND mission_id IN (SELECT value FROM json_each(?2)) ORDER BY id");
  if (vehicle_id) s.bind(1, *vehicle_id);
  if (left_out.turn_id) s.bind(4, *left_out.turn_id);
  if (left_out.mission_id) s.bind(5, *left_out.mission_id);
  s.bind(3, static_cast<std::int64_t>(include_harvested));
  if (!mission_ids.empty()) s.bind(2, nlohmann::json(mission_ids).dump());
  std::vector<kinematics::TurnSequence> out;
  while (s.step()) {
    const std::int64_t id = s.column_int64(0);
    if (!s.is_null(1) && !s.is_null(2)) {
      kinematics::TurnSequence head =
          parse_stored_turn(id, "normalized_meta_json", s.column_text(1));
      kinematics::TurnSequence turn(head.meta(), unpack_samples(id, s.column_blob(2)));
      for (const auto& w : head.warnings())
        turn.add_warning(w);
      out.push_back(std::move(turn));
    } else if (!s.is_null(3)) {
      out.push_back(parse_stored_turn(id, "normalized_json", s.column_text(3)));
    } else {
      // store_turn never writes an ok turn without its normalised form.
      throw StoreError("turn " + std::to_string(id) + " is ok but has no normalised form");
    }
  }
  return out;
}

std::int64_t Store::save_mission_current(
    const StoredCurrent& current,
    const std::vector<std::pair<std::int64_t, kinematics::TurnSequence>>& water_turns) {
  // Serialised before the write lock, as store_turn does.
  std::vector<PackedWaterTurn> packed;
  packed.reserve(water_turns.size());
  for (const auto& [id, turn] : water_turns)
    packed.push_back(pack_water_turn(id, turn));
  Transaction tx(db_);
  const std::int64_t revision = write_current(db_, current, packed);
  tx.commit();
  return revision;
}

namespace {

constexpr const char* kCurrentColumns =
    "SELECT c.mission_id, c.t_s, c.method, c.east_mps, c.north_mps, c.cov_ee, c.cov_en, c.cov_nn, "
    "c.speed_scale, c.residual_rms_mps, c.evidence, c.revision, c.reference_legs, "
    "c.rms_over_ground_mps, c.rms_through_water_mps, c.reference_separation_mps, "
    "c.speed_reference, c.drift_legs, c.drift_along_mps, c.drift_cross_mps, c.drift_mean_leg_s "
    "FROM mission_currents c ";

StoredCurrent current_from_row(Statement& s) {
  StoredCurrent c;
  c.mission_id = s.column_int64(0);
  c.t_s = s.column_double(1);
  c.method = s.column_text(2);
  c.estimate.east_mps = s.column_double(3);
  c.estimate.north_mps = s.column_double(4);
  c.estimate.covariance = {s.column_double(5), s.column_double(6), s.column_double(7)};
  c.estimate.speed_scale = s.column_double(8);
  c.estimate.residual_rms_mps = s.column_double(9);
  c.estimate.legs = static_cast<std::size_t>(s.column_int64(10));
  c.revision = s.column_int64(11);
  if (!s.is_null(12)) {
    kinematics::SpeedReferenceEvidence r;
    r.legs = static_cast<std::size_t>(s.column_int64(12));
    r.rms_over_ground_mps = s.column_double(13);
    r.rms_through_water_mps = s.column_double(14);
    r.separation_mps = s.column_double(15);
    if (!s.is_null(16)) {
      const std::string name = s.column_text(16);
      r.identified = kinematics::parse_speed_reference(name);
      if (!r.identified)
        throw StoreError("mission " + std::to_string(c.mission_id) +
                         " has unknown speed reference '" + name + "'");
    }
    c.speed_reference = r;
  }
  if (!s.is_null(17))
    c.drift_scatter =
        kinematics::DriftScatter{s.column_double(18), s.column_double(19),
                                 static_cast<std::size_t>(s.column_int64(17)), s.column_double(20)};
  return c;
}

}  // namespace

std::optional<StoredCurrent> Store::mission_current(std::int64_t mission_id) {
  auto s = db_.prepare(std::string(kCurrentColumns) + "WHERE c.mission_id = ?");
  s.bind(1, mission_id);
  if (!s.step()) return std::nullopt;
  return current_from_row(s);
}

std::optional<StoredCurrent> Store::latest_vehicle_current(const std::string& vehicle_id) {
  auto s = db_.prepare(std::string(kCurrentColumns) +
                       "JOIN missions m ON m.id = c.mission_id WHERE m.vehicle_id = ? "
                       "ORDER BY c.revision DESC LIMIT 1");
  s.bind(1, vehicle_id);
  if (!s.step()) return std::nullopt;
  return current_from_row(s);
}

std::vector<StoredCurrent> Store::vehicle_currents(const std::string& vehicle_id) {
  auto s = db_.prepare(std::string(kCurrentColumns) +
                       "JOIN missions m ON m.id = c.mission_id WHERE m.vehicle_id = ? "
                       "ORDER BY c.revision");
  s.bind(1, vehicle_id);
  std::vector<StoredCurrent> out;
  while (s.step())
    out.push_back(current_from_row(s));
  return out;
}

std::int64_t Store::current_revision(const std::string& vehicle_id) {
  auto s = db_.prepare(
      "SELECT coalesce(max(c.revision), 0) FROM mission_currents c JOIN missions m ON "
      "m.id = c.mission_id WHERE m.vehicle_id = ?");
  s.bind(1, vehicle_id);
  s.step();
  return s.column_int64(0);
}

std::vector<double> Store::turn_start_times(std::int64_t mission_id) {
  auto s = db_.prepare("SELECT start_time_s FROM turns WHERE mission_id = ? ORDER BY start_time_s");
  s.bind(1, mission_id);
  std::vector<double> out;
  while (s.step())
    out.push_back(s.column_double(0));
  return out;
}

std::int64_t Store::save_harvest(const HarvestRecord& h) {
  auto s = db_.prepare(
      "INSERT INTO harvests (mission_id, steps, harvested, already_recorded, rejected_json) "
      "VALUES (?, ?, ?, ?, ?)");
  s.bind(1, h.mission_id).bind(2, h.steps).bind(3, h.harvested).bind(4, h.already_recorded);
  s.bind(5, nlohmann::json(h.rejected).dump());
  s.run();
  return db_.last_insert_rowid();
}

std::vector<HarvestRecord> Store::list_harvests(std::int64_t mission_id) {
  auto s = db_.prepare(
      "SELECT id, mission_id, created_utc, steps, harvested, already_recorded, rejected_json "
      "FROM harvests WHERE mission_id = ? ORDER BY id");
  s.bind(1, mission_id);
  std::vector<HarvestRecord> out;
  while (s.step()) {
    HarvestRecord h;
    h.id = s.column_int64(0);
    h.mission_id = s.column_int64(1);
    h.created_utc = s.column_text(2);
    h.steps = s.column_int64(3);
    h.harvested = s.column_int64(4);
    h.already_recorded = s.column_int64(5);
    try {
      h.rejected =
          nlohmann::json::parse(s.column_text(6)).get<std::map<std::string, std::int64_t>>();
    } catch (const std::exception& e) {
      throw StoreError("harvest " + std::to_string(h.id) +
                       ": stored rejected_json is corrupt: " + e.what());
    }
    out.push_back(std::move(h));
  }
  return out;
}

void Store::append_nav(std::int64_t mission_id, std::span<const NavRow> rows) {
  Transaction tx(db_);
  insert_nav(db_, mission_id, rows);
  tx.commit();
}

std::int64_t Store::import_mission(const MissionImport& m) {
  // Everything serialised before the write lock, as store_turn does: a document that cannot be
  // written fails before the database is touched.
  std::vector<TurnDocuments> docs;
  docs.reserve(m.turns.size());
  for (const StoredTurn& t : m.turns) {
    std::string raw_json = kinematics::to_json_string(t.raw);
    docs.push_back(t.normalized
                       ? normalized_documents(std::move(raw_json), *t.normalized)
                       : TurnDocuments{std::move(raw_json), std::nullopt, std::nullopt, {}});
  }
  for (const auto& [index, turn] : m.water_turns)
    if (index >= m.turns.size())
      throw StoreError("water-frame turn " + std::to_string(index) + " of " +
                       std::to_string(m.turns.size()) + " turns");

  Transaction tx(db_);
  auto v = db_.prepare(
      "INSERT INTO vehicles (id, kind, max_speed_mps, length_m) VALUES (?, ?, ?, ?) "
      "ON CONFLICT (id) DO NOTHING");
  v.bind(1, m.vehicle.id).bind(2, m.vehicle.kind).bind(3, m.vehicle.max_speed_mps);
  v.bind(4, m.vehicle.length_m);
  v.run();
  const Mission& mi = m.mission;
  auto s = db_.prepare(
      "INSERT INTO missions (vehicle_id, name, config_json, status, created_utc, started_s, "
      "ended_s, status_reason) VALUES (?, ?, ?, ?, ?, ?, ?, ?)");
  s.bind(1, mi.vehicle_id).bind(2, mi.name).bind(3, mi.config_json).bind(4, to_string(mi.status));
  s.bind(5, mi.created_utc).bind(6, mi.started_s).bind(7, mi.ended_s).bind(8, mi.status_reason);
  s.run();
  const std::int64_t id = db_.last_insert_rowid();
  insert_nav(db_, id, m.nav);
  for (const MissionEvent& e : m.events)
    append_event(id, e.t_s, e.kind, e.message);
  for (const ConditionSetTiming& c : m.condition_sets)
    append_condition_set(id, c);
  std::vector<std::int64_t> turn_ids;
  turn_ids.reserve(m.turns.size());
  for (std::size_t i = 0; i < m.turns.size(); ++i)
    turn_ids.push_back(insert_turn(db_, id, m.turns[i].row, docs[i]));
  if (m.current) {
    std::vector<PackedWaterTurn> packed;
    for (const auto& [index, turn] : m.water_turns)
      packed.push_back(pack_water_turn(turn_ids[index], turn));
    StoredCurrent c = *m.current;
    c.mission_id = id;
    write_current(db_, c, packed);
  }
  tx.commit();
  return id;
}

std::vector<NavRow> Store::nav_for_mission(std::int64_t mission_id) {
  std::vector<NavRow> out;
  for_each_nav(mission_id, [&](const NavRow& r) { out.push_back(r); });
  return out;
}

void Store::for_each_nav(std::int64_t mission_id, const std::function<void(const NavRow&)>& fn) {
  // rowid breaks ties between samples stamped with the same time: insertion order.
  auto s = db_.prepare(
      "SELECT t_s, x_m, y_m, heading_deg, speed_mps, desired_heading_deg, desired_speed_mps, "
      "helm_mode FROM nav_samples WHERE mission_id = ? ORDER BY t_s, rowid");
  s.bind(1, mission_id);
  while (s.step())
    fn({s.column_double(0), s.column_double(1), s.column_double(2), s.column_double(3),
        s.column_double(4), s.column_optional_double(5), s.column_optional_double(6),
        s.column_text(7)});
}

std::int64_t Store::nav_count(std::int64_t mission_id) {
  auto s = db_.prepare("SELECT COUNT(*) FROM nav_samples WHERE mission_id = ?");
  s.bind(1, mission_id);
  return s.step() ? s.column_int64(0) : 0;
}

std::vector<NavPageRow> Store::nav_page(std::int64_t mission_id, std::int64_t after_rowid,
                                        int limit) {
  auto s = db_.prepare(
      "SELECT rowid, t_s, x_m, y_m, heading_deg, speed_mps, desired_heading_deg, "
      "desired_speed_mps, helm_mode FROM nav_samples WHERE mission_id = ? AND rowid > ? "
      "ORDER BY rowid LIMIT ?");
  s.bind(1, mission_id).bind(2, after_rowid).bind(3, limit);
  std::vector<NavPageRow> out;
  while (s.step())
    out.push_back({s.column_int64(0),
                   {s.column_double(1), s.column_double(2), s.column_double(3), s.column_double(4),
                    s.column_double(5), s.column_optional_double(6), s.column_optional_double(7),
                    s.column_text(8)}});
  return out;
}

std::int64_t Store::save_ckt_snapshot(const kinematics::Ckt& table,
                                      const std::vector<std::int64_t>& mission_ids) {
  const std::string ids = nlohmann::json(mission_ids).dump();
  const std::string doc = kinematics::ckt_to_json_string(table);
  auto s =
      db_.prepare("INSERT INTO ckt_snapshots (mission_ids, document, vehicle_id) VALUES (?, ?, ?)");
  s.bind(1, ids).bind(2, doc).bind(3, table.vehicle_id);
  s.run();
  return db_.last_insert_rowid();
}

std::int64_t Store::latest_ckt_snapshot_id(const std::string& vehicle_id) {
  auto s = db_.prepare("SELECT coalesce(max(id), 0) FROM ckt_snapshots WHERE vehicle_id = ?");
  s.bind(1, vehicle_id);
  s.step();
  return s.column_int64(0);
}

std::optional<CktSnapshot> Store::latest_ckt_snapshot(const std::string& vehicle_id) {
  auto s = db_.prepare(
      "SELECT id, created_utc, mission_ids, document FROM ckt_snapshots WHERE vehicle_id = ? "
      "ORDER BY id DESC LIMIT 1");
  s.bind(1, vehicle_id);
  if (!s.step()) return std::nullopt;
  CktSnapshot snap;
  snap.id = s.column_int64(0);
  snap.created_utc = s.column_text(1);
  snap.document = s.column_text(3);
  try {
    snap.mission_ids = nlohmann::json::parse(s.column_text(2)).get<std::vector<std::int64_t>>();
    snap.table = kinematics::parse_ckt_json(snap.document);
  } catch (const std::exception& e) {
    throw StoreError("CKT snapshot " + std::to_string(snap.id) + " is corrupt: " + e.what());
  }
  return snap;
}

namespace {

constexpr const char* kModelColumns =
    "id, created_utc, vehicle_id, training_missions, train_one_step_rms_deg, validation_mse_m2, "
    "validation_heading_rms_deg, document";

StoredModel read_model(const Statement& s) {
  StoredModel m;
  m.id = s.column_int64(0);
  m.created_utc = s.column_text(1);
  m.vehicle_id = s.column_text(2);
  m.train_one_step_rms_deg = s.column_optional_double(4);
  m.validation_mse_m2 = s.column_optional_double(5);
  m.validation_heading_rms_deg = s.column_optional_double(6);
  try {
    m.training_missions = nlohmann::json::parse(s.column_text(3)).get<std::vector<std::int64_t>>();
    m.model = kinematics::parse_yaw_model_json(s.column_text(7));
  } catch (const std::exception& e) {
    throw StoreError("yaw model " + std::to_string(m.id) + " is corrupt: " + e.what());
  }
  return m;
}

}  // namespace

std::int64_t Store::save_model(const StoredModel& m) {
  auto s = db_.prepare(
      "INSERT INTO yaw_models (vehicle_id, form, history, rate_hz, refined, training_missions, "
      "train_one_step_rms_deg, validation_mse_m2, validation_heading_rms_deg, document) "
      "VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
  s.bind(1, m.vehicle_id).bind(2, kinematics::to_string(m.model.form));
  s.bind(3, static_cast<std::int64_t>(m.model.history)).bind(4, m.model.rate_hz);
  s.bind(5, static_cast<std::int64_t>(m.model.refined ? 1 : 0));
  s.bind(6, nlohmann::json(m.training_missions).dump());
  s.bind(7, m.train_one_step_rms_deg).bind(8, m.validation_mse_m2);
  s.bind(9, m.validation_heading_rms_deg).bind(10, kinematics::yaw_model_to_json(m.model));
  s.run();
  return db_.last_insert_rowid();
}

std::optional<StoredModel> Store::get_model(std::int64_t id) {
  auto s = db_.prepare(std::string("SELECT ") + kModelColumns + " FROM yaw_models WHERE id = ?");
  s.bind(1, id);
  if (!s.step()) return std::nullopt;
  return read_model(s);
}

std::vector<StoredModel> Store::list_models(const std::optional<std::string>& vehicle_id) {
  auto s = db_.prepare(std::string("SELECT ") + kModelColumns +
                       " FROM yaw_models WHERE ?1 IS NULL OR vehicle_id = ?1 ORDER BY id");
  if (vehicle_id) s.bind(1, *vehicle_id);
  std::vector<StoredModel> out;
  while (s.step())
    out.push_back(read_model(s));
  return out;
}

std::optional<StoredModel> Store::latest_model(const std::optional<std::string>& vehicle_id) {
  auto s = db_.prepare(std::string("SELECT ") + kModelColumns +
                       " FROM yaw_models WHERE ?1 IS NULL OR vehicle_id = ?1 "
                       "ORDER BY id DESC LIMIT 1");
  if (vehicle_id) s.bind(1, *vehicle_id);
  if (!s.step()) return std::nullopt;
  return read_model(s);
}

void Store::overwrite_turn_json_for_testing(std::int64_t turn_id, std::string_view raw_json) {
  auto s = db_.prepare("UPDATE turns SET raw_json = ? WHERE id = ?");
  s.bind(1, raw_json).bind(2, turn_id);
  s.run();
}

}  // namespace avk::store
