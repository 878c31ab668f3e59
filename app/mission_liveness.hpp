#pragma once
// Whether a mission stored as running still has a process behind it. A mission whose process is
// gone (kill -9, power loss) reads as interrupted and can be resumed.

#include <cstdint>

#include "store/store.hpp"

namespace avk::app {

bool process_alive(std::int64_t pid);
store::MissionStatus effective_status(const store::Mission& m);
// Stores interrupted for every mission stored as running whose process is gone; returns how many.
int mark_orphaned_missions_interrupted(store::Store& db, double t_s);

}  // namespace avk::app
