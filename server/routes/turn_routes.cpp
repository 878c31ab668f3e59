#include "server/routes/routes.hpp"

#include "app/turns.hpp"
#include "server/api_params.hpp"
#include "server/serialize/turns.hpp"
#include "server/serialize/values.hpp"

namespace avk::server {

void add_turn_routes(RouteTable& routes, app::Context& ctx) {
  routes.get(
      "/api/v1/turns",
      [&ctx](const ApiRequest& r, const PathParams&) {
        const Format f = negotiate(r, true);
        app::TurnQuery filter;
        filter.mission_id = id_param(r, "mission");
        filter.speed_mps = number_param(r, "speed", 0.0, 100.0);
        filter.dheading_deg = number_param(r, "dheading", -180.0, 180.0);
        if (const auto it = r.query.find("status"); it != r.query.end()) {
          const auto s = kinematics::turn_status_from_string(it->second);
          if (!s) throw bad_parameter("status", "must be ok, aborted or rejected");
          filter.status = *s;
        }
        filter.after_id = id_param(r, "after").value_or(0);
        filter.limit = static_cast<int>(whole_param(r, "limit", 1, 1000).value_or(100));
        return answer(app::query_turns(ctx, filter), false,
                      [f](const app::Page<app::TurnView>& page) {
                        if (f == Format::csv) {
                          ApiResponse resp = csv_response(turns_csv(page.items));
                          if (page.next)
                            resp.headers.push_back({"X-Next-After", std::to_string(*page.next)});
                          return resp;
                        }
                        return json_response(turns_page_json(page));
                      });
      },
      kJsonOrCsv);
  routes.get("/api/v1/turns/{id}", [&ctx](const ApiRequest&, const PathParams& p) {
    return answer(app::get_turn(ctx, path_id(p, "id", "turn")), false,
                  [](const app::TurnDetail& t) { return json_response(turn_json(t)); });
  });
}

}  // namespace avk::server
