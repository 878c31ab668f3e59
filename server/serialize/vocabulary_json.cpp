#include "server/serialize/vocabulary.hpp"

#include <string>

#include "kinematics/turn_sequence.hpp"
#include "mission/event_kind.hpp"
#include "mission/helm_mode.hpp"
#include "vehicle/vehicle.hpp"

namespace avk::server {

nlohmann::json vocabulary_json() {
  nlohmann::json kinds = nlohmann::json::array();
  for (const mission::EventKind k : mission::all_event_kinds()) {
    kinds.push_back({{"kind", std::string(mission::to_string(k))},
                     {"severity", std::string(mission::to_string(mission::severity(k)))}});
  }
  nlohmann::json modes = nlohmann::json::array();
  for (const mission::HelmMode m : mission::all_helm_modes())
    modes.push_back(mission::to_string(m));
  nlohmann::json links = nlohmann::json::array();
  for (const vehicle::LinkState l : vehicle::all_link_states())
    links.push_back(vehicle::to_string(l));
  nlohmann::json statuses = nlohmann::json::array();
  for (const auto s : {kinematics::TurnStatus::ok, kinematics::TurnStatus::aborted,
                       kinematics::TurnStatus::rejected})
    statuses.push_back(kinematics::to_string(s));
  return {{"event_kinds", std::move(kinds)},
          {"helm_modes", std::move(modes)},
          {"link_states", std::move(links)},
          {"turn_statuses", std::move(statuses)}};
}

}  // namespace avk::server
