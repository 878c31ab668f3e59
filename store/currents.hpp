#pragma once
// The current each mission flew in, as last estimated, and the water-frame form of its turns.

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "kinematics/current_estimate.hpp"
#include "kinematics/drift_scatter.hpp"
#include "kinematics/speed_reference.hpp"
#include "kinematics/turn_sequence.hpp"
#include "store/store_error.hpp"

namespace avk::store {

// The current a mission flew in, as last estimated (app/current.hpp), and how.
struct StoredCurrent {
  std::int64_t mission_id = 0;
  double t_s = 0.0;             // station clock: the end of the newest evidence used
  std::string method = "legs";  // legs (steady legs before turns) or turns (turn residuals)
  kinematics::CurrentEstimate estimate;
  std::int64_t revision = 0;  // grows with every save in the database: tells a cache it changed
  // Judged from the mission's steady legs in this current (app/vehicle_motion.hpp); none when not
  // evaluated (estimates stored before schema 12) or, for the scatter, too few legs.
  std::optional<kinematics::SpeedReferenceEvidence> speed_reference;
  std::optional<kinematics::DriftScatter> drift_scatter;
};

class CurrentRepository {
 public:
  virtual ~CurrentRepository() = default;

  // Replaces the mission's current estimate and the water-frame form of its turns (normalised,
  // each by turn id; turns not listed lose theirs) in one transaction, so a reader sees either the
  // old estimate with the old turns or the new with the new. Returns the new revision. Throws
  // StoreError for a turn that is not the mission's.
  virtual std::int64_t save(
      const StoredCurrent& current,
      const std::vector<std::pair<std::int64_t, kinematics::TurnSequence>>& water_turns) = 0;
  virtual std::optional<StoredCurrent> for_mission(std::int64_t mission_id) = 0;
  // The newest estimate (by revision) of any of the vehicle's missions.
  virtual std::optional<StoredCurrent> latest_for_vehicle(const std::string& vehicle_id) = 0;
  // Every stored estimate of the vehicle's missions, oldest revision first.
  virtual std::vector<StoredCurrent> for_vehicle(const std::string& vehicle_id) = 0;
  // The newest revision among the vehicle's missions (0: none): tells a cache whether the water
  // frame of its turns changed.
  virtual std::int64_t revision(const std::string& vehicle_id) = 0;
};

}  // namespace avk::store
