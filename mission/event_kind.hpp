#pragma once
// The kinds of entry in a mission's event log and of the live stream's status messages, with how
// loudly an operator is told about each. One list, so that the store, the stream, the command
// line and the dashboard (through the stream's hello) cannot disagree about a name or a severity.
// The names are stored in the database and sent over the API: never rename one.

#include <optional>
#include <string_view>
#include <vector>

namespace avk::mission {

enum class EventKind {
  // Events of a running mission (MissionObserver::on_event, stored in its event log).
  link,                   // navigation lost or back
  condition_set_timeout,  // the conditions for a turn were not set in time
  containment,            // the vehicle reached the buffer zone: heading for the interior
  turning_back,           // too little room ahead to set conditions: turning inward first
  turn_rejected,          // a finished turn failed the anomaly checks
  turn_given_up,          // a cell's turn failed for the last allowed time
  turn_aborted,           // a turn ended before its goal heading
  excitation,             // persistent excitation started
  returning,              // all done: heading for the return point
  pause,
  resume,
  halted,       // the mission stopped itself (left the operating region)
  aborted,      // an operator aborted the mission
  interrupted,  // the station process went away mid-mission
  // Station status (the stream's status topic only): a mission attached to or detached from the
  // vehicle, and a mission's state changes (mission_<MissionState>).
  mission_attached,
  mission_detached,
  mission_running,
  mission_paused,
  mission_interrupted,
  mission_aborted,
  mission_halted,
  mission_done,
  // The operator commanded the vehicle (hold, go to, return, stop), or a mission's end left it
  // holding at its return point; and the vehicle arrived at the point it holds.
  vehicle_command,
  arrived,
  // A vehicle of the station's fleet reported for the first time or again after its link was
  // lost, and one whose link was lost (the station no longer knows where it is).
  vehicle_joined,
  vehicle_left,
  // Two vehicles (of the fleet, or one of them an AIS contact) are predicted to pass closer than
  // the standoff within the watch's horizon; and the pair is predicted clear again.
  collision_watch,
  collision_clear,
};

enum class Severity { info, warning };

std::string_view to_string(EventKind k);
std::optional<EventKind> event_kind_from_string(std::string_view s);
std::string_view to_string(Severity s);
// Warnings are what an operator must not miss: something went wrong or the mission stopped short.
Severity severity(EventKind k);
// Every kind, in declaration order.
const std::vector<EventKind>& all_event_kinds();

}  // namespace avk::mission
