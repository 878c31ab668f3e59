#pragma once
// Plane geometry on the local grid (x east, y north, metres) shared by turns, fits and the CKT.

#include <cstddef>
#include <vector>

namespace avk::kinematics {

struct Point {
  double x_m = 0.0;  // east
  double y_m = 0.0;  // north
  friend bool operator==(const Point&, const Point&) = default;
};

using Polyline = std::vector<Point>;

// A vehicle pose: position and heading (deg clockwise from north).
struct Pose {
  double x_m = 0.0;
  double y_m = 0.0;
  double heading_deg = 0.0;
};

enum class TurnSide { right, left };

inline TurnSide side_of(double signed_dheading_deg) {
  return signed_dheading_deg < 0.0 ? TurnSide::left : TurnSide::right;
}

double distance_m(Point a, Point b);
double distance_to_segment_m(Point p, Point a, Point b);
// Distance from p to the nearest point of the polyline (a single point counts as a polyline).
double distance_to_polyline_m(Point p, const Polyline& line);

// Cumulative arc length at each vertex (first entry 0).
std::vector<double> cumulative_arc_length_m(const Polyline& line);
double arc_length_m(const Polyline& line);

// Points every step_m along the polyline by arc length, always including both ends.
Polyline resample_by_arc_length(const Polyline& line, double step_m);

// Rotates a vector so that its heading grows by dheading_deg (clockwise positive).
Point rotate_by_heading(Point v, double dheading_deg);

// A left turn from the normalised right turn: the mirror image across the y axis.
Polyline reflect_x(Polyline line);

// Takes a trajectory in the normalised frame (start at the origin, initial heading north, a right
// turn) to the world: reflected for a left turn, rotated to the pose heading, translated to it.
Polyline place_normalized(const Polyline& normalized, const Pose& pose, TurnSide side);

// The inverse of place_normalized for one point.
Point normalize_point(Point world, const Pose& start, TurnSide side);

}  // namespace avk::kinematics
