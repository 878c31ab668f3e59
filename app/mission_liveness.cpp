#include "app/mission_liveness.hpp"

#include <signal.h>

#include <cerrno>
#include <fstream>
#include <string>

#include "app/station_identity.hpp"

namespace avk::app {

bool process_alive(std::int64_t pid) {
  if (pid <= 0 || (::kill(static_cast<pid_t>(pid), 0) != 0 && errno != EPERM)) return false;
  // A killed process that its parent has not reaped yet still answers kill(0): a zombie.
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  if (!std::getline(stat, line)) return true;
  const auto paren = line.rfind(')');
  return paren == std::string::npos || paren + 2 >= line.size() || line[paren + 2] != 'Z';
}

// A paused mission is held by its process as much as a running one: the process waits for the
// operator's resume. Without the process nobody can resume it there, so it is interrupted too.
bool held_by_a_process(store::MissionStatus s) {
  return s == store::MissionStatus::running || s == store::MissionStatus::paused;
}

// Another station's mission is run by a process on another machine: its pid says nothing here,
// so its stored status stands.
bool run_by_another_station(const store::Mission& m) {
  return m.station_id && *m.station_id != station_id();
}

store::MissionStatus effective_status(const store::Mission& m) {
  if (held_by_a_process(m.status) && !run_by_another_station(m) &&
      (!m.runner_pid || !process_alive(*m.runner_pid))) {
    return store::MissionStatus::interrupted;
  }
  return m.status;
}

int mark_orphaned_missions_interrupted(store::Store& db) {
  int n = 0;
  for (const auto& m : db.missions().list()) {
    if (held_by_a_process(m.status) && effective_status(m) == store::MissionStatus::interrupted) {
      // Nothing recorded: it ended where it started.
      const auto end_s = db.missions().clock_end_s(m.id);
      db.missions().close_orphaned(m.id, "the process running it stopped",
                                   end_s ? end_s : m.started_s);
      ++n;
    }
  }
  return n;
}

}  // namespace avk::app
