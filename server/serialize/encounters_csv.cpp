#include "server/serialize/encounters.hpp"

#include "server/serialize/csv.hpp"
#include "server/serialize/values.hpp"

namespace avk::server {

std::string encounter_bench_csv(const app::EncounterBench& b) {
  std::string csv =
      "scenario,standoff_m,safe_existed,course_held_cpa_m,method,chosen_dheading_deg,"
      "predicted_cpa_m,predicted_edge_cpa_m,actual_cpa_m,violation,"
      "no_maneuver_while_one_existed,unsafe_while_safe_existed\n";
  const auto flag = [](bool v) { return v ? '1' : '0'; };
  for (const auto& s : b.scenarios) {
    for (const auto& r : s.methods) {
      // The scenario's name as the file gives it, unquoted, as this table has always had it.
      csv += s.name + ',' + num(s.standoff_m) + ',' + flag(s.safe_existed) + ',' +
             num(s.course_held_cpa_m) + ',' + app::to_string(r.method) + ',' +
             optional_csv(r.chosen_dheading_deg) + ',' + optional_csv(r.predicted_cpa_m) + ',' +
             optional_csv(r.predicted_edge_cpa_m) + ',' + num(r.actual_cpa_m) + ',' +
             flag(r.violation) + ',' + flag(r.no_maneuver_while_one_existed) + ',' +
             flag(r.unsafe_while_safe_existed) + '\n';
    }
  }
  return csv;
}

}  // namespace avk::server
