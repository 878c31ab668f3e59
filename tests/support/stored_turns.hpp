#pragma once
// A vehicle's turns in a database, without running a mission: one mission row and analytic arc
// turns over a small grid, with a radius that grows with speed times `scale`, so two vehicles
// stored with different scales turn measurably differently.

#include <cstdint>
#include <string>

#include "store/store.hpp"
#include "support/synthetic_turns.hpp"

namespace avk::testing {

inline std::int64_t store_arc_turns(store::Store& db, const std::string& vehicle_id,
                                    double scale = 1.0, int per_cell = 2) {
  db.vehicles().upsert({vehicle_id, "usim", 2.0, std::nullopt});
  const std::int64_t mission = db.missions().create(vehicle_id, "arcs", "{}");
  unsigned seed = 1;
  for (double u : {0.5, 1.0, 1.5}) {
    for (double d : {40.0, 100.0, 160.0}) {
      for (int r = 0; r < per_cell; ++r) {
        ArcTurnSpec s;
        s.speed_mps = u;
        s.dheading_deg = r % 2 ? -d : d;
        s.lead_in_m = (0.5 + u) * scale;
        s.radius_m = (1.0 + 2.0 * u) * scale;
        s.dt_s = 0.25;
        s.seed = seed;
        s.start = {-40.0 + 7.0 * (seed % 11), 25.0 - 5.0 * (seed % 9), 31.0 * seed};
        s.vehicle_id = vehicle_id;
        s.mission_id = std::to_string(mission);
        ++seed;
        db.turns().add(mission, make_arc_turn(s), kinematics::TurnStatus::ok, "");
      }
    }
  }
  return mission;
}

// One more ok turn of the vehicle in a stored mission: lead-in 1.5 m, radius 3 m, as
// store_arc_turns' cells at 1 m/s and scale 1.
inline void store_one_arc_turn(store::Store& db, std::int64_t mission,
                               const std::string& vehicle_id, double speed_mps,
                               double dheading_deg) {
  ArcTurnSpec s;
  s.speed_mps = speed_mps;
  s.dheading_deg = dheading_deg;
  s.lead_in_m = 1.5;
  s.radius_m = 3.0;
  s.vehicle_id = vehicle_id;
  db.turns().add(mission, make_arc_turn(s), kinematics::TurnStatus::ok, "");
}

}  // namespace avk::testing
