#pragma once
// The Cached Kinematics Table (thesis §3.2): turn trajectories over speed x heading change.
//
// Every cell trajectory is a normalised right turn (start at the origin heading north); a left
// turn is its reflection across the y axis. Past its last vertex a trajectory continues along the
// goal heading. Between cells, trajectories are interpolated in their heading profile over
// fraction of arc length (never by averaging y at equal x across different heading changes), so
// an interpolated turn ends on the requested heading.

#include <cmath>
#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "kinematics/corridor.hpp"
#include "kinematics/curve_fit.hpp"
#include "kinematics/geometry.hpp"
#include "kinematics/turn_sequence.hpp"
#include "kinematics/turn_timing.hpp"

namespace avk::kinematics {

struct MeanSd {
  double mean = 0.0;
  double sd = 0.0;  // sample standard deviation (n - 1); 0 for a single value
  friend bool operator==(const MeanSd&, const MeanSd&) = default;
};
MeanSd mean_sd(const std::vector<double>& values);

// How a cell's turns are averaged into its representative mean turn.
enum class MeanKind {
  // Positions averaged at equal arc length (stations from each turn's clock at its commanded
  // speed, path_metric.hpp): a shallow turn's mean follows where its turns went.
  arc_length,
  // The thesis' y averaged at equal x (§5.2), which a shallow turn turns into a long line along
  // the goal heading: available by name.
  x_grid,
};
const char* to_string(MeanKind k);
std::optional<MeanKind> mean_kind_from_string(const std::string& s);

struct CktOptions {
  FitKind fit_kind = FitKind::arc_length_spline;
  MeanKind mean_kind = MeanKind::arc_length;
  double pwl_epsilon_m = 0.05;
  double mean_x_step_m = 0.01;
  // The representative mean turn runs this far (in x) past the set's largest x so that it ends
  // on the goal heading; the thesis' metrics keep using the unextended domain.
  double mean_x_margin_m = 0.5;
  // A turn belongs to a grid cell when its commanded speed and |goal| are this close to it.
  double speed_match_mps = 0.05;
  double dheading_match_deg = 0.5;
  friend bool operator==(const CktOptions&, const CktOptions&) = default;
};

// Whether two values (speeds, heading changes) fall in one cell at a match tolerance: when they
// are closer than it. Values the tolerance itself apart, as a mission may plan them, are two cells
// however their decimals round in binary (1.15 - 1.1 is 0.04999999999999982 as doubles, 1.05 - 1.0
// is 0.05000000000000004): the comparison allows 1e-9 for that rounding.
inline bool within_match(double a, double b, double match) {
  constexpr double kRounding = 1e-9;
  return std::abs(a - b) < match - kRounding;
}

struct CktGrid {
  std::vector<double> speeds_mps;     // ascending
  std::vector<double> dheadings_deg;  // ascending, each in (0, 180]
  friend bool operator==(const CktGrid&, const CktGrid&) = default;
};

// Heading change as a step function of fraction of arc length: on [breaks[j], breaks[j+1]) the
// heading is fraction[j] * goal. Derived from a cell's trajectory; reconstructing it reproduces
// the trajectory exactly (any heading plus a multiple of 360 draws the same segment), and which
// multiple of 360 a segment is given only matters to a blend (heading_profile).
struct HeadingProfile {
  double length_m = 0.0;
  std::vector<double> breaks;    // size m + 1, from 0 to 1
  std::vector<double> fraction;  // size m
};

struct CktCell {
  double speed_mps = 0.0;
  double dheading_deg = 0.0;  // > 0: the table stores right turns
  std::size_t n_turns = 0;
  MeanSd advance_m;
  MeanSd transfer_m;
  std::optional<double> avk_error_m2;  // mean MSE of the turns against their mean; needs 2 turns
  CurveFit fit;
  Polyline trajectory;              // piecewise-linear approximation of the fit of the mean turn
  HeadingProfile profile;           // derived from trajectory
  std::vector<TurnSequence> turns;  // the observed turns, normalised (empty when loaded from file)
  Polyline mean_turn;               // the representative mean turn (empty when loaded from file)
  // The spread of the turns about their mean (2 turns or more), for prediction corridors.
  std::optional<Corridor> corridor;
  // When the turns, on average, passed each point of the trajectory (turn_timing.hpp); empty in a
  // table file of schema 1 or 2.
  std::optional<TurnTiming> timing;
  // The turns, on average, stopped well short of the goal (mean observed change below
  // kShortOfGoalFraction of it): the trajectory past their end is the table's extension along
  // the goal heading, not something the vehicle was seen to do.
  bool short_of_goal = false;

  bool has_data() const { return n_turns > 0; }
};

// What a query answers: a normalised trajectory (reflected for a left turn), and the expected
// advance and transfer at the end of the turn (transfer positive towards the turn side).
struct TurnPrediction {
  double speed_mps = 0.0;
  double dheading_deg = 0.0;  // signed as asked
  Polyline trajectory;
  double advance_m = 0.0;
  double transfer_m = 0.0;
  bool exact_cell = false;    // answered by one cell, not interpolated
  bool extrapolated = false;  // |dheading| outside the heading changes the table holds
  // The spread, blended from the cells that answered as the trajectory is; empty when one of
  // them has none (a single turn, or a table file without corridors).
  std::optional<Corridor> corridor;
  // When the trajectory's points are passed, blended like the corridor and spanning the answered
  // trajectory; empty when one of the cells that answered has none.
  std::optional<TurnTiming> timing;
  bool short_of_goal = false;  // one of the cells that answered is short of its goal
  friend bool operator==(const TurnPrediction&, const TurnPrediction&) = default;
};

inline constexpr double kShortOfGoalFraction = 0.8;

class CktRangeError : public std::out_of_range {
 public:
  using std::out_of_range::out_of_range;
};

// Where the table's turns were recorded: over ground as navigated, or in the water frame (the
// drift of an estimated current removed, water_frame.hpp); mixed when some turns had no estimate.
enum class TableFrame { ground, water, mixed };
const char* to_string(TableFrame f);
std::optional<TableFrame> table_frame_from_string(const std::string& s);

struct CktBuildReport {
  std::size_t turns_used = 0;
  std::size_t turns_water_frame = 0;     // of turns_used
  std::size_t turns_skipped_status = 0;  // aborted or rejected
  std::size_t turns_unassigned = 0;      // no grid cell within the match tolerances
  // Turns with a commanded speed change (TurnMeta::speed_after_mps): never in a constant-speed
  // cell; kinematics/speed_change_table.hpp holds them.
  std::size_t turns_speed_change = 0;
  std::vector<std::string> warnings;
};

class Ckt {
 public:
  Ckt() = default;

  // Builds the table from turns (raw or normalised; only status ok is used, and no turn with a
  // speed change). Without a grid the grid is the set of distinct commanded speeds and |goal|
  // heading changes.
  static Ckt build(const std::vector<TurnSequence>& turns, const CktOptions& options = {},
                   std::optional<CktGrid> grid = std::nullopt, CktBuildReport* report = nullptr);

  // Assembles a table from stored cells (the CKT file); derives each cell's profile.
  static Ckt from_cells(CktGrid grid, std::vector<CktCell> cells, CktOptions options);

  const CktGrid& grid() const { return grid_; }
  const CktOptions& options() const { return options_; }
  const std::vector<CktCell>& cells() const { return cells_; }  // row-major: speed, dheading
  const CktCell& cell(std::size_t speed_index, std::size_t dheading_index) const;
  std::optional<std::size_t> speed_index(double speed_mps) const;  // exact grid match
  std::optional<std::size_t> dheading_index(double dheading_deg) const;

  std::string vehicle_id;
  std::optional<double> vehicle_length_m;
  std::string created_utc;  // ISO 8601
  TableFrame frame = TableFrame::ground;

  // Speeds the table can answer: the range of speed rows that hold at least one turn.
  std::optional<std::pair<double, double>> speed_range_mps() const;

  // Any speed within speed_range_mps and any heading change in [-180, 180]. Throws
  // CktRangeError for a speed outside the range, std::invalid_argument for non-finite input.
  TurnPrediction query(double speed_mps, double dheading_deg) const;

  // Lets go of every cell's observed turns, as a table read from a file has none: query answers
  // exactly as before, and a table kept for queries alone holds a fraction of the memory.
  void drop_observed_turns();

 private:
  CktGrid grid_;
  CktOptions options_;
  std::vector<CktCell> cells_;
};

// The grid Ckt::build uses without one: the distinct commanded speeds (0.01 m/s) and |goal|
// heading changes (0.1 deg) of the ok turns.
CktGrid grid_of(const std::vector<TurnSequence>& turns);

// Derives the step-function heading profile of a normalised trajectory of a turn of
// goal_dheading_deg (D). A right turn by D runs from heading 0 to D, so each segment's heading
// change is taken within 180 deg of the turn's mid-heading, in (D/2 - 180, D/2 + 180]: the whole
// turn, with at least 90 deg to spare for an overshoot past D or a wobble before 0, and never
// beyond D + 180 or -180. Every segment is placed on its own, not unwrapped from the one before:
// the mean of noisy turns can start with a short segment pointing backwards (position noise near
// the origin at low speed), and unwrapping from it carried a 360 deg wrap into the rest of the
// profile, so a turn ended on D - 360 (or D + 360) and its blends with neighbours were rotated by
// up to 180 deg. A trajectory that ends on its goal heading, as every cell's and every answer's
// does, ends on exactly D (fraction 1), and so does every blend of such profiles.
HeadingProfile heading_profile(const Polyline& trajectory, double goal_dheading_deg);

// A heading profile with its weight in a blend.
struct WeightedProfile {
  const HeadingProfile* profile;
  double weight;
};
// The trajectory of a turn of dheading_deg (>= 0) whose heading profile is the weighted blend of
// the sources' (over fraction of arc length) and whose length is length_m, thinned to
// pwl_epsilon_m keeping the final segment on the goal heading. Ckt::query, MaterializedCkt::query
// and the initial-yaw-rate table (ckt3.hpp) all blend with it.
Polyline blended_trajectory(const std::vector<WeightedProfile>& sources, double length_m,
                            double dheading_deg, double pwl_epsilon_m);

// The fine table guidance uses (default 0.1 m/s x 1 deg), computed once so that a lookup is an
// index computation. Between its rows and columns a query blends the neighbouring fine cells the
// way Ckt::query blends table cells, so an answer does not jump to the nearer row (answering
// 0.75 m/s from the 0.8 m/s row moved a turn's error from 0.65 to 0.95 m).
struct FineGridSpec {
  double speed_step_mps = 0.1;
  double dheading_step_deg = 1.0;
};

// The fine table holds at most this many speed rows: a table whose speeds span more than
// (rows - 1) steps gets a coarser speed step instead, so its size (and the time to build it on the
// first prediction) stays bounded whatever speeds the table holds. 256 rows x 181 heading changes
// covers 0..25.5 m/s at the default 0.1 m/s.
inline constexpr std::size_t kMaxFineSpeedRows = 256;
// The finest heading step the fine table accepts.
inline constexpr double kMinFineDheadingStepDeg = 0.1;

class MaterializedCkt {
 public:
  MaterializedCkt(const Ckt& table, FineGridSpec spec = {});

  struct Lookup {
    const TurnPrediction* right_turn;  // the stored right turn; reflect x for a left turn
    TurnSide side;
  };
  // The nearest fine cell. Throws CktRangeError outside the speed range (half a step of slack).
  Lookup lookup(double speed_mps, double dheading_deg) const;
  // A prediction with the speed and heading change as asked, reflected for a left turn: on a fine
  // grid point a copy of that cell; between them the heading profiles of the two neighbouring
  // speed rows and heading-change columns blended over fraction of arc length (Ckt::query's
  // blend), so it ends on the asked heading and agrees with Ckt::query to the table's simplifying
  // tolerance. exact_cell only on a fine grid point that is a table cell; extrapolated when any
  // blended fine cell is. Throws as lookup does.
  TurnPrediction query(double speed_mps, double dheading_deg) const;

  // Rows (columns) are a step apart from the lowest speed (0 deg); the last one is the top of the
  // range (180 deg) even when that is less than a step past the one before.
  std::size_t speed_count() const { return speed_count_; }
  std::size_t dheading_count() const { return dheading_count_; }
  double speed_min_mps() const { return speed_min_mps_; }
  double row_speed_mps(std::size_t row) const;
  double column_dheading_deg(std::size_t column) const;
  // The spec in force: its speed step is coarser than asked when the speed range needs it.
  const FineGridSpec& spec() const { return spec_; }

 private:
  // Where a value falls between two rows (columns): value = (1 - weight) lo + weight hi; lo == hi
  // on a row.
  struct Bracket {
    std::size_t lo = 0;
    std::size_t hi = 0;
    double weight = 0.0;
  };
  Bracket speed_bracket(double speed_mps) const;
  Bracket dheading_bracket(double dheading_deg) const;
  void check_range(double speed_mps, double dheading_deg) const;

  FineGridSpec spec_;
  double speed_min_mps_ = 0.0;
  double speed_max_mps_ = 0.0;
  double pwl_epsilon_m_ = 0.05;  // the table's: an interpolated answer is thinned as Ckt::query's
  std::size_t speed_count_ = 0;
  std::size_t dheading_count_ = 0;
  std::vector<TurnPrediction> entries_;  // row-major: speed, dheading 0..180
  // The heading profile of each entry, for the blend; the 0 deg column, whose profile has no
  // shape, carries the 1-step column's shape with its own length.
  std::vector<HeadingProfile> profiles_;
};

}  // namespace avk::kinematics
