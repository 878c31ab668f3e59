#include "kinematics/colregs.hpp"

#include <cmath>

#include "kinematics/angles.hpp"

namespace avk::kinematics {

const char* to_string(Situation s) {
  switch (s) {
    case Situation::head_on:
      return "head_on";
    case Situation::crossing_give_way:
      return "crossing_give_way";
    case Situation::crossing_stand_on:
      return "crossing_stand_on";
    case Situation::overtaking:
      return "overtaking";
    case Situation::overtaken:
      return "overtaken";
    case Situation::none:
      return "none";
  }
  return "none";
}

const char* rule_of(Situation s) {
  switch (s) {
    case Situation::head_on:
      return "14";
    case Situation::crossing_give_way:
    case Situation::crossing_stand_on:
      return "15";
    case Situation::overtaking:
    case Situation::overtaken:
      return "13";
    case Situation::none:
      return "";
  }
  return "";
}

bool asks_starboard(Situation s) {
  return s == Situation::head_on || s == Situation::crossing_give_way;
}

Situation classify_encounter(const Pose& own, double own_speed_mps, const Contact& c) {
  const double dx = c.x_m - own.x_m, dy = c.y_m - own.y_m;
  if (std::hypot(dx, dy) < 1e-9) return Situation::none;
  // Closing: the range decreases.
  const Point vo = rotate_by_heading({0.0, own_speed_mps}, own.heading_deg);
  const Point vc = rotate_by_heading({0.0, c.speed_mps}, c.course_deg);
  const double closing = dx * (vc.x_m - vo.x_m) + dy * (vc.y_m - vo.y_m);
  if (closing >= 0.0) return Situation::none;
  const double bearing_to_contact = heading_of_deg(dx, dy);
  const double contact_rel = angle180_deg(bearing_to_contact - own.heading_deg);
  const double own_rel_from_contact = angle180_deg(bearing_to_contact + 180.0 - c.course_deg);
  // Overtaking first: it holds until the vessels are past and clear (rule 13 (d)).
  if (std::abs(own_rel_from_contact) > kAbaftBeamDeg && own_speed_mps > c.speed_mps)
    return Situation::overtaking;
  if (std::abs(contact_rel) > kAbaftBeamDeg && c.speed_mps > own_speed_mps)
    return Situation::overtaken;
  const double reciprocal = angle180_deg(c.course_deg - own.heading_deg - 180.0);
  if (std::abs(contact_rel) <= kHeadOnToleranceDeg && std::abs(reciprocal) <= kHeadOnToleranceDeg)
    return Situation::head_on;
  return contact_rel > 0.0 ? Situation::crossing_give_way : Situation::crossing_stand_on;
}

}  // namespace avk::kinematics
