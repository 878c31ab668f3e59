#include "store/missions.hpp"

#include <iterator>

namespace avk::store {

namespace {

// The names as stored: the status column holds them, so they never change.
constexpr const char* kMissionStatusNames[] = {"created", "running", "paused", "interrupted",
                                               "aborted", "halted",  "done"};

}  // namespace

const char* to_string(MissionStatus s) {
  return kMissionStatusNames[static_cast<int>(s)];
}

std::optional<MissionStatus> mission_status_from_string(std::string_view s) {
  for (int i = 0; i < static_cast<int>(std::size(kMissionStatusNames)); ++i)
    if (s == kMissionStatusNames[i]) return static_cast<MissionStatus>(i);
  return std::nullopt;
}

}  // namespace avk::store
