#pragma once
// The encounter situation of two power-driven vessels in sight of one another (COLREGS rules
// 13-15), from the own vehicle's pose and speed and a contact's course and speed: what the rules
// ask of the own vehicle.
//
// - Rule 13, overtaking: a vessel coming up from more than 22.5° abaft the other's beam (the
//   other's relative bearing of her is beyond 112.5°) and faster. The overtaking vessel keeps
//   out of the way, to either side.
// - Rule 14, head-on: on reciprocal or nearly reciprocal courses, each nearly ahead of the
//   other: each alters course to starboard. "Nearly" is taken as within kHeadOnToleranceDeg of
//   dead ahead and of the reciprocal course (the rule gives no number; masthead lights in line
//   or nearly in line by night are a few degrees).
// - Rule 15, crossing: the vessel which has the other on her own starboard side keeps out of the
//   way and, if the circumstances admit, avoids crossing ahead: in practice a starboard turn.
//   The other (rule 17) stands on.
//
// Bearings: relative to the bow, degrees in (−180, 180], + to starboard.

#include "kinematics/geometry.hpp"
#include "kinematics/maneuver.hpp"

namespace avk::kinematics {

inline constexpr double kHeadOnToleranceDeg = 10.0;
inline constexpr double kAbaftBeamDeg = 112.5;

enum class Situation {
  head_on,            // rule 14: alter to starboard
  crossing_give_way,  // rule 15: keep out of the way (starboard)
  crossing_stand_on,  // rule 15/17: the contact gives way
  overtaking,         // rule 13: the own vehicle overtakes, keeps out of the way
  overtaken,          // rule 13/17: the contact overtakes
  none,               // not closing (or at rest): no situation between them
};
const char* to_string(Situation s);

// The rule that names the situation: "13", "14", "15" or "" for none.
const char* rule_of(Situation s);

// True when the rules ask the own vehicle to turn to starboard (head-on, crossing give-way).
bool asks_starboard(Situation s);

Situation classify_encounter(const Pose& own, double own_speed_mps, const Contact& contact);

}  // namespace avk::kinematics
