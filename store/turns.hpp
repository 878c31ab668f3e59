#pragma once
// Recorded turns: each turn's summary columns, its raw document and its normalised form, and the
// reads the CKT and the reports make of them.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "kinematics/turn_sequence.hpp"
#include "store/store_error.hpp"

namespace avk::store {

// Summary columns of a stored turn, readable without parsing its JSON.
struct TurnRow {
  std::int64_t id = 0;
  std::int64_t mission_id = 0;
  std::string vehicle_id;
  double cell_speed_mps = 0.0;     // commanded speed
  double cell_dheading_deg = 0.0;  // |goal|: the CKT stores right turns
  kinematics::TurnStatus status = kinematics::TurnStatus::ok;
  std::string reason;
  double commanded_speed_mps = 0.0;
  double goal_dheading_deg = 0.0;  // signed
  double observed_dheading_deg = 0.0;
  double start_time_s = 0.0;
  double end_time_s = 0.0;
  std::optional<double> advance_m;  // absent when the turn could not be normalised
  std::optional<double> transfer_m;
  std::optional<double> condition_set_time_s;
  std::optional<double> start_heading_error_deg;
  std::optional<double> start_yaw_rate_dps;
  kinematics::TurnSource source = kinematics::TurnSource::collection;
  std::optional<double> quality;          // harvested turns
  std::optional<double> speed_after_mps;  // u1 of a speed-change turn
  // The key the recording station gave the turn (add's record_key); none for turns stored
  // without one (before schema 13, imports).
  std::optional<std::string> record_key;
};

// How steady the vehicle was when its turn was commanded, as the ConditionSet saw it.
struct TurnStart {
  std::optional<double> condition_set_time_s;
  std::optional<double> heading_error_deg;  // heading minus the held course
  std::optional<double> yaw_rate_dps;       // moving average
};

// Turns a read leaves out: one mission's, one turn.
struct TurnsLeftOut {
  std::optional<std::int64_t> mission_id;
  std::optional<std::int64_t> turn_id;
};

struct StoredTurn {
  TurnRow row;
  kinematics::TurnSequence raw;
  std::optional<kinematics::TurnSequence> normalized;
};

struct TurnFilter {
  std::optional<std::int64_t> mission_id;
  std::optional<double> speed_mps;     // matches commanded speed within speed_tolerance_mps
  std::optional<double> dheading_deg;  // matches the signed goal within dheading_tolerance_deg
  std::optional<kinematics::TurnStatus> status;
  double speed_tolerance_mps = 0.05;
  double dheading_tolerance_deg = 0.5;
  std::int64_t after_id = 0;  // keyset pagination: rows with id > after_id
  int limit = 100;
};

// Which form of a turn the table reads.
enum class TurnFrameChoice {
  ground,             // as navigated
  water_where_known,  // the water-frame form where the mission has a current estimate
};

class TurnRepository {
 public:
  virtual ~TurnRepository() = default;

  // Stores the turn with the given status and reason (written into its metadata too), its
  // normalised form and advance/transfer, in one transaction. A turn that cannot be normalised
  // is kept without the normalised form only when it is not ok. Returns the turn id.
  // record_key (non-empty): a key unique to this turn, given by the station that recorded it; a
  // turn already stored under the key is not stored again, and its id is returned. A write whose
  // outcome was unknown (the connection broke during its commit) can so be tried again safely.
  virtual std::int64_t add(std::int64_t mission_id, const kinematics::TurnSequence& raw,
                           kinematics::TurnStatus status, const std::string& reason,
                           const TurnStart& start = {}, const std::string& record_key = {}) = 0;
  // The id of the vehicle's newest ok turn (0 without any): tells a cache whether the vehicle's
  // table changed. Collection turns only unless include_harvested.
  virtual std::int64_t newest_ok_id(const std::string& vehicle_id,
                                    bool include_harvested = false) = 0;
  // Oldest first, at most filter.limit rows with id > filter.after_id.
  virtual std::vector<TurnRow> list(const TurnFilter& filter) = 0;
  // The turn's summary columns alone (its documents are not read).
  virtual std::optional<TurnRow> get_row(std::int64_t turn_id) = 0;
  // Throws StoreError naming the turn when its stored JSON is corrupt.
  virtual std::optional<StoredTurn> get(std::int64_t turn_id) = 0;
  // Normalised turns of status ok for the CKT, oldest first, from the given missions (empty: all
  // missions), optionally of one vehicle. Each equals get(id)->normalized. Reads the packed
  // samples; turns stored before schema 2 have none and are parsed from their JSON instead.
  // Collection turns only, unless include_harvested. With water_where_known, a turn that has a
  // water-frame form (CurrentRepository::save) is read in it. left_out: every turn but those (a
  // turn shown against predictions that never saw it or its mission).
  virtual std::vector<kinematics::TurnSequence> load_normalized(
      const std::vector<std::int64_t>& mission_ids,
      const std::optional<std::string>& vehicle_id = std::nullopt, bool include_harvested = false,
      TurnFrameChoice frame = TurnFrameChoice::ground, const TurnsLeftOut& left_out = {}) = 0;
  // Start times of every turn stored for the mission (any status or source), ascending.
  virtual std::vector<double> start_times(std::int64_t mission_id) = 0;
};

}  // namespace avk::store
