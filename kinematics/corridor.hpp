#pragma once
// How far a turn may stray from its prediction: a lateral band about a predicted path that holds
// a stated share of the vehicle's turns.
//
// A cell's corridor is the spread of its turns about their mean: at each station (equal arc
// length, see path_metric.hpp) the sample standard deviation of the turns' lateral offsets from
// the mean path. The band for a share P is ± t·sd·√(1 + 1/n), with t the two-sided P quantile of
// Student's t with n − 1 degrees of freedom: the prediction interval of one new turn from n
// observed ones. With 5 turns the 90 % band is 2.3 sd wide each side instead of the 1.64 sd a
// known spread would give; with 2 turns 7.0 sd: a cell with few turns says honestly that it knows
// little. The offsets are taken at equal stations, so the band is lateral only: it says how far
// to either side a turn goes, not how far ahead or behind along its path it is.
//
// The spread is kept at fixed fractions of the path's length so that cells of different lengths
// blend as their trajectories do (CKT interpolation over fraction of arc length).

#include <cstddef>
#include <optional>
#include <vector>

#include "kinematics/geometry.hpp"
#include "kinematics/path_metric.hpp"

namespace avk::kinematics {

// Stations of a corridor: fractions 0, 1/(k−1), ..., 1 of its length.
inline constexpr std::size_t kCorridorStations = 101;
inline constexpr double kDefaultCorridorShare = 0.9;

struct Corridor {
  std::size_t n_turns = 0;           // the turns the spread is from (>= 2)
  double length_m = 0.0;             // the span of the stations
  std::vector<double> lateral_sd_m;  // kCorridorStations values at equal fractions of length
  friend bool operator==(const Corridor&, const Corridor&) = default;
};

// The spread of the turns about their mean at equal stations, over [0, the longest turn]. Empty
// for fewer than 2 turns.
std::optional<Corridor> corridor_of(const std::vector<StationedPath>& turns,
                                    const StationedPath& mean, double goal_dheading_deg);

// The sd at station s: linear between stations, the last value past the end.
double lateral_sd_at_m(const Corridor& c, double s_m);

// t_{(1+share)/2, n−1} · √(1 + 1/n). Throws std::invalid_argument for n < 2 or a share outside
// (0, 1).
double corridor_factor(std::size_t n_turns, double share);

// The blend of cell corridors with weights (summing to 1), as the CKT blends trajectories: sd at
// equal fractions weighted, length weighted, n the smallest of the sources (the band is only as
// well known as its least known cell). Empty when any source is empty.
std::optional<Corridor> blend_corridors(
    const std::vector<std::pair<const std::optional<Corridor>*, double>>& sources);

// Signed lateral offset of q from the path at station s (+ to the right of the path's direction).
double lateral_offset_m(const StationedPath& path, double s_m, Point q, double goal_dheading_deg);

// The band about a trajectory (any frame): for every vertex of the trajectory its station, the
// half width, and the two boundary points offset along the trajectory's normal; the corridor's
// stations are scaled to the trajectory's length.
struct CorridorBand {
  double share = kDefaultCorridorShare;
  std::size_t n_turns = 0;
  std::vector<double> s_m;
  std::vector<double> half_width_m;
  Polyline left, right;
};
CorridorBand corridor_band(const Polyline& trajectory, const Corridor& c, double share);
// Only the half widths of the band (one per trajectory vertex), for maneuver evaluation, which
// asks for them for every candidate and never draws the edges.
std::vector<double> corridor_half_widths_m(const Polyline& trajectory, const Corridor& c,
                                           double share);

// Points of a held-out turn inside a band built without it.
struct Coverage {
  std::size_t inside = 0;
  std::size_t total = 0;
  double share() const {
    return total ? static_cast<double>(inside) / static_cast<double>(total) : 0.0;
  }
  Coverage& operator+=(const Coverage& o) {
    inside += o.inside;
    total += o.total;
    return *this;
  }
};

// For each station of the held-out turn's own span (every step_m from 0 to its length), whether
// its lateral offset from the mean is within the band of `share`.
Coverage corridor_coverage(const StationedPath& held_out, const StationedPath& mean,
                           const Corridor& c, double goal_dheading_deg, double share,
                           double step_m = kStationStep_m);

}  // namespace avk::kinematics
