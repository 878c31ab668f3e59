#include "server/station.hpp"

#include <algorithm>
#include <chrono>
#include <limits>
#include <map>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "app/ckt_tables.hpp"
#include "app/compare.hpp"
#include "app/current.hpp"
#include "app/encounters.hpp"
#include "app/foxglove_scene.hpp"
#include "app/harvest.hpp"
#include "app/maneuvers.hpp"
#include "app/mission_mcap.hpp"
#include "app/missions.hpp"
#include "app/models.hpp"
#include "app/predict.hpp"
#include "app/turns.hpp"
#include "app/vehicle_motion.hpp"
#include "app/vehicles.hpp"
#include "kinematics/ckt_file.hpp"
#include "server/api_errors.hpp"
#include "server/api_params.hpp"
#include "server/maneuver_requests.hpp"
#include "server/map_tile_routes.hpp"
#include "server/serialize.hpp"
#include "server/vocabulary_json.hpp"
#include "sim/sim_config.hpp"

namespace avk::server {

using nlohmann::json;

namespace {

ApiResponse json_response(const json& j, int status = 200) {
  return {status, "application/json", j.dump(), {}};
}

ApiResponse csv_response(std::string body, const std::string& filename = "") {
  ApiResponse r{200, "text/csv; charset=utf-8", std::move(body), {}};
  if (!filename.empty())
    r.headers.push_back({"Content-Disposition", "attachment; filename=\"" + filename + "\""});
  return r;
}

ApiResponse created(const json& j, const std::string& location) {
  ApiResponse r = json_response(j, 201);
  r.headers.push_back({"Location", location});
  return r;
}

// The use case's value, or its error as problem+json.
template <class T, class F>
ApiResponse answer(const app::Result<T>& r, bool document, F&& write) {
  if (!r) return problem_of(r.error(), document);
  return write(*r);
}

// A request document: an object, else 400 (not JSON at all) before any field is looked at.
json body_object(const ApiRequest& r, const std::string& what) {
  require_media_type(r, "application/json", "send " + what + " as JSON");
  json body = json::parse(r.body, nullptr, false);
  if (body.is_discarded() || !body.is_object())
    throw RequestError(400, "the body is not a JSON object");
  return body;
}

RequestError bad_field(const std::string& pointer, const std::string& why) {
  return RequestError(422, pointer + " " + why, {{"pointer", pointer}});
}

kinematics::IdentificationOptions identification_options(const json& body) {
  kinematics::IdentificationOptions o;
  if (body.contains("form")) {
    const auto form = body["form"].is_string()
                          ? kinematics::yaw_model_form_from_string(body["form"].get<std::string>())
                          : std::nullopt;
    if (!form) throw bad_field("/form", "must be thesis or invariant");
    o.form = *form;
  }
  if (body.contains("history_s")) {
    const json& h = body["history_s"];
    if (!h.is_number() || !(h.get<double>() > 0.0) || h.get<double>() > 120.0)
      throw bad_field("/history_s", "must be in (0, 120] seconds");
    o.history_s = h.get<double>();
  }
  if (body.contains("refine")) {
    if (!body["refine"].is_boolean()) throw bad_field("/refine", "must be true or false");
    o.refine = body["refine"].get<bool>();
  }
  return o;
}

std::vector<std::int64_t> mission_ids(const json& v) {
  if (!v.is_array() || v.empty()) throw bad_field("/missions", "must be a non-empty array of ids");
  std::vector<std::int64_t> ids;
  for (const auto& e : v) {
    if (!e.is_number_integer() || e.get<std::int64_t>() <= 0)
      throw bad_field("/missions", "holds a bad id: " + describe_value(e));
    ids.push_back(e.get<std::int64_t>());
  }
  return ids;
}

std::vector<std::int64_t> mission_params(const ApiRequest& r) {
  std::vector<std::int64_t> ids;
  for (auto [it, end] = r.multi_query.equal_range("mission"); it != end; ++it) {
    const json v = json::parse(it->second, nullptr, false);
    if (!v.is_number_integer() || v.get<std::int64_t>() <= 0)
      throw bad_parameter("mission", "must be a mission id");
    ids.push_back(v.get<std::int64_t>());
  }
  return ids;
}

app::PredictQuery predict_query(const ApiRequest& r, const std::string& vid) {
  app::PredictQuery q;
  q.vehicle_id = vid;
  // Any finite numbers here: the use case checks speed and heading change together, against
  // the vehicle's table too, so that an answer names every one that is off and its range.
  constexpr double kAny = std::numeric_limits<double>::infinity();
  const auto turn = required_numbers(r, {{"speed", -kAny, kAny}, {"dheading", -kAny, kAny}});
  q.speed_mps = turn[0];
  q.dheading_deg = turn[1];
  q.method = method_param(r).value_or(q.method);
  q.model_id = id_param(r, "model");
  const auto x = number_param(r, "x", -1e7, 1e7);
  const auto y = number_param(r, "y", -1e7, 1e7);
  const auto heading = number_param(r, "heading", -360.0, 720.0);
  if ((x || y || heading) && !(x && y && heading))
    throw bad_parameter(x ? (y ? "heading" : "y") : "x", "a pose needs x, y and heading");
  if (x) q.pose = kinematics::Pose{*x, *y, *heading};
  q.corridor_share = number_param(r, "corridor", 0.5, 0.999).value_or(q.corridor_share);
  const CurrentParam current = current_param(r);
  q.current = current.current;
  q.live_current = current.live;
  q.no_current = current.none;
  q.speed_over_ground = speed_reference_param(r);
  q.include_harvested = include_harvested_param(r);
  q.initial_yaw_rate_dps = number_param(r, "initial_yaw_rate", -90.0, 90.0);
  q.speed_after_mps = number_param(r, "speed_after", 0.0, 100.0);
  q.without_mission_id = id_param(r, "without_mission");
  q.without_turn_id = id_param(r, "without_turn");
  return q;
}

}  // namespace

Station::Station(StationOptions options, StreamHub& hub)
    : Router(options.token),
      options_(std::move(options)),
      hub_(hub),
      feed_(hub),
      foxglove_(
          hub.foxglove(),
          [this](const std::string& vid, double speed_mps, double dheading_deg,
                 const kinematics::Pose& start) {
            return app::foxglove::scene_predictions(context_, vid, speed_mps, dheading_deg, start);
          },
          options_.datum),
      feeds_({&feed_, &foxglove_}),
      context_(options_.db_path, options_.vehicle, &feeds_) {
  add_routes();
}

Station::~Station() {
  shutdown();
}

void Station::start() {
  context_.start();
}

void Station::shutdown() {
  context_.shutdown("the server stopped");
  foxglove_.withdraw();
}

void Station::add_routes() {
  app::Context& ctx = context_;
  // How much work each answer takes (docs/api.md, "Request work"); a route not named here is
  // cheap. Immediate: answered on an I/O thread, so /health answers while every request worker
  // is busy. Expensive: work that grows with the stored data (whole missions, every turn, a
  // simulation, a fit), limited in number and per client address.
  const RouteCost expensive{Workload::expensive};
  std::map<std::string, std::pair<RouteCost, bool>> costs = {
      {"GET /api/v1/health", {{Workload::immediate}, false}},
      {"GET /api/v1/meta", {{Workload::immediate}, false}},
      {"GET /api/v1/missions/{id}/current", {expensive, false}},
      {"GET /api/v1/missions/{id}/export", {expensive, false}},
      {"POST /api/v1/missions/{id}/harvest", {expensive, false}},
      {"GET /api/v1/vehicles/{vid}/ckt/yaw-rate", {expensive, false}},
      {"POST /api/v1/vehicles/{vid}/ckt/import", {expensive, false}},
      // A table built for the answer: the vehicle's other turns, or its table over yaw rate.
      {"GET /api/v1/vehicles/{vid}/predict",
       {{Workload::cheap, {"without_turn", "without_mission", "initial_yaw_rate"}}, false}},
      {"POST /api/v1/vehicles/{vid}/maneuvers/evaluate", {expensive, false}},
      {"POST /api/v1/vehicles/{vid}/maneuvers/simulate", {expensive, false}},
      {"GET /api/v1/vehicles/{vid}/compare", {expensive, false}},
      {"POST /api/v1/vehicles/{vid}/models", {expensive, false}},
      {"GET /api/v1/vehicles/{vid}/models/sweep", {expensive, false}},
      {"GET /api/v1/models/{id}/headings", {expensive, false}},
  };
  const auto route = [this, &costs](std::string method, std::string pattern, Access access,
                                    RouteHandler h, std::optional<std::size_t> limit,
                                    std::vector<Representation> representations) {
    RouteCost cost;
    if (const auto it = costs.find(method + " " + pattern); it != costs.end()) {
      cost = it->second.first;
      it->second.second = true;
    }
    Route r;
    r.method = std::move(method);
    r.pattern = std::move(pattern);
    r.access = access;
    r.body_limit_bytes = limit;
    r.handler = std::move(h);
    r.representations = std::move(representations);
    add(std::move(r), std::move(cost));
  };
  const auto get = [route](std::string pattern, RouteHandler h,
                           std::vector<Representation> representations = {kJsonRepresentation}) {
    route("GET", std::move(pattern), Access::read, std::move(h), std::nullopt,
          std::move(representations));
  };
  // A collection or table: JSON, or CSV with units in its column names (docs/api.md, "CSV").
  const std::vector<Representation> json_or_csv{kJsonRepresentation, kCsvRepresentation};
  const auto post = [route](std::string pattern, RouteHandler h,
                            std::optional<std::size_t> limit = std::nullopt) {
    route("POST", std::move(pattern), Access::control, std::move(h), limit, {kJsonRepresentation});
  };
  // A question sent as a document that changes nothing and commands nothing: open on loopback,
  // like the reads.
  const auto post_question = [route](std::string pattern, RouteHandler h) {
    route("POST", std::move(pattern), Access::read, std::move(h), std::nullopt,
          {kJsonRepresentation});
  };

  // --- the station, vehicles ---------------------------------------------------------------
  get("/api/v1/health", [this, &ctx](const ApiRequest&, const PathParams&) {
    app::VehicleLoop* loop = ctx.vehicle_loop();
    json j = {{"status", "ok"},
              {"server_version", options_.server_version},
              {"session_id", hub_.session_id()},
              {"vehicle_id", loop ? json(loop->info().id) : json()}};
    // The station clock beside the wall clock at one moment: every time of this session (nav,
    // events, turns) is in the station clock, which runs x realtime_factor on the simulator; a
    // front end shows wall-clock time as utc_ms - (clock_s - t_s) / realtime_factor * 1000.
    j["utc_ms"] = std::chrono::duration_cast<std::chrono::milliseconds>(
                      std::chrono::system_clock::now().time_since_epoch())
                      .count();
    // Before the loop's first telemetry tick its snapshot has no time yet: the clock is at its
    // start then.
    j["clock_s"] = loop && options_.vehicle
                       ? json(std::max(loop->snapshot().t_s, options_.vehicle->start_clock_s))
                       : json();
    j["realtime_factor"] = options_.vehicle ? json(options_.vehicle->realtime_factor) : json();
    // Where this session's clock began: a mission started before it ran in an earlier session,
    // whose times the mapping above does not fit.
    j["session_start_clock_s"] = options_.vehicle ? json(options_.vehicle->start_clock_s) : json();
    j["datum"] = options_.datum ? json{{"lat_deg", options_.datum->lat_deg},
                                       {"lon_deg", options_.datum->lon_deg}}
                                : json();
    return json_response(j);
  });
  // The names the station uses (event kinds with their severity, helm modes, link states, turn
  // statuses), so a client keeps no copy of its own.
  get("/api/v1/meta",
      [](const ApiRequest&, const PathParams&) { return json_response(vocabulary_json()); });
  get(
      "/api/v1/vehicles",
      [&ctx](const ApiRequest& r, const PathParams&) {
        const Format f = negotiate(r, true);
        const auto vehicles = app::list_vehicles(ctx);
        if (f == Format::csv) return csv_response(vehicles_csv(vehicles));
        json out = json::array();
        for (const auto& v : vehicles)
          out.push_back(vehicle_json(v));
        return json_response(out);
      },
      json_or_csv);
  get("/api/v1/vehicles/{vid}", [&ctx](const ApiRequest&, const PathParams& p) {
    return answer(app::get_vehicle(ctx, p.at("vid")), false,
                  [](const app::VehicleStatus& v) { return json_response(vehicle_json(v)); });
  });

  // --- missions ----------------------------------------------------------------------------
  const auto list_missions = [&ctx](const ApiRequest& r, std::optional<std::string> vid) {
    const Format f = negotiate(r, true);
    const auto missions = app::list_missions(ctx, vid);
    if (f == Format::csv) return csv_response(missions_csv(missions));
    json out = json::array();
    for (const auto& m : missions)
      out.push_back(mission_json(m));
    return json_response(out);
  };
  get(
      "/api/v1/missions",
      [list_missions](const ApiRequest& r, const PathParams&) {
        return list_missions(r, std::nullopt);
      },
      json_or_csv);
  get(
      "/api/v1/vehicles/{vid}/missions",
      [list_missions](const ApiRequest& r, const PathParams& p) {
        return list_missions(r, p.at("vid"));
      },
      json_or_csv);
  post("/api/v1/vehicles/{vid}/missions", [&ctx](const ApiRequest& r, const PathParams& p) {
    require_media_type(r, "application/json", "a mission is a JSON document");
    return answer(app::start_mission(ctx, p.at("vid"), r.body), true, [](std::int64_t id) {
      const std::string location = "/api/v1/missions/" + std::to_string(id);
      return created({{"id", id}, {"location", location}}, location);
    });
  });
  const auto report = [](const app::MissionReport& m) {
    return json_response(report_json(m, true));
  };
  get("/api/v1/missions/{id}", [&ctx, report](const ApiRequest&, const PathParams& p) {
    return answer(app::mission_report(ctx, path_id(p, "id", "mission")), false, report);
  });
  // The current the mission flew in: estimated from its stored navigation now, with what is
  // stored (the estimate its turns' water frame was made with); POST stores a new estimate.
  get("/api/v1/missions/{id}/current", [&ctx](const ApiRequest& r, const PathParams& p) {
    const auto id = path_id(p, "id", "mission");
    const auto from = r.query.find("from");
    const bool turns = from != r.query.end() && from->second == "turns";
    if (from != r.query.end() && !turns && from->second != "legs")
      throw bad_parameter("from", "must be legs or turns");
    return answer(
        turns ? app::estimate_mission_current_from_turns(ctx, id)
              : app::estimate_mission_current(ctx, id),
        false, [&ctx, id](const app::MissionCurrent& c) {
          return json_response(mission_current_json(c, ctx.db().currents().for_mission(id)));
        });
  });
  post("/api/v1/missions/{id}/current", [&ctx](const ApiRequest&, const PathParams& p) {
    return answer(app::apply_mission_current(ctx, path_id(p, "id", "mission")), true,
                  [](const app::AppliedCurrent& a) {
                    json j = mission_current_json(a.current, a.stored);
                    j["water_frame_turns"] = a.water_turns;
                    return json_response(j);
                  });
  });
  // A page of a mission's log or track; as CSV the cursor travels in X-Next-After, like /turns.
  const auto page_response = [](Format f, const auto& page, const auto& to_csv,
                                const auto& item_json) {
    if (f == Format::csv) {
      ApiResponse resp = csv_response(to_csv(page.items));
      if (page.next) resp.headers.push_back({"X-Next-After", std::to_string(*page.next)});
      return resp;
    }
    json items = json::array();
    for (const auto& item : page.items)
      items.push_back(item_json(item));
    return json_response({{"items", items}, {"next", optional_json(page.next)}});
  };
  get(
      "/api/v1/missions/{id}/events",
      [&ctx, page_response](const ApiRequest& r, const PathParams& p) {
        const Format f = negotiate(r, true);
        const auto id = path_id(p, "id", "mission");
        const auto after = id_param(r, "after").value_or(0);
        const auto limit = whole_param(r, "limit", 1, 1000).value_or(100);
        return answer(app::mission_events(ctx, id, after, static_cast<int>(limit)), false,
                      [f, page_response](const app::Page<store::MissionEvent>& page) {
                        return page_response(f, page, events_csv, event_json);
                      });
      },
      json_or_csv);
  get(
      "/api/v1/missions/{id}/nav",
      [&ctx, page_response](const ApiRequest& r, const PathParams& p) {
        const Format f = negotiate(r, true);
        const auto id = path_id(p, "id", "mission");
        const auto after = id_param(r, "after").value_or(0);
        const auto limit = whole_param(r, "limit", 1, 10000).value_or(5000);
        return answer(app::mission_track(ctx, id, after, static_cast<int>(limit)), false,
                      [f, page_response](const app::Page<store::NavPageRow>& page) {
                        return page_response(f, page, nav_csv, [](const store::NavPageRow& row) {
                          return nav_row_json(row.row);
                        });
                      });
      },
      json_or_csv);
  // The mission as an MCAP recording for Foxglove/Lichtblick (docs/foxglove.md).
  get("/api/v1/missions/{id}/export",
      [this, &ctx](const ApiRequest& r, const PathParams& p) {
        const auto id = path_id(p, "id", "mission");
        const auto format = r.query.find("format");
        if (format == r.query.end() || format->second != "mcap")
          throw bad_parameter("format", "must be mcap (the only export format of a mission)");
        app::McapExportOptions o;
        // The station's grid on the earth (avk serve --datum), so a recording has its location
        // fixes.
        o.datum = options_.datum;
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
    post("/api/v1/missions/{id}/" + std::string(app::to_string(c)),
         [&ctx, report, c](const ApiRequest&, const PathParams& p) {
           return answer(app::command_mission(ctx, path_id(p, "id", "mission"), c), true, report);
         });
  }

  // Harvesting stores turns: a control endpoint like the other writes.
  post("/api/v1/missions/{id}/harvest", [&ctx](const ApiRequest&, const PathParams& p) {
    return answer(
        app::harvest_mission(ctx, path_id(p, "id", "mission")), true,
        [](const app::HarvestReport& h) { return json_response(harvest_report_json(h)); });
  });

  // --- turns -------------------------------------------------------------------------------
  get(
      "/api/v1/turns",
      [&ctx](const ApiRequest& r, const PathParams&) {
        const Format f = negotiate(r, true);
        store::TurnFilter filter;
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
        return answer(
            app::query_turns(ctx, filter), false, [f](const app::Page<store::TurnRow>& page) {
              if (f == Format::csv) {
                ApiResponse resp = csv_response(turns_csv(page.items));
                if (page.next) resp.headers.push_back({"X-Next-After", std::to_string(*page.next)});
                return resp;
              }
              json items = json::array();
              for (const auto& t : page.items)
                items.push_back(turn_row_json(t));
              return json_response({{"items", items}, {"next", optional_json(page.next)}});
            });
      },
      json_or_csv);
  get("/api/v1/turns/{id}", [&ctx](const ApiRequest&, const PathParams& p) {
    return answer(app::get_turn(ctx, path_id(p, "id", "turn")), false,
                  [](const store::StoredTurn& t) { return json_response(turn_json(t)); });
  });

  // --- the CKT -----------------------------------------------------------------------------
  get(
      "/api/v1/vehicles/{vid}/ckt",
      [&ctx](const ApiRequest& r, const PathParams& p) {
        const Format f = negotiate(r, true);
        return answer(app::vehicle_table(ctx, p.at("vid"), include_harvested_param(r)), false,
                      [f](const app::VehicleTable& t) {
                        if (f == Format::csv) return csv_response(kinematics::ckt_to_csv(*t.table));
                        return json_response(ckt_summary_json(t));
                      });
      },
      json_or_csv);
  get("/api/v1/vehicles/{vid}/ckt/cells", [&ctx](const ApiRequest& r, const PathParams& p) {
    const double speed = required_number(r, "speed", 0.0, 100.0);
    // Signed like predict's: + starboard, - port (the cell of |dheading|, mirrored).
    const double dheading = required_number(r, "dheading", -180.0, 180.0);
    return answer(app::ckt_cell(ctx, p.at("vid"), speed, dheading, include_harvested_param(r)),
                  false, [](const app::SidedCell& c) { return json_response(ckt_cell_json(c)); });
  });
  get("/api/v1/vehicles/{vid}/ckt/yaw-rate", [&ctx](const ApiRequest& r, const PathParams& p) {
    app::YawRateTableOptions o;
    o.model_id = id_param(r, "model");
    o.check_model = true;
    return answer(app::vehicle_yaw_rate_table(ctx, p.at("vid"), o), false,
                  [](const app::YawRateTable& t) { return json_response(yaw_rate_table_json(t)); });
  });
  get(
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
      json_or_csv);
  post(
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

  // --- predictions, models, the comparison ---------------------------------------------------
  // The station's estimate of the current the vehicle is in (the running mission's, updated at
  // every turn; else its newest mission's).
  get("/api/v1/vehicles/{vid}/current", [&ctx](const ApiRequest&, const PathParams& p) {
    const std::string vid = p.at("vid");
    auto c = app::vehicle_current(ctx, vid);
    // No estimate yet is an answer, not a missing resource: a page asks on every load.
    if (!c && c.error().code == app::ErrorCode::not_found)
      return json_response({{"vehicle_id", vid}, {"estimated", false}});
    return answer(std::move(c), false, [&vid](const store::StoredCurrent& cur) {
      return json_response(current_json(vid, cur));
    });
  });
  // What the station has learned of how the vehicle moves on a held heading: which speed its loop
  // holds, how fast a straight-line prediction's error grows, the current it was last seen in.
  get("/api/v1/vehicles/{vid}/motion", [&ctx](const ApiRequest&, const PathParams& p) {
    return answer(app::vehicle_motion(ctx, p.at("vid")), false, [](const app::VehicleMotion& m) {
      return json_response(vehicle_motion_json(m));
    });
  });
  get("/api/v1/vehicles/{vid}/predict", [&ctx](const ApiRequest& r, const PathParams& p) {
    return answer(app::predict(ctx, predict_query(r, p.at("vid"))), false,
                  [](const app::Prediction& pr) { return json_response(prediction_json(pr)); });
  });
  // --- maneuvers: candidates scored by CPA, a maneuver in progress, one flown in the simulator --
  post_question("/api/v1/vehicles/{vid}/maneuvers/evaluate", [&ctx](const ApiRequest& r,
                                                                    const PathParams& p) {
    const auto request = maneuver_request(body_object(r, "the encounter"), p.at("vid"));
    if (!request) return problem_of(request.error(), true);
    return answer(app::evaluate_maneuvers(ctx, request->query), true,
                  [&](const app::ManeuverEvaluation& e) {
                    return ApiResponse{200, "application/json",
                                       maneuver_evaluation_text(e, request->path_step_s)};
                  });
  });
  get("/api/v1/vehicles/{vid}/maneuvers/ongoing", [&ctx](const ApiRequest& r, const PathParams& p) {
    return answer(
        app::evaluate_ongoing(ctx, ongoing_query(r, p.at("vid"))), false,
        [](const app::OngoingManeuver& o) { return json_response(ongoing_maneuver_json(o)); });
  });
  post_question("/api/v1/vehicles/{vid}/maneuvers/simulate", [this](const ApiRequest& r,
                                                                    const PathParams& p) {
    auto request = simulate_request(body_object(r, "the maneuver"));
    if (!request) return problem_of(request.error(), true);
    const std::string vid = p.at("vid");
    // The station's simulated vehicle flies its own setup; anything else (a real
    // boat, another vehicle's id) the calibrated M200's defaults.
    const auto& v = options_.vehicle;
    const bool own_setup = v && !v->m200 && v->setup.vehicle.id == vid;
    request->query.setup = own_setup ? v->setup : sim::default_sim_setup(kDefaultManeuverSimKind);
    return answer(
        app::simulate_maneuver(request->query), true, [&](const app::SimulatedManeuver& m) {
          json j = simulated_maneuver_json(m, request->own_position, request->standoff_m,
                                           request->path_step_s);
          j["vehicle_id"] = vid;
          j["sim_vehicle"] = request->query.setup.vehicle.kind;
          j["station_setup"] = own_setup;
          if (!own_setup)
            j["note"] =
                "the vehicle is not the station's simulated one: "
                "flown with the default " +
                std::string(kDefaultManeuverSimKind) + " setup";
          j["seed"] = request->query.seed;
          j["dheading_deg"] = request->query.dheading_deg;
          j["speed_mps"] = request->query.speed_mps.value_or(request->query.own_speed_mps);
          return json_response(j);
        });
  });
  get(
      "/api/v1/vehicles/{vid}/compare",
      [&ctx](const ApiRequest& r, const PathParams& p) {
        const Format f = negotiate(r, true);
        app::CompareQuery q;
        q.vehicle_id = p.at("vid");
        q.model_id = id_param(r, "model");
        q.corridor_share = number_param(r, "corridor", 0.5, 0.999).value_or(q.corridor_share);
        for (auto [it, end] = r.multi_query.equal_range("test_mission"); it != end; ++it) {
          const json v = json::parse(it->second, nullptr, false);
          if (!v.is_number_integer() || v.get<std::int64_t>() <= 0)
            throw bad_parameter("test_mission", "must be a mission id");
          q.test_missions.push_back(v.get<std::int64_t>());
        }
        bool in_sample = false;
        if (const auto it = r.query.find("scoring"); it != r.query.end()) {
          if (it->second != "predictive" && it->second != "in_sample")
            throw bad_parameter("scoring", "must be predictive or in_sample");
          in_sample = it->second == "in_sample";
        }
        return answer(app::compare(ctx, q), false, [f, &q, in_sample](const app::Comparison& c) {
          if (f == Format::csv)
            return csv_response(in_sample ? comparison_csv(c) : predictive_csv(c),
                                "compare-" + q.vehicle_id + ".csv");
          return json_response(comparison_json(c));
        });
      },
      json_or_csv);
  get(
      "/api/v1/vehicles/{vid}/models",
      [&ctx](const ApiRequest& r, const PathParams& p) {
        const Format f = negotiate(r, true);
        const auto models = app::list_models(ctx, p.at("vid"));
        if (f == Format::csv) return csv_response(models_csv(models));
        json out = json::array();
        for (const auto& m : models)
          out.push_back(model_json(m, false));
        return json_response(out);
      },
      json_or_csv);
  post("/api/v1/vehicles/{vid}/models", [&ctx](const ApiRequest& r, const PathParams& p) {
    const json body = body_object(r, "the fit request");
    const auto missions = mission_ids(body.value("missions", json()));
    return answer(app::fit_model(ctx, p.at("vid"), missions, identification_options(body)), true,
                  [](const app::FittedModel& f) {
                    return created(model_json(f.stored),
                                   "/api/v1/models/" + std::to_string(f.stored.id));
                  });
  });
  get(
      "/api/v1/vehicles/{vid}/models/sweep",
      [&ctx](const ApiRequest& r, const PathParams& p) {
        const Format f = negotiate(r, true);
        const auto missions = mission_params(r);
        if (missions.empty()) throw bad_parameter("mission", "missing");
        return answer(app::sweep_model_history(ctx, p.at("vid"), missions, {}), false,
                      [f](const std::vector<kinematics::HistorySweepRow>& rows) {
                        if (f == Format::csv) return csv_response(sweep_csv(rows));
                        return json_response(sweep_json(rows));
                      });
      },
      json_or_csv);
  get("/api/v1/models/{id}", [&ctx](const ApiRequest&, const PathParams& p) {
    return answer(app::get_model(ctx, path_id(p, "id", "model")), false,
                  [](const store::StoredModel& m) { return json_response(model_json(m)); });
  });
  get("/api/v1/models/{id}/headings", [&ctx](const ApiRequest& r, const PathParams& p) {
    const auto model = path_id(p, "id", "model");
    const auto mission = id_param(r, "mission");
    if (!mission) throw bad_parameter("mission", "missing");
    const auto limit = whole_param(r, "limit", 1, 100000).value_or(2400);
    return answer(
        app::model_headings(ctx, model, *mission, static_cast<std::size_t>(limit)), false,
        [](const app::ModelHeadings& h) { return json_response(model_headings_json(h)); });
  });

  // --- the map background (avk serve --tiles) ---------------------------------------------
  add_map_tile_routes(*this, options_.tiles, options_.datum);

  for (const auto& [key, cost] : costs)
    if (!cost.second) throw std::logic_error("Station: a cost for no route: " + key);
}

}  // namespace avk::server
