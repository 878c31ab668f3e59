#include "server/serialize/band.hpp"

namespace avk::server {

using nlohmann::json;

namespace {

json coverage_json(const kinematics::Coverage& c) {
  return {{"inside", c.inside}, {"total", c.total}, {"share", c.share()}};
}

json errors_json(const app::ErrorStats& e) {
  return {{"points", e.n},
          {"along_mean_m", e.along_mean_m},
          {"along_rms_m", e.along_rms_m},
          {"along_band_sd_m", e.along_band_sd_m},
          {"cross_mean_m", e.cross_mean_m},
          {"cross_rms_m", e.cross_rms_m},
          {"cross_band_sd_m", e.cross_band_sd_m}};
}
}  // namespace

json band_coverage_json(const app::BandCoverage& c) {
  json speeds = json::array();
  for (const auto& s : c.by_speed)
    speeds.push_back({{"speed_mps", s.speed_mps},
                      {"turns", s.turns},
                      {"during_turn", coverage_json(s.during_turn)},
                      {"after_turn", coverage_json(s.after_turn)},
                      {"all", coverage_json(s.all)}});
  return {{"table_missions", c.table_missions},
          {"test_missions", c.test_missions},
          {"share", c.share},
          {"turns", c.turns},
          {"speed_reference", c.speed_over_ground ? "over_ground" : "through_water"},
          {"scatter", {{"along_mps", c.scatter_along_mps}, {"cross_mps", c.scatter_cross_mps}}},
          {"during_turn", coverage_json(c.during_turn)},
          {"after_turn", coverage_json(c.after_turn)},
          {"all", coverage_json(c.all)},
          {"errors_during_turn", errors_json(c.errors_during_turn)},
          {"errors_after_turn", errors_json(c.errors_after_turn)},
          {"by_speed", speeds}};
}

}  // namespace avk::server
