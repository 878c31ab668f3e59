#include "server/routes/routes.hpp"

#include <string>
#include <string_view>

#include "app/current.hpp"
#include "app/harvest.hpp"
#include "app/mission_mcap.hpp"
#include "app/missions.hpp"
#include "server/api_params.hpp"
#include "server/body_file.hpp"
#include "server/serialize/currents.hpp"
#include "server/serialize/missions.hpp"
#include "server/serialize/turns.hpp"
#include "server/serialize/values.hpp"

namespace avk::server {

void add_mission_routes(RouteTable& routes, app::Context& ctx,
                        std::optional<vehicle::LatLon> datum) {
  const auto list_missions = [&ctx](const ApiRequest& r, std::optional<std::string> vid) {
    const Format f = negotiate(r, true);
    const auto missions = app::list_missions(ctx, vid);
    if (f == Format::csv) return csv_response(missions_csv(missions));
    return json_response(missions_json(missions));
  };
  routes.get(
      "/api/v1/missions",
      [list_missions](const ApiRequest& r, const PathParams&) {
        return list_missions(r, std::nullopt);
      },
      kJsonOrCsv);
  routes.get(
      "/api/v1/vehicles/{vid}/missions",
      [list_missions](const ApiRequest& r, const PathParams& p) {
        return list_missions(r, p.at("vid"));
      },
      kJsonOrCsv);
  routes.post("/api/v1/vehicles/{vid}/missions", [&ctx](const ApiRequest& r, const PathParams& p) {
    require_media_type(r, "application/json", "a mission is a JSON document");
    return answer(app::start_mission(ctx, p.at("vid"), r.body), true, [](std::int64_t id) {
      const std::string location = "/api/v1/missions/" + std::to_string(id);
      return created({{"id", id}, {"location", location}}, location);
    });
  });
  const auto report = [](const app::MissionReport& m) {
    return json_response(report_json(m, true));
  };
  routes.get("/api/v1/missions/{id}", [&ctx, report](const ApiRequest&, const PathParams& p) {
    return answer(app::mission_report(ctx, path_id(p, "id", "mission")), false, report);
  });
  // The current the mission flew in: estimated from its stored navigation now, with what is
  // stored (the estimate its turns' water frame was made with); POST stores a new estimate.
  routes.get("/api/v1/missions/{id}/current", [&ctx](const ApiRequest& r, const PathParams& p) {
    const auto id = path_id(p, "id", "mission");
    const auto from = r.query.find("from");
    const bool turns = from != r.query.end() && from->second == "turns";
    if (from != r.query.end() && !turns && from->second != "legs")
      throw bad_parameter("from", "must be legs or turns");
    return answer(turns ? app::estimate_mission_current_from_turns(ctx, id)
                        : app::estimate_mission_current(ctx, id),
                  false, [&ctx, id](const app::MissionCurrent& c) {
                    return answer(app::stored_mission_current(ctx, id), false,
                                  [&c](const std::optional<app::CurrentView>& stored) {
                                    return json_response(mission_current_json(c, stored));
                                  });
                  });
  });
  routes.post("/api/v1/missions/{id}/current", [&ctx](const ApiRequest&, const PathParams& p) {
    return answer(
        app::apply_mission_current(ctx, path_id(p, "id", "mission")), true,
        [](const app::AppliedCurrent& a) { return json_response(applied_current_json(a)); });
  });
  // A page of a mission's log or track; as CSV the cursor travels in X-Next-After, like /turns.
  const auto page_response = [](Format f, const auto& page, const auto& to_csv,
                                const auto& to_json) {
    if (f == Format::csv) {
      ApiResponse resp = csv_response(to_csv(page.items));
      if (page.next) resp.headers.push_back({"X-Next-After", std::to_string(*page.next)});
      return resp;
    }
    return json_response(to_json(page));
  };
  routes.get(
      "/api/v1/missions/{id}/events",
      [&ctx, page_response](const ApiRequest& r, const PathParams& p) {
        const Format f = negotiate(r, true);
        const auto id = path_id(p, "id", "mission");
        const auto after = id_param(r, "after").value_or(0);
        const auto limit = whole_param(r, "limit", 1, 1000).value_or(100);
        return answer(app::mission_events(ctx, id, after, static_cast<int>(limit)), false,
                      [f, page_response](const app::Page<app::MissionEventView>& page) {
                        return page_response(f, page, events_csv, events_page_json);
                      });
      },
      kJsonOrCsv);
  routes.get(
      "/api/v1/missions/{id}/nav",
      [&ctx, page_response](const ApiRequest& r, const PathParams& p) {
        const Format f = negotiate(r, true);
        const auto id = path_id(p, "id", "mission");
        const auto after = id_param(r, "after").value_or(0);
        const auto limit = whole_param(r, "limit", 1, 10000).value_or(5000);
        return answer(app::mission_track(ctx, id, after, static_cast<int>(limit)), false,
                      [f, page_response](const app::Page<app::TrackPoint>& page) {
                        return page_response(f, page, nav_csv, nav_page_json);
                      });
      },
      kJsonOrCsv);
  routes.get("/api/v1/missions/{id}/last-position", [&ctx](const ApiRequest&, const PathParams& p) {
    return answer(app::mission_last_position(ctx, path_id(p, "id", "mission")), false,
                  [](const app::TrackPoint& t) { return json_response(track_point_json(t)); });
  });
  // The mission as an MCAP recording for Foxglove/Lichtblick (docs/foxglove.md).
  routes.get(
      "/api/v1/missions/{id}/export",
      [datum, &ctx](const ApiRequest& r, const PathParams& p) {
        const auto id = path_id(p, "id", "mission");
        const auto format = r.query.find("format");
        if (format == r.query.end() || format->second != "mcap")
          throw bad_parameter("format", "must be mcap (the only export format of a mission)");
        app::McapExportOptions o;
        // The station's grid on the earth (avk serve --datum), so a recording has its location
        // fixes.
        o.datum = datum;
        if (const auto c = r.query.find("compression"); c != r.query.end()) {
          if (c->second == "none")
            o.compression = app::mcap::Compression::none;
          else if (c->second != "zstd")
            throw bad_parameter("compression", "must be zstd or none");
        }
        // Written to a temporary file as it is made and sent from there: a long mission's
        // recording (tens of MB) is never held in memory whole.
        const auto file = temporary_body_file();
        const auto to_file = [&file](std::string_view bytes) { file->write(bytes); };
        return answer(
            app::export_mission_mcap(ctx, id, o, to_file), false,
            [id, &file](const app::McapExport&) {
              ApiResponse resp{200, app::kMcapMediaType, ""};
              resp.body_file = file;
              resp.headers.push_back({"Content-Disposition", "attachment; filename=\"mission-" +
                                                                 std::to_string(id) + ".mcap\""});
              return resp;
            });
      },
      {{"mcap", app::kMcapMediaType}});
  for (const auto c :
       {app::MissionCommand::pause, app::MissionCommand::resume, app::MissionCommand::abort}) {
    routes.post("/api/v1/missions/{id}/" + std::string(app::to_string(c)),
                [&ctx, report, c](const ApiRequest&, const PathParams& p) {
                  return answer(app::command_mission(ctx, path_id(p, "id", "mission"), c), true,
                                report);
                });
  }

  // Harvesting stores turns: a control endpoint like the other writes.
  routes.post("/api/v1/missions/{id}/harvest", [&ctx](const ApiRequest&, const PathParams& p) {
    return answer(
        app::harvest_mission(ctx, path_id(p, "id", "mission")), true,
        [](const app::HarvestReport& h) { return json_response(harvest_report_json(h)); });
  });
}

}  // namespace avk::server
