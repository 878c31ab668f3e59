#pragma once
// The CKT over (speed, heading change, initial yaw rate) (thesis §6.2): one 2-D table
// (Ckt) per initial-yaw-rate grid value, all on the same speed x heading-change grid. The initial
// yaw rate is the normalised one: + into the turn (towards its side), - against it. Between two
// slices a query blends the slices' answers as Ckt::query blends heading changes: heading
// profiles over fraction of arc length (blended_trajectory), advance and transfer linearly. The
// 2-D table is the slice at 0 deg/s; a table file without slices loads as that slice alone.
//
// Every cell has a source: `measured` (built from turns), `model` (a turn simulated by the
// black-box yaw model started at the slice's yaw rate, filled where no turn was measured) or
// `interpolated` (no turn and no fill: a query there blends the neighbouring cells).

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "kinematics/ckt.hpp"

namespace avk::kinematics {

enum class CellSource { measured, interpolated, model };
const char* to_string(CellSource s);
std::optional<CellSource> cell_source_from_string(const std::string& s);

struct YawRateSlice {
  double initial_yaw_rate_dps = 0.0;
  Ckt table;
  std::vector<CellSource> sources;  // one per table cell, in the order of table.cells()
};

struct YawRateCktOptions {
  // A turn belongs to the slice whose yaw rate is within this of its normalised initial yaw rate
  // (a turn without one counts as 0 deg/s).
  double yaw_rate_match_dps = 2.5;
};

struct YawRateBuildReport {
  std::size_t turns_used = 0;
  std::size_t turns_unassigned = 0;  // no slice within yaw_rate_match_dps
  std::vector<CktBuildReport> slices;
};

// Turns that would fill a cell: the model's normalised right turn for (speed, heading change,
// initial yaw rate), as a TurnSequence. Empty when the model cannot produce one.
using CellFiller = std::function<std::optional<TurnSequence>(double speed_mps, double dheading_deg,
                                                             double initial_yaw_rate_dps)>;

struct YawRatePrediction {
  TurnPrediction prediction;          // as Ckt::query answers, with the blend across slices
  double initial_yaw_rate_dps = 0.0;  // as asked
  // The asked yaw rate lies outside the slices' range: answered by the nearest slice.
  bool yaw_rate_clamped = false;
  // measured or model: one cell of one slice answered; interpolated otherwise.
  CellSource source = CellSource::interpolated;
};

struct SliceCoverage {
  double initial_yaw_rate_dps = 0.0;
  std::size_t measured = 0;
  std::size_t model = 0;
  std::size_t empty = 0;  // interpolated
};

class YawRateCkt {
 public:
  YawRateCkt() = default;

  // One slice per value of yaw_rates_dps (default: 0 and the clusters of the turns' normalised
  // initial yaw rates, at least 2 x yaw_rate_match_dps apart), each built by Ckt::build from the
  // turns assigned to it, all on `grid` (default: the grid of all ok turns, as Ckt::build makes).
  static YawRateCkt build(const std::vector<TurnSequence>& turns,
                          std::optional<std::vector<double>> yaw_rates_dps = std::nullopt,
                          const CktOptions& options = {},
                          std::optional<CktGrid> grid = std::nullopt,
                          const YawRateCktOptions& yaw_options = {},
                          YawRateBuildReport* report = nullptr);

  // A 2-D table as the 0 deg/s slice; its cells with turns are measured.
  static YawRateCkt from_table(Ckt table);
  // Slices as stored; sorted by yaw rate. Throws std::invalid_argument for slices on different
  // grids, a sources list of the wrong length, or two slices at the same yaw rate.
  static YawRateCkt from_slices(std::vector<YawRateSlice> slices);

  // Fills every cell without data by the filler's turn and marks it `model`.
  void fill(const CellFiller& filler);

  const std::vector<YawRateSlice>& slices() const { return slices_; }
  // The 0 deg/s slice (the 2-D table); nullptr when there is none.
  const YawRateSlice* steady() const;
  std::vector<SliceCoverage> coverage() const;

  // Throws as Ckt::query does (speed outside every slice's range, non-finite input, no slices).
  YawRatePrediction query(double speed_mps, double dheading_deg, double initial_yaw_rate_dps) const;

 private:
  std::vector<YawRateSlice> slices_;  // ascending yaw rate
};

// The slice yaw rates a set of turns suggests (see YawRateCkt::build).
std::vector<double> yaw_rate_grid(const std::vector<TurnSequence>& turns, double match_dps);
// A turn's normalised initial yaw rate (0 when it has none).
double normalized_initial_yaw_rate_dps(const TurnSequence& turn);

}  // namespace avk::kinematics
