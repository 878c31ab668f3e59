#include "server/routes/routes.hpp"

#include <vector>

#include "app/compare.hpp"
#include "app/models.hpp"
#include "server/api_params.hpp"
#include "server/serialize/comparison.hpp"
#include "server/serialize/models.hpp"
#include "server/serialize/values.hpp"

namespace avk::server {

using nlohmann::json;

namespace {

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

}  // namespace

void add_model_routes(RouteTable& routes, app::Context& ctx) {
  routes.get(
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
      kJsonOrCsv);
  routes.get(
      "/api/v1/vehicles/{vid}/models",
      [&ctx](const ApiRequest& r, const PathParams& p) {
        const Format f = negotiate(r, true);
        const auto models = app::list_models(ctx, p.at("vid"));
        if (f == Format::csv) return csv_response(models_csv(models));
        return json_response(models_json(models));
      },
      kJsonOrCsv);
  routes.post("/api/v1/vehicles/{vid}/models", [&ctx](const ApiRequest& r, const PathParams& p) {
    const json body = body_object(r, "the fit request");
    const auto missions = mission_ids(body.value("missions", json()));
    return answer(app::fit_model(ctx, p.at("vid"), missions, identification_options(body)), true,
                  [](const app::FittedModel& f) {
                    return created(model_json(f.stored),
                                   "/api/v1/models/" + std::to_string(f.stored.id));
                  });
  });
  routes.get(
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
      kJsonOrCsv);
  routes.get("/api/v1/models/{id}", [&ctx](const ApiRequest&, const PathParams& p) {
    return answer(app::get_model(ctx, path_id(p, "id", "model")), false,
                  [](const app::ModelView& m) { return json_response(model_json(m)); });
  });
  routes.get("/api/v1/models/{id}/headings", [&ctx](const ApiRequest& r, const PathParams& p) {
    const auto model = path_id(p, "id", "model");
    const auto mission = id_param(r, "mission");
    if (!mission) throw bad_parameter("mission", "missing");
    const auto limit = whole_param(r, "limit", 1, 100000).value_or(2400);
    return answer(
        app::model_headings(ctx, model, *mission, static_cast<std::size_t>(limit)), false,
        [](const app::ModelHeadings& h) { return json_response(model_headings_json(h)); });
  });
}

}  // namespace avk::server
