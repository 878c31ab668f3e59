#include "mission/event_kind.hpp"

namespace avk::mission {

// A switch without a default: the compiler names any kind added to the enum but not here.
std::string_view to_string(EventKind k) {
  switch (k) {
    case EventKind::link:
      return "link";
    case EventKind::condition_set_timeout:
      return "condition_set_timeout";
    case EventKind::containment:
      return "containment";
    case EventKind::turning_back:
      return "turning_back";
    case EventKind::turn_rejected:
      return "turn_rejected";
    case EventKind::turn_given_up:
      return "turn_given_up";
    case EventKind::turn_aborted:
      return "turn_aborted";
    case EventKind::excitation:
      return "excitation";
    case EventKind::returning:
      return "returning";
    case EventKind::pause:
      return "pause";
    case EventKind::resume:
      return "resume";
    case EventKind::halted:
      return "halted";
    case EventKind::aborted:
      return "aborted";
    case EventKind::interrupted:
      return "interrupted";
    case EventKind::mission_attached:
      return "mission_attached";
    case EventKind::mission_detached:
      return "mission_detached";
    case EventKind::mission_running:
      return "mission_running";
    case EventKind::mission_paused:
      return "mission_paused";
    case EventKind::mission_interrupted:
      return "mission_interrupted";
    case EventKind::mission_aborted:
      return "mission_aborted";
    case EventKind::mission_halted:
      return "mission_halted";
    case EventKind::mission_done:
      return "mission_done";
    case EventKind::vehicle_command:
      return "vehicle_command";
    case EventKind::arrived:
      return "arrived";
    case EventKind::vehicle_joined:
      return "vehicle_joined";
    case EventKind::vehicle_left:
      return "vehicle_left";
    case EventKind::collision_watch:
      return "collision_watch";
    case EventKind::collision_clear:
      return "collision_clear";
  }
  return {};  // not an enumerator: all_event_kinds() stops here
}

std::optional<EventKind> event_kind_from_string(std::string_view s) {
  for (const EventKind k : all_event_kinds())
    if (to_string(k) == s) return k;
  return std::nullopt;
}

std::string_view to_string(Severity s) {
  switch (s) {
    case Severity::info:
      return "info";
    case Severity::warning:
      return "warning";
  }
  return "info";
}

Severity severity(EventKind k) {
  switch (k) {
    case EventKind::link:
    case EventKind::condition_set_timeout:
    case EventKind::containment:
    case EventKind::turn_rejected:
    case EventKind::turn_given_up:
    case EventKind::turn_aborted:
    case EventKind::halted:
    case EventKind::aborted:
    case EventKind::interrupted:
    case EventKind::vehicle_left:
    case EventKind::collision_watch:
      return Severity::warning;
    case EventKind::excitation:
    case EventKind::returning:
    case EventKind::turning_back:
    case EventKind::pause:
    case EventKind::resume:
    case EventKind::mission_attached:
    case EventKind::mission_detached:
    case EventKind::mission_running:
    case EventKind::mission_paused:
    case EventKind::mission_interrupted:
    case EventKind::mission_aborted:
    case EventKind::mission_halted:
    case EventKind::mission_done:
    case EventKind::vehicle_command:
    case EventKind::arrived:
    case EventKind::vehicle_joined:
    case EventKind::collision_clear:
      return Severity::info;
  }
  return Severity::info;
}

const std::vector<EventKind>& all_event_kinds() {
  // The enumerators are 0..n-1 and to_string names each of them (the switch is checked), so
  // walking until the first unnamed value lists them all without a second list to keep in step.
  static const std::vector<EventKind> all = [] {
    std::vector<EventKind> out;
    for (int i = 0; !to_string(static_cast<EventKind>(i)).empty(); ++i)
      out.push_back(static_cast<EventKind>(i));
    return out;
  }();
  return all;
}

}  // namespace avk::mission
