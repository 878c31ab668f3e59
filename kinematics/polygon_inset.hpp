#pragma once
// A polygon moved inward by a distance: the operating region's buffer line as the container
// (mission/container.hpp) treats it, for drawing. Each edge is offset along its inward normal and
// consecutive offset edges are intersected: exact for a convex polygon (the regions a collection
// mission flies in), an approximation for a concave one.

#include "kinematics/geometry.hpp"

namespace avk::kinematics {

// Either winding. Empty when the inset turns the polygon inside out (the distance exceeds its
// inradius) or the polygon has fewer than 3 vertices.
Polyline inset_polygon(const Polyline& polygon, double distance_m);

}  // namespace avk::kinematics
