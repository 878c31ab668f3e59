#pragma once
// Collection missions as the station runs and reports them: validate, start on the station's
// vehicle, pause/resume/abort, list, the report (planned cells merged with what is stored or
// live), the event log and the recorded track.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "app/mission_views.hpp"
#include "app/result.hpp"
#include "app/turn_views.hpp"
#include "kinematics/ckt.hpp"
#include "mission/helm_mode.hpp"
#include "mission/mission_config.hpp"
#include "mission/mission_observer.hpp"
#include "mission/mission_runner.hpp"

namespace avk::app {

class Context;

// Every problem of a mission document at once (invalid_argument with Error::fields).
Result<mission::MissionConfig> validate_mission(const std::string& config_text,
                                                double max_speed_mps);

// Stores the mission and hands it to that vehicle of the station; the mission id. conflict when the
// vehicle is not this station's or another mission runs.
Result<std::int64_t> start_mission(Context& ctx, const std::string& vehicle_id,
                                   const std::string& config_text);

// One turn-array cell of a mission: what was planned, how its turns went, their statistics.
struct CellReport {
  double speed_mps = 0.0;
  double dheading_deg = 0.0;  // |goal|
  int planned = 0;            // 0: not in the turn array (an imported log's turns)
  std::int64_t ok = 0, aborted = 0, rejected = 0;
  int given_up = 0;                             // live only: cells whose turns failed too often
  bool running = false;                         // live only: the cell of the turn under way
  std::optional<kinematics::MeanSd> advance_m;  // over ok turns
  std::optional<kinematics::MeanSd> transfer_m;
  std::optional<kinematics::MeanSd> condition_set_time_s;
  std::optional<double> speed_after_mps;  // a speed-change cell (speed_mps -> this)
};

// A mission's cells as its runner sees them now (the live stream's progress).
std::vector<CellReport> cell_reports(const std::vector<mission::CellProgress>& cells);

struct MissionSummary {
  MissionView mission;
  MissionStatus status;  // a mission stored as running whose process died: interrupted
  TurnCounts turns;
};

struct MissionReport {
  MissionSummary summary;
  // Attached to its vehicle's loop now: state and helm from the same live moment.
  bool live = false;
  std::optional<mission::MissionState> live_state;   // live, none until it starts
  std::optional<mission::HelmMode> helm_mode;        // live only
  std::optional<mission::RunningTurn> running_turn;  // live only: the turn under way
  std::vector<CellReport> cells;
  std::optional<double> duration_s;  // mission clock, start to end
  // ConditionSet episodes by outcome ("set", "timeout", "interrupted"), and the time to set.
  std::map<std::string, int> condition_set_episodes;
  std::optional<kinematics::MeanSd> condition_set_time_s;
  std::size_t condition_set_count = 0;
  // Every turn of the mission, oldest first: how steady each began (heading error and yaw rate
  // at its start) as well as how it ended.
  std::vector<TurnView> turns;
};

// The status a front end shows: the live state while the mission runs, else the stored one.
std::string status_text(const MissionReport& r);

std::vector<MissionSummary> list_missions(Context& ctx,
                                          const std::optional<std::string>& vehicle_id);
// The one vehicle the missions were run on (every stored mission when none are named):
// not_found for an unknown mission or an empty database, invalid_argument (field "vehicle")
// naming them when they are of several vehicles.
Result<std::string> vehicle_of_missions(Context& ctx, const std::vector<std::int64_t>& mission_ids);
// Where the station clock continues: after every time stored, so that times never repeat.
double station_clock_start_s(Context& ctx);
Result<MissionSummary> mission_summary(Context& ctx, std::int64_t mission_id);
Result<MissionReport> mission_report(Context& ctx, std::int64_t mission_id);

enum class MissionCommand { pause, resume, abort };
const char* to_string(MissionCommand c);
// Applies the command to the running mission, or resumes a stored one on its vehicle;
// the report after the command took effect. conflict when it cannot apply now.
Result<MissionReport> command_mission(Context& ctx, std::int64_t mission_id, MissionCommand c);

// Keyset pages: items after the cursor, oldest first; next is the cursor of the next page (none
// when this one is the last).
template <class T>
struct Page {
  std::vector<T> items;
  std::optional<std::int64_t> next;
};
// The page of rows read with this limit: a full page has a next cursor, the last one has none.
template <class T, class Cursor>
Page<T> make_page(std::vector<T> items, int limit, Cursor cursor) {
  Page<T> page;
  page.items = std::move(items);
  if (!page.items.empty() && static_cast<int>(page.items.size()) == limit)
    page.next = cursor(page.items.back());
  return page;
}
Result<Page<MissionEventView>> mission_events(Context& ctx, std::int64_t mission_id,
                                              std::int64_t after, int limit);
// The recorded navigation; the cursor is the row id, so rows recorded while a client pages are
// appended after it and nothing is skipped or repeated.
Result<Page<TrackPoint>> mission_track(Context& ctx, std::int64_t mission_id, std::int64_t after,
                                       int limit);

// Where the mission's vehicle was last seen: its latest navigation report. not_found for an
// unknown mission and for one that recorded no navigation.
Result<TrackPoint> mission_last_position(Context& ctx, std::int64_t mission_id);

}  // namespace avk::app
