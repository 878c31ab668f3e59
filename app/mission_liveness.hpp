#pragma once
// Whether a mission stored as running or paused still has a process behind it. A mission whose
// process is gone (kill -9, power loss) reads as interrupted and can be resumed.

#include <cstdint>

#include "store/store.hpp"

namespace avk::app {

bool process_alive(std::int64_t pid);
store::MissionStatus effective_status(const store::Mission& m);
// Closes every mission stored as running or paused whose process is gone as interrupted, ended at
// the last mission-clock time anything of it was recorded (its navigation, usually); returns how
// many.
int mark_orphaned_missions_interrupted(store::Store& db);

}  // namespace avk::app
