#pragma once
// What the use cases answer about missions: the mission, its turns by status, its event log and
// its recorded navigation. These are the front ends' types, not the store's rows: a new column or
// a second database engine changes the store and the conversions in app/, no front end.

#include <cstdint>
#include <optional>
#include <string>

namespace avk::app {

// A stored mission's status; a mission whose process died reads as interrupted
// (app/mission_liveness.hpp).
enum class MissionStatus { created, running, paused, interrupted, aborted, halted, done };
const char* to_string(MissionStatus s);

struct MissionView {
  std::int64_t id = 0;
  std::string vehicle_id;
  std::string name;
  std::string config_json;                        // the mission file as started
  MissionStatus status = MissionStatus::created;  // as stored
  std::string status_reason;
  std::string created_utc;          // ISO 8601
  std::optional<double> started_s;  // mission clock of the first start
  std::optional<double> ended_s;    // mission clock of the end; none while it runs
  // Wall-clock (ISO 8601 UTC) start and end; none for a mission stored before they were kept.
  std::optional<std::string> started_utc;
  std::optional<std::string> ended_utc;
};

// A mission's turns by status.
struct TurnCounts {
  std::int64_t ok = 0, aborted = 0, rejected = 0;
  std::int64_t total() const { return ok + aborted + rejected; }
  friend bool operator==(const TurnCounts&, const TurnCounts&) = default;
};

// One entry of the operator's event log.
struct MissionEventView {
  std::int64_t id = 0;  // the cursor of the event pages
  std::int64_t mission_id = 0;
  double t_s = 0.0;  // mission clock
  // A mission::EventKind name; text, since events logged by older versions may hold kinds that no
  // longer exist and must still be listed.
  std::string kind;
  std::string message;
  friend bool operator==(const MissionEventView&, const MissionEventView&) = default;
};

// One navigation report as recorded, with the guidance input in force; rowid is the cursor of the
// track pages (insertion order, so a page boundary never moves while the mission records).
struct TrackPoint {
  std::int64_t rowid = 0;
  double t_s = 0.0;  // mission clock
  double x_m = 0.0;  // local grid: east
  double y_m = 0.0;  // local grid: north
  double heading_deg = 0.0;
  double speed_mps = 0.0;
  std::optional<double> desired_heading_deg;
  std::optional<double> desired_speed_mps;
  std::string helm_mode;
};

}  // namespace avk::app
