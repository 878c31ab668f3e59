#include "mission/direction_chooser.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "kinematics/angles.hpp"

namespace avk::mission {

namespace {

using kinematics::Point;
using kinematics::Polyline;
using kinematics::TurnSide;

double clearance_m(const Container& c, const Polyline& world) {
  double least = std::numeric_limits<double>::infinity();
  for (const Point& p : world) {
    const double d = distance_to_boundary_m(p, c.region().polygon);
    least = std::min(least, point_in_polygon(p, c.region().polygon) ? d : -d);
  }
  return least;
}

// The normalised right-turn path: the table's trajectory, or a ray along the goal heading; both
// continued straight along the goal heading for the run-out.
Polyline predicted_right_turn(double speed_mps, double dheading_deg, const kinematics::Ckt* table,
                              double run_out_m, bool& from_table) {
  Polyline path{{0.0, 0.0}};
  from_table = false;
  if (table) {
    const auto range = table->speed_range_mps();
    if (range && speed_mps >= range->first && speed_mps <= range->second) {
      path = table->query(speed_mps, std::abs(dheading_deg)).trajectory;
      from_table = true;
    }
  }
  const Point goal_dir = kinematics::rotate_by_heading({0.0, 1.0}, std::abs(dheading_deg));
  const Point end = path.back();
  // Sample the run-out so that a boundary corner between its ends is not missed.
  const int steps = std::max(1, static_cast<int>(std::ceil(run_out_m / 2.0)));
  for (int k = 1; k <= steps; ++k) {
    const double s = run_out_m * k / steps;
    path.push_back({end.x_m + s * goal_dir.x_m, end.y_m + s * goal_dir.y_m});
  }
  return path;
}

}  // namespace

SideChoice choose_side(const Container& container, const kinematics::Pose& start, double speed_mps,
                       double dheading_deg, const kinematics::Ckt* table, TurnSide prefer,
                       const DirectionOptions& options) {
  SideChoice choice;
  const double run_out = std::max(options.min_run_out_m, speed_mps * options.run_out_s);
  const Polyline right =
      predicted_right_turn(speed_mps, dheading_deg, table, run_out, choice.from_table);
  choice.right_clearance_m =
      clearance_m(container, kinematics::place_normalized(right, start, TurnSide::right));
  choice.left_clearance_m =
      clearance_m(container, kinematics::place_normalized(right, start, TurnSide::left));
  const double buffer = container.region().buffer_m;
  const bool right_ok = choice.right_clearance_m >= buffer;
  const bool left_ok = choice.left_clearance_m >= buffer;
  if (right_ok && left_ok) {
    choice.side = prefer;
  } else if (right_ok != left_ok) {
    choice.side = right_ok ? TurnSide::right : TurnSide::left;
  } else {
    choice.side =
        choice.right_clearance_m >= choice.left_clearance_m ? TurnSide::right : TurnSide::left;
  }
  return choice;
}

}  // namespace avk::mission
