#include "server/routes/routes.hpp"

#include "app/ckt_tables.hpp"
#include "app/yaw_rate_table.hpp"
#include "kinematics/ckt_file.hpp"
#include "server/api_params.hpp"
#include "server/serialize/ckt.hpp"
#include "server/station.hpp"

namespace avk::server {

void add_ckt_routes(RouteTable& routes, app::Context& ctx) {
  routes.get(
      "/api/v1/vehicles/{vid}/ckt",
      [&ctx](const ApiRequest& r, const PathParams& p) {
        const Format f = negotiate(r, true);
        // ?pool=class: the table of every stored vehicle of this vehicle's kind.
        const bool pooled = pool_param(r);
        const bool harvested = include_harvested_param(r);
        return answer(pooled ? app::class_table(ctx, p.at("vid"), harvested)
                             : app::vehicle_table(ctx, p.at("vid"), harvested),
                      false, [f](const app::VehicleTable& t) {
                        if (f == Format::csv) return csv_response(kinematics::ckt_to_csv(*t.table));
                        return json_response(ckt_summary_json(t));
                      });
      },
      kJsonOrCsv);
  routes.get("/api/v1/vehicles/{vid}/ckt/cells", [&ctx](const ApiRequest& r, const PathParams& p) {
    const double speed = required_number(r, "speed", 0.0, 100.0);
    // Signed like predict's: + starboard, - port (the cell of |dheading|, mirrored).
    const double dheading = required_number(r, "dheading", -180.0, 180.0);
    return answer(app::ckt_cell(ctx, p.at("vid"), speed, dheading, include_harvested_param(r)),
                  false, [](const app::SidedCell& c) { return json_response(ckt_cell_json(c)); });
  });
  routes.get("/api/v1/vehicles/{vid}/ckt/yaw-rate", [&ctx](const ApiRequest& r,
                                                           const PathParams& p) {
    app::YawRateTableOptions o;
    o.model_id = id_param(r, "model");
    o.check_model = true;
    return answer(app::vehicle_yaw_rate_table(ctx, p.at("vid"), o), false,
                  [](const app::YawRateTable& t) { return json_response(yaw_rate_table_json(t)); });
  });
  routes.get(
      "/api/v1/vehicles/{vid}/ckt/export",
      [&ctx](const ApiRequest& r, const PathParams& p) {
        // ?format= as the Export view asks, or Accept like every other route.
        const std::string format = negotiate(r, true) == Format::csv ? "csv" : "json";
        const std::string vid = p.at("vid");
        return answer(
            app::ckt_for_export(ctx, vid, include_harvested_param(r)), false,
            [&](const kinematics::Ckt& t) {
              if (format == "csv")
                return csv_response(kinematics::ckt_to_csv(t), "ckt-" + vid + ".csv");
              ApiResponse resp{200, "application/json", kinematics::ckt_to_json_string(t), {}};
              resp.headers.push_back(
                  {"Content-Disposition", "attachment; filename=\"ckt-" + vid + ".json\""});
              return resp;
            });
      },
      kJsonOrCsv);
  routes.post(
      "/api/v1/vehicles/{vid}/ckt/import",
      [&ctx](const ApiRequest& r, const PathParams& p) {
        require_media_type(r, "application/json", "a CKT file is JSON");
        return answer(app::import_ckt(ctx, p.at("vid"), r.body), true,
                      [](const app::ImportedTable& t) {
                        return json_response(
                            {{"snapshot_id", t.snapshot_id}, {"vehicle_id", t.vehicle_id}}, 201);
                      });
      },
      kCktImportBodyLimitBytes);
}

}  // namespace avk::server
