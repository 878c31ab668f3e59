#pragma once
// The station's SQLite store: vehicles, missions, recorded turns (raw and normalised), navigation
// samples and CKT snapshots. The only code in the project that writes SQL.
//
// One Store is one connection, for one thread. Several Stores (threads or processes) may open the
// same file: WAL mode lets readers see committed data while a writer works.

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "kinematics/ckt.hpp"
#include "kinematics/current_estimate.hpp"
#include "kinematics/drift_scatter.hpp"
#include "kinematics/speed_reference.hpp"
#include "kinematics/turn_sequence.hpp"
#include "kinematics/yaw_model.hpp"
#include "store/sqlite.hpp"
#include "vehicle/vehicle.hpp"

namespace avk::store {

// The schema version this code writes; opening a newer database is refused.
int schema_version();

// The SQL of migration step `index` (0-based: it moves a database from version index to
// index + 1), so a test can build a database exactly as an older release left it. Throws
// std::out_of_range outside [0, schema_version()).
std::string_view migration_step_sql(int index);

enum class MissionStatus { created, running, paused, interrupted, aborted, halted, done };
const char* to_string(MissionStatus s);
std::optional<MissionStatus> mission_status_from_string(std::string_view s);

struct Mission {
  std::int64_t id = 0;
  std::string vehicle_id;
  std::string name;
  std::string config_json;
  MissionStatus status = MissionStatus::created;
  std::string created_utc;          // ISO 8601, set by the database
  std::optional<double> started_s;  // mission clock of the first switch to running
  // mission clock of the switch to interrupted/aborted/halted/done; none while it runs again
  std::optional<double> ended_s;
  std::string status_reason;
  std::optional<std::int64_t> runner_pid;  // the process running the mission, if any
  // Wall-clock moments (ISO 8601 UTC, set by the database) of the first switch to running and of
  // the end; none for a mission stored before they were kept (schema 11).
  std::optional<std::string> started_utc;
  std::optional<std::string> ended_utc;
};

// Summary columns of a stored turn, readable without parsing its JSON.
struct TurnRow {
  std::int64_t id = 0;
  std::int64_t mission_id = 0;
  std::string vehicle_id;
  double cell_speed_mps = 0.0;     // commanded speed
  double cell_dheading_deg = 0.0;  // |goal|: the CKT stores right turns
  kinematics::TurnStatus status = kinematics::TurnStatus::ok;
  std::string reason;
  double commanded_speed_mps = 0.0;
  double goal_dheading_deg = 0.0;  // signed
  double observed_dheading_deg = 0.0;
  double start_time_s = 0.0;
  double end_time_s = 0.0;
  std::optional<double> advance_m;  // absent when the turn could not be normalised
  std::optional<double> transfer_m;
  std::optional<double> condition_set_time_s;
  std::optional<double> start_heading_error_deg;
  std::optional<double> start_yaw_rate_dps;
  kinematics::TurnSource source = kinematics::TurnSource::collection;
  std::optional<double> quality;          // harvested turns
  std::optional<double> speed_after_mps;  // u1 of a speed-change turn
};

// How steady the vehicle was when its turn was commanded, as the ConditionSet saw it.
struct TurnStart {
  std::optional<double> condition_set_time_s;
  std::optional<double> heading_error_deg;  // heading minus the held course
  std::optional<double> yaw_rate_dps;       // moving average
};

// Turns a read leaves out: one mission's, one turn.
struct TurnsLeftOut {
  std::optional<std::int64_t> mission_id;
  std::optional<std::int64_t> turn_id;
};

struct StoredTurn {
  TurnRow row;
  kinematics::TurnSequence raw;
  std::optional<kinematics::TurnSequence> normalized;
};

struct TurnFilter {
  std::optional<std::int64_t> mission_id;
  std::optional<double> speed_mps;     // matches commanded speed within speed_tolerance_mps
  std::optional<double> dheading_deg;  // matches the signed goal within dheading_tolerance_deg
  std::optional<kinematics::TurnStatus> status;
  double speed_tolerance_mps = 0.05;
  double dheading_tolerance_deg = 0.5;
  std::int64_t after_id = 0;  // keyset pagination: rows with id > after_id
  int limit = 100;
};

// One navigation report as the mission records it, with the guidance input in force.
struct NavRow {
  double t_s = 0.0;
  double x_m = 0.0;
  double y_m = 0.0;
  double heading_deg = 0.0;
  double speed_mps = 0.0;
  std::optional<double> desired_heading_deg;
  std::optional<double> desired_speed_mps;
  std::string helm_mode;
  friend bool operator==(const NavRow&, const NavRow&) = default;
};

// A navigation row with its rowid: the keyset cursor of nav_page.
struct NavPageRow {
  std::int64_t rowid = 0;
  NavRow row;
};

// One ConditionSet episode (thesis: the time spent establishing a turn's initial conditions).
struct ConditionSetTiming {
  double start_s = 0.0;
  double end_s = 0.0;
  double target_speed_mps = 0.0;
  std::string outcome;  // "set", "timeout", "interrupted"
  double duration_s() const { return end_s - start_s; }
  friend bool operator==(const ConditionSetTiming&, const ConditionSetTiming&) = default;
};

// One entry of the operator's event log of a mission.
struct MissionEvent {
  std::int64_t id = 0;
  std::int64_t mission_id = 0;
  double t_s = 0.0;
  // A mission::EventKind name ("containment", "turn_aborted", ...). Kept as text: rows written by
  // older versions may hold kinds that no longer exist, and must still be listed.
  std::string kind;
  std::string message;
  friend bool operator==(const MissionEvent&, const MissionEvent&) = default;
};

// A mission's turns by status.
struct TurnCounts {
  std::int64_t ok = 0, aborted = 0, rejected = 0;
  std::int64_t total() const { return ok + aborted + rejected; }
  void add(kinematics::TurnStatus s, std::int64_t n = 1) {
    (s == kinematics::TurnStatus::ok        ? ok
     : s == kinematics::TurnStatus::aborted ? aborted
                                            : rejected) += n;
  }
  friend bool operator==(const TurnCounts&, const TurnCounts&) = default;
};

// Per turn-array cell of one mission: cell = (cell_speed_mps, cell_dheading_deg) as stored.
struct CellStats {
  double speed_mps = 0.0;
  double dheading_deg = 0.0;  // |goal|, as cell_dheading_deg
  std::int64_t n_ok = 0, n_aborted = 0, n_rejected = 0;
  std::optional<kinematics::MeanSd> advance_m;  // over ok turns; absent with no ok turn
  std::optional<kinematics::MeanSd> transfer_m;
  std::optional<kinematics::MeanSd> condition_set_time_s;  // over ok turns that have one
  std::optional<double> speed_after_mps;  // a speed-change cell (u0 -> u1); empty: constant speed
};

// An identified black-box yaw model with its provenance and validation errors.
struct StoredModel {
  std::int64_t id = 0;
  std::string created_utc;
  std::string vehicle_id;
  std::vector<std::int64_t> training_missions;
  kinematics::YawModel model;
  std::optional<double> train_one_step_rms_deg;
  std::optional<double> validation_mse_m2;  // trajectory position MSE on validation turns
  std::optional<double> validation_heading_rms_deg;
};

struct CktSnapshot {
  std::int64_t id = 0;
  std::string created_utc;
  std::vector<std::int64_t> mission_ids;
  std::string document;  // the CKT file (docs/ckt-format.md) as saved
  kinematics::Ckt table;
};

// The current a mission flew in, as last estimated (app/current.hpp), and how.
struct StoredCurrent {
  std::int64_t mission_id = 0;
  double t_s = 0.0;             // station clock: the end of the newest evidence used
  std::string method = "legs";  // legs (steady legs before turns) or turns (turn residuals)
  kinematics::CurrentEstimate estimate;
  std::int64_t revision = 0;  // grows with every save in the database: tells a cache it changed
  // Judged from the mission's steady legs in this current (app/vehicle_motion.hpp); none when not
  // evaluated (estimates stored before schema 12) or, for the scatter, too few legs.
  std::optional<kinematics::SpeedReferenceEvidence> speed_reference;
  std::optional<kinematics::DriftScatter> drift_scatter;
};

// Which form of a turn the table reads.
enum class TurnFrameChoice {
  ground,             // as navigated
  water_where_known,  // the water-frame form where the mission has a current estimate
};

// One harvest run over a mission's navigation (mission/turn_harvester.hpp): how many steps of
// the desired heading it judged, how many turns it stored, and the others by reason.
struct HarvestRecord {
  std::int64_t id = 0;
  std::int64_t mission_id = 0;
  std::string created_utc;
  std::int64_t steps = 0;
  std::int64_t harvested = 0;
  std::int64_t already_recorded = 0;
  std::map<std::string, std::int64_t> rejected;  // reason -> count (reasons with a count only)
};

// A whole mission as another station recorded it (app/mission_mcap.hpp), for import_mission.
struct MissionImport {
  vehicle::VehicleInfo vehicle;  // inserted when the database does not know the vehicle yet
  Mission mission;               // id and runner_pid are ignored: the mission gets a new id
  std::vector<NavRow> nav;
  std::vector<MissionEvent> events;  // id and mission_id ignored; stored in this order
  std::vector<ConditionSetTiming> condition_sets;
  // row.id and row.mission_id are ignored; every other row column is stored as given (not
  // recomputed), and the documents are stored as given too (their metadata's status included).
  std::vector<StoredTurn> turns;
  std::optional<StoredCurrent> current;  // mission_id and revision ignored
  // The water-frame form of turns (by index into `turns`), as save_mission_current stores it.
  std::vector<std::pair<std::size_t, kinematics::TurnSequence>> water_turns;
};

class Store {
 public:
  // Opens (creating if needed) and migrates the database. ":memory:" gives a private in-memory
  // database. Throws StoreError for a database newer than this code or any SQLite failure.
  explicit Store(const std::string& path);

  int user_version();
  std::string journal_mode();
  bool integrity_check();  // PRAGMA integrity_check says "ok"

  void upsert_vehicle(const vehicle::VehicleInfo& info);
  std::optional<vehicle::VehicleInfo> get_vehicle(const std::string& id);

  std::int64_t create_mission(const std::string& vehicle_id, const std::string& name,
                              const std::string& config_json);
  // Records the first start (running) and the end (interrupted/aborted/halted/done) on the
  // mission clock and in wall-clock time; running again (a resume) clears the end.
  // Throws StoreError for an unknown mission.
  void set_mission_status(std::int64_t mission_id, MissionStatus status, const std::string& reason,
                          double t_s);
  std::optional<Mission> get_mission(std::int64_t mission_id);
  std::vector<Mission> list_missions();
  // Throws StoreError for an unknown mission.
  void set_mission_runner(std::int64_t mission_id, std::optional<std::int64_t> pid);
  // A mission whose process died (kill -9, power loss) before it could store its end: interrupted
  // for `reason`, ended at end_s (mission clock), no runner. When that was in wall-clock time is
  // not known (nothing stored holds it), so ended_utc is cleared. Throws StoreError for an unknown
  // mission.
  void close_orphaned_mission(std::int64_t mission_id, const std::string& reason,
                              std::optional<double> end_s);

  // Both throw StoreError for an unknown mission or an outcome other than set/timeout/interrupted.
  void append_condition_set(std::int64_t mission_id, const ConditionSetTiming& timing);
  std::vector<ConditionSetTiming> condition_sets(std::int64_t mission_id);  // by start_s

  // Returns the event id. list_events is keyset-paginated: oldest first, ids > after_id.
  std::int64_t append_event(std::int64_t mission_id, double t_s, const std::string& kind,
                            const std::string& message);
  std::vector<MissionEvent> list_events(std::int64_t mission_id, std::int64_t after_id = 0,
                                        int limit = 1000);

  // Latest mission-clock time anything of the mission was recorded at (nav t_s, turn end_time_s,
  // event t_s, condition set end_s); empty when nothing was. A resumed run continues its clock
  // after this so that times never repeat.
  std::optional<double> mission_clock_end_s(std::int64_t mission_id);
  // The latest of mission_clock_end_s over every mission (0 without any): a station that runs
  // missions continues its clock after it, so stored times never repeat.
  double station_clock_end_s();
  // Ordered by speed, then heading change.
  std::vector<CellStats> mission_cell_stats(std::int64_t mission_id);
  // Every mission's turns by status, in one query (a listing without a query per mission).
  std::map<std::int64_t, TurnCounts> turn_counts_by_mission();

  // Stores the turn with the given status and reason (written into its metadata too), its
  // normalised form and advance/transfer, in one transaction. A turn that cannot be normalised
  // is kept without the normalised form only when it is not ok. Returns the turn id.
  std::int64_t store_turn(std::int64_t mission_id, const kinematics::TurnSequence& raw,
                          kinematics::TurnStatus status, const std::string& reason,
                          const TurnStart& start = {});
  // The id of the vehicle's newest ok turn (0 without any): tells a cache whether the vehicle's
  // table changed. Collection turns only unless include_harvested.
  std::int64_t newest_ok_turn_id(const std::string& vehicle_id, bool include_harvested = false);
  // Oldest first, at most filter.limit rows with id > filter.after_id.
  std::vector<TurnRow> list_turns(const TurnFilter& filter);
  // The turn's summary columns alone (its documents are not read).
  std::optional<TurnRow> get_turn_row(std::int64_t turn_id);
  // Throws StoreError naming the turn when its stored JSON is corrupt.
  std::optional<StoredTurn> get_turn(std::int64_t turn_id);
  // Normalised turns of status ok for the CKT, oldest first, from the given missions (empty: all
  // missions), optionally of one vehicle. Each equals get_turn(id)->normalized. Reads the packed
  // samples; turns stored before schema 2 have none and are parsed from their JSON instead.
  // Collection turns only, unless include_harvested. With water_where_known, a turn that has a
  // water-frame form (save_mission_current) is read in it. left_out: every turn but those (a
  // turn shown against predictions that never saw it or its mission).
  std::vector<kinematics::TurnSequence> load_normalized_turns(
      const std::vector<std::int64_t>& mission_ids,
      const std::optional<std::string>& vehicle_id = std::nullopt, bool include_harvested = false,
      TurnFrameChoice frame = TurnFrameChoice::ground, const TurnsLeftOut& left_out = {});
  // Start times of every turn stored for the mission (any status or source), ascending.
  std::vector<double> turn_start_times(std::int64_t mission_id);

  // Harvest runs of a mission, oldest first. save_harvest ignores h.id and h.created_utc.
  std::int64_t save_harvest(const HarvestRecord& h);
  std::vector<HarvestRecord> list_harvests(std::int64_t mission_id);

  // Replaces the mission's current estimate and the water-frame form of its turns (normalised,
  // each by turn id; turns not listed lose theirs) in one transaction, so a reader sees either the
  // old estimate with the old turns or the new with the new. Returns the new revision. Throws
  // StoreError for a turn that is not the mission's.
  std::int64_t save_mission_current(
      const StoredCurrent& current,
      const std::vector<std::pair<std::int64_t, kinematics::TurnSequence>>& water_turns);
  std::optional<StoredCurrent> mission_current(std::int64_t mission_id);
  // The newest estimate (by revision) of any of the vehicle's missions.
  std::optional<StoredCurrent> latest_vehicle_current(const std::string& vehicle_id);
  // Every stored estimate of the vehicle's missions, oldest revision first.
  std::vector<StoredCurrent> vehicle_currents(const std::string& vehicle_id);
  // The newest revision among the vehicle's missions (0: none): tells a cache whether the water
  // frame of its turns changed.
  std::int64_t current_revision(const std::string& vehicle_id);

  // Stores the mission with everything it recorded in one transaction: on any failure the
  // database is left as it was. Returns the new mission id. Throws StoreError.
  std::int64_t import_mission(const MissionImport& m);

  // One transaction, one prepared statement for the whole batch.
  void append_nav(std::int64_t mission_id, std::span<const NavRow> rows);
  std::vector<NavRow> nav_for_mission(std::int64_t mission_id);
  // The same rows in the same order (time, then insertion), one at a time: a long mission's
  // navigation need not be held whole. fn may read through this Store.
  void for_each_nav(std::int64_t mission_id, const std::function<void(const NavRow&)>& fn);
  // How many navigation rows the mission holds: what a reader reserves before for_each_nav.
  std::int64_t nav_count(std::int64_t mission_id);
  // Keyset pagination in insertion (rowid) order: at most `limit` rows with rowid > after_rowid.
  // Insertion order, not time order, so that a page boundary never moves while a mission records.
  std::vector<NavPageRow> nav_page(std::int64_t mission_id, std::int64_t after_rowid, int limit);

  std::int64_t save_ckt_snapshot(const kinematics::Ckt& table,
                                 const std::vector<std::int64_t>& mission_ids);
  // The newest snapshot of the vehicle's table. Throws StoreError when its stored document no
  // longer parses.
  std::optional<CktSnapshot> latest_ckt_snapshot(const std::string& vehicle_id);
  // Its id alone (0: none), without reading the document: tells a cache whether it changed.
  std::int64_t latest_ckt_snapshot_id(const std::string& vehicle_id);

  // Returns the model id (m.id is ignored). Reads throw StoreError for a corrupt document.
  std::int64_t save_model(const StoredModel& m);
  std::optional<StoredModel> get_model(std::int64_t id);
  std::vector<StoredModel> list_models(const std::optional<std::string>& vehicle_id = {});
  std::optional<StoredModel> latest_model(const std::optional<std::string>& vehicle_id = {});

  // Test seams. The hook runs inside store_turn's transaction after each step ("turn_inserted"),
  // so a test can fail it halfway; overwrite_turn_json_for_testing corrupts a stored turn.
  void set_store_turn_hook_for_testing(std::function<void(std::string_view step)> hook) {
    store_turn_hook_ = std::move(hook);
  }
  void overwrite_turn_json_for_testing(std::int64_t turn_id, std::string_view raw_json);

 private:
  void migrate();

  Connection db_;
  std::function<void(std::string_view)> store_turn_hook_;
};

}  // namespace avk::store
