#pragma once
// A database file as an older station left it: the newest migration steps undone by hand, newest
// first, so a migration test starts from a file written before those steps existed. One place to
// extend when a step is added (the tests that downgrade keep working).

#include <stdexcept>
#include <string>

#include "store/sqlite.hpp"
#include "store/store.hpp"

namespace avk::testing {

// Undoes steps down to schema `version` (>= 8) and sets the file's user_version to it.
inline void downgrade_schema(store::Connection& c, int version) {
  if (version < 8 || version > store::schema_version())
    throw std::invalid_argument("downgrade_schema: no undo for schema " + std::to_string(version));
  for (int v = store::schema_version(); v > version; --v) {
    switch (v) {
      case 13:  // stations and turn record keys
        c.exec("DROP INDEX turns_by_record_key");
        c.exec("ALTER TABLE turns DROP COLUMN record_key");
        c.exec("ALTER TABLE missions DROP COLUMN station_id");
        break;
      case 12:  // the speed reference and drift scatter kept with a current
        for (const char* column : {"reference_legs", "rms_over_ground_mps", "rms_through_water_mps",
                                   "reference_separation_mps", "speed_reference", "drift_legs",
                                   "drift_along_mps", "drift_cross_mps", "drift_mean_leg_s"})
          c.exec(("ALTER TABLE mission_currents DROP COLUMN " + std::string(column)).c_str());
        break;
      case 11:  // when missions ran, in wall-clock time
        c.exec("ALTER TABLE missions DROP COLUMN started_utc");
        c.exec("ALTER TABLE missions DROP COLUMN ended_utc");
        break;
      case 10:  // the currents and the water-frame turns
        c.exec("DROP TABLE mission_currents");
        c.exec("ALTER TABLE turns DROP COLUMN water_samples");
        c.exec("ALTER TABLE turns DROP COLUMN water_meta_json");
        break;
      case 9:  // the speed after a speed-change turn
        c.exec("ALTER TABLE turns DROP COLUMN speed_after_mps");
        break;
      default:
        throw std::logic_error("downgrade_schema: step " + std::to_string(v) +
                               " has no undo here; add it");
    }
  }
  const std::string set = "PRAGMA user_version = " + std::to_string(version);
  c.exec(set.c_str());
}

}  // namespace avk::testing
