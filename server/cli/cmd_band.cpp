// avk band coverage: is the position band honest on whole missions the table never saw
// (app/band_coverage.hpp)?
#include <iomanip>
#include <ostream>

#include "app/band_coverage.hpp"
#include "app/context.hpp"
#include "server/cli/app_error.hpp"
#include "server/cli/args.hpp"
#include "server/cli/commands.hpp"
#include "server/cli/db_selection.hpp"
#include "server/serialize.hpp"

namespace avk::server {

namespace {

void print_errors(const char* what, const app::ErrorStats& e, std::ostream& out) {
  out << "  " << what << ": along mean " << fixed(e.along_mean_m, 2) << " m, rms "
      << fixed(e.along_rms_m, 2) << " m (band sd " << fixed(e.along_band_sd_m, 2)
      << " m); across mean " << fixed(e.cross_mean_m, 2) << " m, rms " << fixed(e.cross_rms_m, 2)
      << " m (band sd " << fixed(e.cross_band_sd_m, 2) << " m)\n";
}

std::string share_text(const kinematics::Coverage& c) {
  return c.total ? fixed(100.0 * c.share(), 1) + " %" : std::string("-");
}

int band_coverage(const std::vector<std::string>& rest, Io& io) {
  const Args a(rest, {"db", "vehicle", "share", "after", "format", "speed-reference"}, {},
               {"mission", "test-mission"});
  app::Context ctx(a.require("db"));
  app::BandCoverageQuery q;
  q.vehicle_id = vehicle_of(a, ctx, {}, "vehicle");
  q.table_missions = mission_ids(a);
  for (const std::string& s : a.all("test-mission"))
    q.test_missions.push_back(parse_id(s, "--test-mission"));
  if (q.test_missions.empty()) throw UsageError("give at least one --test-mission");
  q.share = a.number("share").value_or(q.share);
  q.after_turn_s = a.number("after").value_or(q.after_turn_s);
  if (const auto ref = a.get("speed-reference")) {
    if (*ref != "over_ground" && *ref != "through_water")
      throw UsageError("--speed-reference must be over_ground or through_water");
    q.speed_over_ground = *ref == "over_ground";
  }
  const std::string format = a.get("format").value_or("text");
  if (format != "text" && format != "json") throw UsageError("--format must be text or json");
  const app::BandCoverage c = value_or_fail(app::band_coverage(ctx, q));
  if (format == "json") {
    io.out << band_coverage_json(c).dump(2) << "\n";
    return 0;
  }
  io.out << "band coverage at " << fixed(100.0 * c.share, 0) << " %: " << c.turns
         << " turns of the test missions, predicted by the table of the others\n";
  io.out << "speed (m/s)  turns   during turn   after turn          all\n";
  for (const auto& s : c.by_speed)
    io.out << std::setw(11) << fixed(s.speed_mps, 2) << std::setw(7) << s.turns << std::setw(14)
           << share_text(s.during_turn) << std::setw(13) << share_text(s.after_turn)
           << std::setw(13) << share_text(s.all) << "\n";
  io.out << std::setw(11) << "all" << std::setw(7) << c.turns << std::setw(14)
         << share_text(c.during_turn) << std::setw(13) << share_text(c.after_turn) << std::setw(13)
         << share_text(c.all) << "\n";
  io.out << "errors at equal time (+ ahead of the prediction, + to its right)\n";
  print_errors("during turns", c.errors_during_turn, io.out);
  print_errors("after turns ", c.errors_after_turn, io.out);
  return 0;
}

}  // namespace

int cmd_band(const std::vector<std::string>& args, Io& io) {
  if (args.empty() || args[0] != "coverage") throw UsageError("expected 'band coverage'");
  return band_coverage(std::vector<std::string>(args.begin() + 1, args.end()), io);
}

}  // namespace avk::server
