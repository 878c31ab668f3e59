// `avk turns harvest`: turns harvested from the navigation of stored missions (docs/harvest.md).
#include <iomanip>
#include <ostream>

#include "app/context.hpp"
#include "app/harvest.hpp"
#include "server/cli/app_error.hpp"
#include "server/cli/args.hpp"
#include "server/cli/commands.hpp"
#include "server/cli/db_selection.hpp"
#include "server/serialize.hpp"

namespace avk::server {

void print_harvest(const app::HarvestReport& r, std::ostream& out) {
  out << "mission " << r.mission_id << " of vehicle " << r.vehicle_id << ": " << r.nav_rows
      << " navigation rows, " << r.steps << " steps of the desired heading\n";
  out << "  harvested " << r.harvested << " turns";
  if (r.harvested > 0) out << " (mean quality " << fixed(r.mean_quality, 2) << ")";
  out << ", " << r.already_recorded << " already recorded, " << r.rejected << " rejected\n";
  for (const auto& [reason, n] : r.rejected_by_reason)
    if (n > 0) out << "    " << std::left << std::setw(26) << reason << n << "\n";
}

int cmd_harvest(const std::vector<std::string>& args, Io& io) {
  const Args a(args, {"db", "mission", "vehicle", "format"}, {"all"});
  const std::string format = a.get("format").value_or("table");
  if (format != "table" && format != "json")
    throw UsageError("--format must be table or json, got '" + format + "'");
  const bool all = a.flag("all");
  if (all == a.get("mission").has_value())
    throw UsageError("give one of --mission ID or --all [--vehicle ID]");
  app::Context ctx(a.require("db"));
  std::vector<app::HarvestReport> reports;
  if (all) {
    const std::string vehicle = vehicle_of(a, ctx, {});
    reports = value_or_fail(app::harvest_vehicle(ctx, vehicle));
  } else {
    reports.push_back(
        value_or_fail(app::harvest_mission(ctx, parse_id(*a.get("mission"), "--mission"))));
  }
  if (format == "json") {
    io.out << (all ? harvest_reports_json(reports) : harvest_report_json(reports[0])).dump(2)
           << "\n";
    return 0;
  }
  std::size_t harvested = 0, steps = 0;
  for (const auto& r : reports) {
    print_harvest(r, io.out);
    harvested += r.harvested;
    steps += r.steps;
  }
  if (all)
    io.out << "total: " << harvested << " turns harvested from " << steps << " steps in "
           << reports.size() << " missions\n";
  return 0;
}

}  // namespace avk::server
