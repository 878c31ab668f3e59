#pragma once
// Missions and what they record besides turns and navigation: their status, ConditionSet
// episodes and the operator's event log, and the summaries read over a mission's turns.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "kinematics/ckt.hpp"
#include "kinematics/turn_sequence.hpp"
#include "store/store_error.hpp"

namespace avk::store {

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
  // The station that created it (several may share a PostgreSQL database); none for a mission
  // stored before stations were recorded (schema 13) or by a store without a station id.
  std::optional<std::string> station_id;
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

class MissionRepository {
 public:
  virtual ~MissionRepository() = default;

  virtual std::int64_t create(const std::string& vehicle_id, const std::string& name,
                              const std::string& config_json) = 0;
  // Records the first start (running) and the end (interrupted/aborted/halted/done) on the
  // mission clock and in wall-clock time; running again (a resume) clears the end.
  // Throws StoreError for an unknown mission.
  virtual void set_status(std::int64_t mission_id, MissionStatus status, const std::string& reason,
                          double t_s) = 0;
  virtual std::optional<Mission> get(std::int64_t mission_id) = 0;
  virtual std::vector<Mission> list() = 0;  // by id
  // Throws StoreError for an unknown mission.
  virtual void set_runner(std::int64_t mission_id, std::optional<std::int64_t> pid) = 0;
  // A mission whose process died (kill -9, power loss) before it could store its end: interrupted
  // for `reason`, ended at end_s (mission clock), no runner. When that was in wall-clock time is
  // not known (nothing stored holds it), so ended_utc is cleared. Throws StoreError for an unknown
  // mission.
  virtual void close_orphaned(std::int64_t mission_id, const std::string& reason,
                              std::optional<double> end_s) = 0;

  // Both throw StoreError for an unknown mission or an outcome other than set/timeout/interrupted.
  virtual void append_condition_set(std::int64_t mission_id, const ConditionSetTiming& timing) = 0;
  virtual std::vector<ConditionSetTiming> condition_sets(std::int64_t mission_id) = 0;  // by start

  // Returns the event id. events is keyset-paginated: oldest first, ids > after_id.
  virtual std::int64_t append_event(std::int64_t mission_id, double t_s, const std::string& kind,
                                    const std::string& message) = 0;
  virtual std::vector<MissionEvent> events(std::int64_t mission_id, std::int64_t after_id = 0,
                                           int limit = 1000) = 0;

  // Latest mission-clock time anything of the mission was recorded at (nav t_s, turn end_time_s,
  // event t_s, condition set end_s); empty when nothing was. A resumed run continues its clock
  // after this so that times never repeat.
  virtual std::optional<double> clock_end_s(std::int64_t mission_id) = 0;
  // The latest of clock_end_s over every mission (0 without any): a station that runs missions
  // continues its clock after it, so stored times never repeat.
  virtual double station_clock_end_s() = 0;
  // Ordered by speed, then heading change.
  virtual std::vector<CellStats> cell_stats(std::int64_t mission_id) = 0;
  // Every mission's turns by status, in one query (a listing without a query per mission).
  virtual std::map<std::int64_t, TurnCounts> turn_counts() = 0;
};

}  // namespace avk::store
