#pragma once
// Measured cells of turns with a speed change: for each
// collected pair (u0 -> u1), a CKT over the heading changes flown with it, built by Ckt::build
// from those turns alone (the same mean turn, fit, corridor and timing as a constant-speed cell).
// It answers only at a collected pair: anything else is the re-timed prediction's
// (retimed_turn.hpp) or the model's.

#include <optional>
#include <vector>

#include "kinematics/ckt.hpp"

namespace avk::kinematics {

struct SpeedChangeCells {
  double from_mps = 0.0;  // u0: the speed the ConditionSet established
  double to_mps = 0.0;    // u1: commanded with the new heading
  Ckt table;              // one speed row (u0) over the pair's heading changes
};

class SpeedChangeTable {
 public:
  // From the ok turns that carry TurnMeta::speed_after_mps (others are left out). Pairs closer
  // than the options' speed_match_mps in both speeds are one pair (within_match).
  static SpeedChangeTable build(const std::vector<TurnSequence>& turns,
                                const CktOptions& options = {});

  const std::vector<SpeedChangeCells>& pairs() const { return pairs_; }
  bool empty() const { return pairs_.empty(); }

  // The cells of a collected pair (both speeds within the options' speed_match_mps), or none.
  const SpeedChangeCells* find(double from_mps, double to_mps) const;

  // The pair's answer at any heading change (interpolated across heading changes as Ckt::query,
  // extrapolated beyond them); speed_mps of the answer is u0. None when the pair was not
  // collected. Throws as Ckt::query for a heading change outside [-180, 180].
  std::optional<TurnPrediction> query(double from_mps, double to_mps, double dheading_deg) const;

 private:
  std::vector<SpeedChangeCells> pairs_;
  double speed_match_mps_ = 0.05;
};

}  // namespace avk::kinematics
