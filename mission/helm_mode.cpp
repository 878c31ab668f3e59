#include "mission/helm_mode.hpp"

#include <array>

namespace avk::mission {

namespace {
constexpr std::array<const char*, 11> kNames = {"CONTAINING", "CONDITIONING", "TURNING", "EXCITING",
                                                "RETURNING",  "PAUSED",       "DONE",    "HALTED",
                                                "TRANSITING", "HOLDING",      "STOPPED"};
}

const char* to_string(HelmMode m) {
  return kNames[static_cast<std::size_t>(m)];
}

std::optional<HelmMode> helm_mode_from_string(std::string_view s) {
  for (std::size_t i = 0; i < kNames.size(); ++i)
    if (s == kNames[i]) return static_cast<HelmMode>(i);
  return std::nullopt;
}

const std::vector<HelmMode>& all_helm_modes() {
  static const std::vector<HelmMode> all = [] {
    std::vector<HelmMode> out;
    for (std::size_t i = 0; i < kNames.size(); ++i)
      out.push_back(static_cast<HelmMode>(i));
    return out;
  }();
  return all;
}

bool commands_motion(HelmMode m) {
  return m == HelmMode::containing || m == HelmMode::conditioning || m == HelmMode::turning ||
         m == HelmMode::exciting || m == HelmMode::returning || m == HelmMode::transiting ||
         m == HelmMode::holding;
}

}  // namespace avk::mission
