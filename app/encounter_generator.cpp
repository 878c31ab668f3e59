#include "app/encounters.hpp"

#include <cmath>
#include <cstdio>
#include <optional>
#include <random>
#include <string>

#include "kinematics/angles.hpp"

namespace avk::app {

namespace kin = avk::kinematics;

// ---- the generator --------------------------------------------------------------------------

namespace {

enum class EncounterKind {
  head_on,
  crossing_from_starboard,
  crossing_from_port,
  overtaking,
  overtaken,
  several
};
constexpr EncounterKind kKinds[] = {EncounterKind::head_on,
                                    EncounterKind::crossing_from_starboard,
                                    EncounterKind::crossing_from_port,
                                    EncounterKind::overtaking,
                                    EncounterKind::overtaken,
                                    EncounterKind::several};

const char* kind_name(EncounterKind k) {
  switch (k) {
    case EncounterKind::head_on:
      return "head-on";
    case EncounterKind::crossing_from_starboard:
      return "crossing-from-starboard";
    case EncounterKind::crossing_from_port:
      return "crossing-from-port";
    case EncounterKind::overtaking:
      return "overtaking";
    case EncounterKind::overtaken:
      return "overtaken";
    case EncounterKind::several:
      return "several-contacts";
  }
  return "?";
}

constexpr double kGenStandoffM = 10.0;
constexpr double kGenHorizonS = 120.0;
constexpr double kMinRangeM = 15.0, kMaxRangeM = 80.0;
constexpr double kMinSpeedMps = 0.5, kMaxGenSpeedMps = 1.5;
constexpr double kMinAimS = 15.0, kMaxAimS = 60.0;

// v rounded to 1/per_unit (per_unit whole), so that it prints as short as it reads: 36.3.
double rounded(double v, double per_unit) {
  return std::round(v * per_unit) / per_unit;
}

double course_held_cpa_m(const EncounterScenario& s, const kin::Contact& c) {
  const double h = kin::deg_to_rad(s.own_heading_deg);
  const kin::TimedPath straight{{0.0, 0.0, 0.0},
                                {kGenHorizonS, std::sin(h) * s.own_speed_mps * kGenHorizonS,
                                 std::cos(h) * s.own_speed_mps * kGenHorizonS}};
  return kin::closest_approach(straight, c).distance_m;
}

// A contact of this kind aimed at a point of own track 15-60 s ahead, offset sideways by less
// than the standoff; none when its start falls outside 15-80 m or holding course would clear.
std::optional<kin::Contact> aimed_contact(std::mt19937_64& rng, EncounterKind kind,
                                          const EncounterScenario& s) {
  const auto uniform = [&](double a, double b) {
    return std::uniform_real_distribution<double>(a, b)(rng);
  };
  const double aim_s = uniform(kMinAimS, kMaxAimS);
  const double offset_m = uniform(-0.6, 0.6) * kGenStandoffM;
  double course = s.own_heading_deg;
  double speed = uniform(kMinSpeedMps, kMaxGenSpeedMps);
  switch (kind) {
    case EncounterKind::head_on:
      course += 180.0 + uniform(-10.0, 10.0);
      break;
    case EncounterKind::crossing_from_starboard:  // comes from the right, heading left
      course += -90.0 + uniform(-30.0, 30.0);
      break;
    case EncounterKind::crossing_from_port:
      course += 90.0 + uniform(-30.0, 30.0);
      break;
    case EncounterKind::overtaking:  // ahead, slower, on the same course
      course += uniform(-10.0, 10.0);
      speed = uniform(kMinSpeedMps, s.own_speed_mps - 0.25);
      break;
    case EncounterKind::overtaken:  // behind, faster
      course += uniform(-10.0, 10.0);
      speed = uniform(s.own_speed_mps + 0.25, kMaxGenSpeedMps);
      break;
    case EncounterKind::several:
      break;
  }
  const double h = kin::deg_to_rad(s.own_heading_deg);
  const double along = s.own_speed_mps * aim_s;
  const double aim_x = std::sin(h) * along + std::cos(h) * offset_m;  // offset to starboard
  const double aim_y = std::cos(h) * along - std::sin(h) * offset_m;
  const double c = kin::deg_to_rad(course);
  kin::Contact out;
  out.course_deg = rounded(kin::wrap360_deg(course), 1.0);
  out.speed_mps = rounded(speed, 20.0);
  out.x_m = rounded(aim_x - std::sin(c) * speed * aim_s, 10.0);
  out.y_m = rounded(aim_y - std::cos(c) * speed * aim_s, 10.0);
  const double range = std::hypot(out.x_m, out.y_m);
  if (range < kMinRangeM || range > kMaxRangeM) return std::nullopt;
  if (out.speed_mps < kMinSpeedMps || out.speed_mps > kMaxGenSpeedMps) return std::nullopt;
  if (!(course_held_cpa_m(s, out) < kGenStandoffM)) return std::nullopt;
  return out;
}

std::string range_text(const kin::Contact& c) {
  return std::to_string(static_cast<int>(std::lround(std::hypot(c.x_m, c.y_m)))) + "m";
}

}  // namespace

Result<EncounterFile> generate_encounters(std::uint64_t seed, int count) {
  if (count < 1 || count > 100000) return invalid_argument("count", "must be 1 to 100000");
  std::mt19937_64 rng(seed);
  EncounterFile f;
  f.standoff_m = kGenStandoffM;
  f.horizon_s = kGenHorizonS;
  constexpr int kMaxTries = 100000;
  for (int i = 0; i < count; ++i) {
    const EncounterKind kind = kKinds[static_cast<std::size_t>(i) % std::size(kKinds)];
    EncounterScenario s;
    s.standoff_m = kGenStandoffM;
    s.own_heading_deg = std::uniform_int_distribution<int>(0, 359)(rng);
    // Overtaking needs a slower contact and being overtaken a faster one, both within 0.5-1.5.
    const double lo = kind == EncounterKind::overtaking ? 0.8 : kMinSpeedMps;
    const double hi = kind == EncounterKind::overtaken ? 1.2 : kMaxGenSpeedMps;
    s.own_speed_mps = rounded(std::uniform_real_distribution<double>(lo, hi)(rng), 20.0);
    const int contacts =
        kind == EncounterKind::several ? std::uniform_int_distribution<int>(2, 3)(rng) : 1;
    for (int k = 0; k < contacts; ++k) {
      const EncounterKind each = kind == EncounterKind::several
                                     ? kKinds[std::uniform_int_distribution<std::size_t>(0, 2)(rng)]
                                     : kind;
      std::optional<kin::Contact> c;
      for (int t = 0; t < kMaxTries && !c; ++t)
        c = aimed_contact(rng, each, s);
      if (!c)
        return internal_error("the generator found no contact for " + std::string(kind_name(kind)));
      s.contacts.push_back(*c);
    }
    const auto nearest = std::min_element(
        s.contacts.begin(), s.contacts.end(), [](const kin::Contact& a, const kin::Contact& b) {
          return std::hypot(a.x_m, a.y_m) < std::hypot(b.x_m, b.y_m);
        });
    char index[8];
    std::snprintf(index, sizeof index, "%02d", i + 1);
    // Appended piece by piece: GCC 12's -Wrestrict misfires on "-" + std::string at -O3.
    s.name = kind_name(kind);
    if (kind == EncounterKind::several) {
      s.name += '-';
      s.name += std::to_string(contacts);
    }
    s.name += "-";
    s.name += range_text(*nearest);
    s.name += "-";
    s.name += index;
    f.scenarios.push_back(std::move(s));
  }
  return f;
}

}  // namespace avk::app
