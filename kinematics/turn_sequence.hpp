#pragma once
// TurnSequence (thesis §4.2): the record of one turn, its validation and its normalisation.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "kinematics/geometry.hpp"
#include "kinematics/water_current.hpp"

namespace avk::kinematics {

struct TurnSample {
  double t_s = 0.0;
  double x_m = 0.0;          // east
  double y_m = 0.0;          // north
  double heading_deg = 0.0;  // clockwise from north; in a normalised turn: change from psi0
  double speed_mps = 0.0;
  friend bool operator==(const TurnSample&, const TurnSample&) = default;
};

enum class TurnStatus { ok, aborted, rejected };
const char* to_string(TurnStatus s);
std::optional<TurnStatus> turn_status_from_string(const std::string& s);

// Where a turn came from: a collection mission's turn (recorded by the mission, or a log's turn
// record), or harvested from an ordinary navigation log (mission/turn_harvester.hpp).
enum class TurnSource { collection, harvested };
const char* to_string(TurnSource s);
std::optional<TurnSource> turn_source_from_string(const std::string& s);

struct TurnMeta {
  std::string vehicle_id;
  std::string mission_id;
  double commanded_speed_mps = 0.0;
  double goal_dheading_deg = 0.0;      // signed: + starboard (right), - port (left)
  double observed_dheading_deg = 0.0;  // signed, from the unwrapped sample headings
  double initial_heading_deg = 0.0;    // psi0, deg clockwise from north
  double initial_speed_mps = 0.0;
  double start_time_s = 0.0;
  double end_time_s = 0.0;
  TurnStatus status = TurnStatus::ok;
  std::string status_reason;  // why aborted/rejected; empty for ok
  bool normalized = false;
  // Set on a turn in the water frame (water_frame.hpp): the current whose drift was taken out of
  // its positions. Empty: the positions are over ground, as navigated.
  std::optional<WaterCurrent> removed_current;
  TurnSource source = TurnSource::collection;
  // Harvested turns only: 0..1, how steady the vehicle was before the step times how cleanly
  // the turn completed (mission/turn_harvester.hpp, turn_quality).
  std::optional<double> quality;
  // Smoothed yaw rate (ConditionSet moving average) when the turn's heading was commanded, deg/s.
  // Raw turn: + clockwise. Normalised turn: reflected with the turn, + into the turn (towards
  // its side), - against it. Empty for turns recorded before it was measured (read as 0).
  std::optional<double> initial_yaw_rate_dps;
  // u1, the speed commanded with the new heading when it differs from commanded_speed_mps (u0,
  // the speed the ConditionSet established before the turn). Empty for a constant-speed turn.
  std::optional<double> speed_after_mps;
  friend bool operator==(const TurnMeta&, const TurnMeta&) = default;
};

enum class TurnErrorCode {
  too_few_samples,
  non_finite,
  time_not_increasing,
  instantaneous_turn,
  bad_metadata,
};
const char* to_string(TurnErrorCode c);

// A turn that cannot be used, with the reason and (where it applies) the sample index.
class TurnError : public std::runtime_error {
 public:
  TurnError(TurnErrorCode code, std::string message, std::optional<std::size_t> sample = {})
      : std::runtime_error(std::move(message)), code_(code), sample_(sample) {}
  TurnErrorCode code() const { return code_; }
  std::optional<std::size_t> sample_index() const { return sample_; }

 private:
  TurnErrorCode code_;
  std::optional<std::size_t> sample_;
};

struct TurnValidationOptions {
  std::size_t min_samples = 3;
  // Initial and final headings closer than this make an "instantaneous turn" (thesis §4.5).
  double instantaneous_tolerance_deg = 0.5;
};

class TurnSequence {
 public:
  TurnSequence() = default;
  TurnSequence(TurnMeta meta, std::vector<TurnSample> samples)
      : meta_(std::move(meta)), samples_(std::move(samples)) {}

  // Builds a turn from separately recorded coordinate streams (MOOS posts NAV_X and NAV_Y
  // asynchronously, thesis §4.5). Streams of unequal length are cut to the shortest by dropping
  // trailing values; each cut is recorded as a warning. initial/observed heading and times are
  // filled from the samples.
  static TurnSequence from_streams(TurnMeta meta, const std::vector<double>& t_s,
                                   const std::vector<double>& x_m, const std::vector<double>& y_m,
                                   const std::vector<double>& heading_deg,
                                   const std::vector<double>& speed_mps);

  const TurnMeta& meta() const { return meta_; }
  TurnMeta& meta() { return meta_; }
  const std::vector<TurnSample>& samples() const { return samples_; }
  const std::vector<std::string>& warnings() const { return warnings_; }
  void add_warning(std::string w) { warnings_.push_back(std::move(w)); }

  TurnSide side() const { return side_of(meta_.goal_dheading_deg); }
  Polyline points() const;

  // Signed heading change from the first to the last sample, unwrapped sample by sample so a
  // turn from 350 to 40 degrees is +50 and a 170-degree turn is never read as -190.
  double heading_change_deg() const;

  // Throws TurnError for a turn that cannot be used.
  void validate(const TurnValidationOptions& options = {}) const;

  // Start at the origin, psi0 along +y, left turns reflected across the y axis so every
  // normalised turn is a right turn (thesis §3.2, §4.2). Headings become the change from psi0.
  TurnSequence normalized() const;

  // Sets initial heading/speed, times and observed change from the samples.
  void fill_derived_metadata();

  friend bool operator==(const TurnSequence& a, const TurnSequence& b) {
    return a.meta_ == b.meta_ && a.samples_ == b.samples_;
  }

 private:
  TurnMeta meta_;
  std::vector<TurnSample> samples_;
  std::vector<std::string> warnings_;
};

}  // namespace avk::kinematics
