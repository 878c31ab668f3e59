#pragma once
// A whole mission as another station recorded it (app/mission_mcap.hpp), for Store::import_mission.

#include <cstddef>
#include <optional>
#include <utility>
#include <vector>

#include "kinematics/turn_sequence.hpp"
#include "store/currents.hpp"
#include "store/missions.hpp"
#include "store/navigation.hpp"
#include "store/turns.hpp"
#include "vehicle/vehicle.hpp"

namespace avk::store {

struct MissionImport {
  vehicle::VehicleInfo vehicle;  // inserted when the database does not know the vehicle yet
  Mission mission;               // id and runner_pid are ignored: the mission gets a new id
  std::vector<NavRow> nav;
  std::vector<MissionEvent> events;  // id and mission_id ignored; stored in this order
  std::vector<ConditionSetTiming> condition_sets;
  // row.id and row.mission_id are ignored; every other row column is stored as given (not
  // recomputed), and the documents are stored as given too (their metadata's status included).
  std::vector<StoredTurn> turns;
  std::optional<StoredCurrent> current;  // mission_id and revision ignored
  // The water-frame form of turns (by index into `turns`), as CurrentRepository::save stores it.
  std::vector<std::pair<std::size_t, kinematics::TurnSequence>> water_turns;
};

}  // namespace avk::store
