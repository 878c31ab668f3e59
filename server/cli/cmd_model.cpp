// avk model fit|sweep|list, avk predict, avk compare: the black-box yaw model and the comparison
// of prediction methods (thesis §3.4, §5.2), over the navigation logs and turns in the store.
#include <cmath>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <ostream>
#include <set>
#include <sstream>

#include "kinematics/angles.hpp"
#include "kinematics/ckt.hpp"
#include "kinematics/prediction_comparison.hpp"
#include "kinematics/yaw_identification.hpp"
#include "kinematics/yaw_model_json.hpp"
#include "mission/helm_mode.hpp"
#include "server/cli/args.hpp"
#include "server/cli/commands.hpp"
#include "server/cli/db_selection.hpp"
#include "server/cli/sim_options.hpp"
#include "store/store.hpp"

namespace avk::server {

namespace {

namespace kin = avk::kinematics;
using nlohmann::json;

std::string fixed(double v, int decimals) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(decimals) << v;
  return s.str();
}

// Navigation of the vehicle under guidance: samples while the helm commanded motion (or imported
// logs, whose helm state is unknown). All-stop stretches are left out, so they split segments.
bool guided(const std::string& helm_mode) {
  if (helm_mode == "IMPORTED") return true;
  const auto m = mission::helm_mode_from_string(helm_mode);
  return m && mission::commands_motion(*m);
}

std::vector<kin::IdentSegment> identification_data(store::Store& db,
                                                   const std::vector<std::int64_t>& missions,
                                                   const kin::ResampleOptions& options) {
  std::vector<kin::IdentSegment> out;
  for (const std::int64_t id : missions) {
    if (!db.get_mission(id)) throw std::runtime_error("no mission " + std::to_string(id));
    kin::NavStreams s;
    for (const auto& r : db.nav_for_mission(id)) {
      if (!guided(r.helm_mode) || !r.desired_heading_deg) continue;
      s.heading_deg.push_back({r.t_s, r.heading_deg});
      s.desired_heading_deg.push_back({r.t_s, *r.desired_heading_deg});
      s.x_m.push_back({r.t_s, r.x_m});
      s.y_m.push_back({r.t_s, r.y_m});
      s.speed_mps.push_back({r.t_s, r.speed_mps});
      if (r.desired_speed_mps) s.desired_speed_mps.push_back({r.t_s, *r.desired_speed_mps});
    }
    if (s.desired_speed_mps.size() != s.heading_deg.size()) s.desired_speed_mps.clear();
    for (auto& seg : kin::resample(s, options))
      out.push_back(std::move(seg));
  }
  if (out.empty())
    throw std::runtime_error("the missions hold no guided navigation to identify from");
  return out;
}

kin::IdentificationOptions identification_options(const Args& a) {
  kin::IdentificationOptions o;
  if (const auto f = a.get("form")) {
    const auto form = kin::yaw_model_form_from_string(*f);
    if (!form) throw UsageError("--form must be thesis or invariant, got '" + *f + "'");
    o.form = *form;
  }
  if (const auto h = a.number("history")) {
    if (!(*h > 0.0 && *h <= 120.0)) throw UsageError("--history must be in (0, 120] seconds");
    o.history_s = *h;
  }
  if (const auto r = a.get("ridge"); r && *r != "auto") {
    const auto v = a.number("ridge");
    if (!(*v >= 0.0)) throw UsageError("--ridge must be auto or a relative strength >= 0");
    o.ridge_lambda = *v;
  }
  o.refine = a.flag("refine");
  return o;
}

kin::ResampleOptions resample_options(const Args& a) {
  kin::ResampleOptions r;
  if (const auto hz = a.number("rate")) {
    if (!(*hz > 0.0 && *hz <= 100.0)) throw UsageError("--rate must be in (0, 100] Hz");
    r.rate_hz = *hz;
  }
  return r;
}

json model_json(const store::StoredModel& m) {
  json j = json::parse(kin::yaw_model_to_json(m.model));
  j["id"] = m.id;
  j["created_utc"] = m.created_utc;
  j["vehicle_id"] = m.vehicle_id;
  j["training_missions"] = m.training_missions;
  j["train_one_step_rms_deg"] = m.train_one_step_rms_deg ? json(*m.train_one_step_rms_deg) : json();
  j["validation_mse_m2"] = m.validation_mse_m2 ? json(*m.validation_mse_m2) : json();
  j["validation_heading_rms_deg"] =
      m.validation_heading_rms_deg ? json(*m.validation_heading_rms_deg) : json();
  return j;
}

int model_fit(const std::vector<std::string>& rest, Io& io) {
  const Args a(rest, {"db", "form", "history", "ridge", "rate", "vehicle"}, {"refine"},
               {"mission"});
  store::Store db(a.require("db"));
  const auto missions = mission_ids(a);
  if (missions.empty()) throw UsageError("give the training data: --mission ID (repeatable)");
  const std::string vehicle = vehicle_of(a, db, missions);
  const auto data = identification_data(db, missions, resample_options(a));
  const auto r = kin::identify_yaw_model(data, identification_options(a));
  store::StoredModel m;
  m.vehicle_id = vehicle;
  m.training_missions = missions;
  m.model = r.model;
  m.train_one_step_rms_deg = r.train_one_step_rms_deg;
  if (r.validation.windows) {
    m.validation_mse_m2 = r.validation.position_mse_m2;
    m.validation_heading_rms_deg = r.validation.heading_rms_deg;
  }
  m.id = db.save_model(m);
  const auto& mo = r.model;
  io.out << "model " << m.id << " of " << vehicle << ": " << kin::to_string(mo.form) << " form, "
         << mo.history << " samples of history (" << fixed(mo.history / mo.rate_hz, 2) << " s at "
         << fixed(mo.rate_hz, 2) << " Hz), " << mo.coefficient_count() << " coefficients, ridge "
         << mo.ridge_lambda;
  if (r.refinement) {
    if (r.refinement->best_iteration == 0) {
      io.out << ", refinement ran " << r.refinement->iterations
             << " iterations but none lowered the validation error: least-squares coefficients "
                "kept";
    } else {
      io.out << ", refined (iteration " << r.refinement->best_iteration << " of "
             << r.refinement->iterations << ", weighted cost "
             << fixed(r.refinement->initial_cost, 1) << " -> " << fixed(r.refinement->final_cost, 1)
             << ")";
    }
  }
  io.out << "\n  training:   " << r.train_segments << " segments, one-step heading RMS "
         << fixed(r.train_one_step_rms_deg, 3) << " deg, trajectory MSE "
         << fixed(r.train.position_mse_m2, 3) << " m^2 over " << r.train.windows << " turns\n"
         << "  validation: " << r.validation_segments << " segments, trajectory MSE "
         << fixed(r.validation.position_mse_m2, 3) << " m^2, heading RMS "
         << fixed(r.validation.heading_rms_deg, 2) << " deg over " << r.validation.windows
         << " turns\n";
  return 0;
}

int model_sweep(const std::vector<std::string>& rest, Io& io) {
  const Args a(rest, {"db", "form", "ridge", "rate", "vehicle", "format"}, {"refine"}, {"mission"});
  store::Store db(a.require("db"));
  const auto missions = mission_ids(a);
  if (missions.empty()) throw UsageError("give the data: --mission ID (repeatable)");
  vehicle_of(a, db, missions);
  const auto data = identification_data(db, missions, resample_options(a));
  const auto rows =
      kin::sweep_history(data, identification_options(a), {2, 4, 6, 8, 10, 12, 14, 16, 18, 20});
  const bool csv = a.get("format").value_or("table") == "csv";
  io.out << (csv ? "history_s,history_samples,train_one_step_rms_deg,validation_mse_m2,"
                   "validation_heading_rms_deg,validation_turns\n"
                 : "history_s  samples  one-step RMS deg  validation MSE m^2  heading RMS deg  "
                   "turns\n");
  for (const auto& r : rows) {
    if (csv) {
      io.out << num(r.history_s) << ',' << r.history << ',' << num(r.train_one_step_rms_deg) << ','
             << num(r.validation.position_mse_m2) << ',' << num(r.validation.heading_rms_deg) << ','
             << r.validation.windows << '\n';
    } else {
      io.out << std::setw(9) << fixed(r.history_s, 1) << std::setw(9) << r.history << std::setw(18)
             << fixed(r.train_one_step_rms_deg, 3) << std::setw(20)
             << fixed(r.validation.position_mse_m2, 3) << std::setw(17)
             << fixed(r.validation.heading_rms_deg, 2) << std::setw(7) << r.validation.windows
             << "\n";
    }
  }
  return 0;
}

int model_list(const std::vector<std::string>& rest, Io& io) {
  const Args a(rest, {"db", "vehicle"});
  store::Store db(a.require("db"));
  json out = json::array();
  for (const auto& m : db.list_models(a.get("vehicle"))) {
    json j = model_json(m);
    j.erase("error_coeffs");
    j.erase("heading_coeffs");
    out.push_back(std::move(j));
  }
  io.out << out.dump(2) << "\n";
  return 0;
}

store::StoredModel pick_model(store::Store& db, const Args& a, const std::string& vehicle) {
  if (const auto id = a.number("model")) {
    if (*id < 1 || std::floor(*id) != *id) throw UsageError("--model needs a model id");
    const auto m = db.get_model(static_cast<std::int64_t>(*id));
    if (!m) throw std::runtime_error("no model " + num(*id));
    return *m;
  }
  const auto m = db.latest_model(vehicle);
  if (!m) throw std::runtime_error("no model of " + vehicle + " is stored: run avk model fit");
  return *m;
}

int model_show(const std::vector<std::string>& rest, Io& io) {
  const Args a(rest, {"db", "model"});
  store::Store db(a.require("db"));
  if (!a.get("model")) throw UsageError("give --model ID");
  io.out << model_json(pick_model(db, a, "")).dump(2) << "\n";
  return 0;
}

// Where each cell's turns started: the thesis form is not rotation invariant, so it is asked to
// predict from the course the vehicle actually held (the circular mean of the cell's turns).
double cell_course_deg(const kin::Ckt& table, double speed, double dheading) {
  double sx = 0.0, sy = 0.0;
  for (const auto& c : table.cells()) {
    if (std::abs(c.speed_mps - speed) > 1e-9 || std::abs(c.dheading_deg - dheading) > 1e-9)
      continue;
    for (const auto& t : c.turns) {
      sx += std::sin(kin::deg_to_rad(t.meta().initial_heading_deg));
      sy += std::cos(kin::deg_to_rad(t.meta().initial_heading_deg));
    }
  }
  return sx == 0.0 && sy == 0.0 ? 0.0 : kin::heading_of_deg(sx, sy);
}

int compare(const std::vector<std::string>& rest, Io& io) {
  const Args a(rest, {"db", "model", "vehicle", "format", "threshold"}, {"no-model"}, {"mission"});
  store::Store db(a.require("db"));
  const std::string format = a.get("format").value_or("table");
  if (format != "table" && format != "csv" && format != "json")
    throw UsageError("--format must be table, csv or json");
  const double threshold = a.number("threshold").value_or(5.0);
  const auto missions = mission_ids(a);
  const std::string vehicle = vehicle_of(a, db, missions);
  const auto turns = db.load_normalized_turns(missions, vehicle);
  if (turns.empty()) throw std::runtime_error("no ok turns of " + vehicle + " to compare");
  const kin::Ckt table = kin::Ckt::build(turns);
  std::optional<store::StoredModel> model;
  if (!a.flag("no-model")) model = pick_model(db, a, vehicle);
  kin::TurnPredictor predictor;
  if (model) {
    predictor = [&](double u, double d) {
      return kin::predict_normalized_turn(model->model, u, d, threshold,
                                          cell_course_deg(table, u, d));
    };
  }
  const auto cells = kin::compare_predictions(table, model ? &predictor : nullptr);
  const auto opt = [](const std::optional<double>& v) { return v ? json(*v) : json(); };
  const auto err_json = [&](const kin::MethodError& e) {
    return json{{"mse_m2", e.mse_m2},
                {"improvement_pct", opt(e.improvement_pct)},
                {"advance_error_m", e.advance_error_m},
                {"transfer_error_m", e.transfer_error_m}};
  };
  if (format == "json") {
    json out = {{"vehicle_id", vehicle}, {"model_id", model ? json(model->id) : json()}};
    json jc = json::array();
    for (const auto& c : cells) {
      json j = {{"speed_mps", c.speed_mps},
                {"dheading_deg", c.dheading_deg},
                {"n_turns", c.n_turns},
                {"avk", err_json(c.avk)},
                {"instantaneous", err_json(c.instantaneous)}};
      j["model"] = c.model ? err_json(*c.model) : json();
      j["outliers"] = std::count(c.outlier.begin(), c.outlier.end(), true);
      if (c.without_outliers) {
        j["without_outliers"] = {
            {"n_turns", c.without_outliers->n_turns},
            {"avk", err_json(c.without_outliers->avk)},
            {"instantaneous", err_json(c.without_outliers->instantaneous)},
            {"model", c.without_outliers->model ? err_json(*c.without_outliers->model) : json()}};
      }
      jc.push_back(std::move(j));
    }
    out["cells"] = std::move(jc);
    for (const auto& [name, method] : {std::pair{"avk", kin::PredictionMethod::avk},
                                       {"model", kin::PredictionMethod::model},
                                       {"instantaneous", kin::PredictionMethod::instantaneous}}) {
      out["median_mse_m2"][name] = opt(kin::median_mse_m2(cells, method));
      out["median_mse_without_outliers_m2"][name] = opt(kin::median_mse_m2(cells, method, true));
    }
    io.out << out.dump(2) << "\n";
    return 0;
  }
  const auto mse = [](const kin::MethodError* e) { return e ? num(e->mse_m2) : std::string(); };
  const auto pct = [](const kin::MethodError* e) {
    return e && e->improvement_pct ? num(*e->improvement_pct) : std::string();
  };
  if (format == "csv") {
    io.out << "speed_mps,dheading_deg,n_turns,outliers,avk_mse_m2,model_mse_m2,"
              "instantaneous_mse_m2,avk_improvement_pct,model_improvement_pct,"
              "avk_advance_error_m,model_advance_error_m,instantaneous_advance_error_m,"
              "avk_transfer_error_m,model_transfer_error_m,instantaneous_transfer_error_m\n";
    for (const auto& c : cells) {
      const kin::MethodError* m = c.model ? &*c.model : nullptr;
      io.out << num(c.speed_mps) << ',' << num(c.dheading_deg) << ',' << c.n_turns << ','
             << std::count(c.outlier.begin(), c.outlier.end(), true) << ',' << mse(&c.avk) << ','
             << mse(m) << ',' << mse(&c.instantaneous) << ',' << pct(&c.avk) << ',' << pct(m) << ','
             << num(c.avk.advance_error_m) << ',' << (m ? num(m->advance_error_m) : std::string())
             << ',' << num(c.instantaneous.advance_error_m) << ',' << num(c.avk.transfer_error_m)
             << ',' << (m ? num(m->transfer_error_m) : std::string()) << ','
             << num(c.instantaneous.transfer_error_m) << '\n';
    }
    return 0;
  }
  io.out << "vehicle " << vehicle;
  if (model)
    io.out << ", model " << model->id << " (" << kin::to_string(model->model.form)
           << (model->model.refined ? ", refined" : "") << ", " << model->model.history
           << " samples)";
  io.out << "\n"
         << "  speed  dheading   n  out       AVK m^2     model m^2   instant m^2   AVK %  "
            "model %\n";
  const auto cell_txt = [](const kin::MethodError* e, int w) {
    std::ostringstream s;
    s << std::setw(w) << (e ? fixed(e->mse_m2, 3) : std::string("-"));
    return s.str();
  };
  const auto pct_txt = [](const kin::MethodError* e) {
    std::ostringstream s;
    s << std::setw(8) << (e && e->improvement_pct ? fixed(*e->improvement_pct, 1) : "-");
    return s.str();
  };
  for (const auto& c : cells) {
    const kin::MethodError* m = c.model ? &*c.model : nullptr;
    io.out << std::setw(7) << fixed(c.speed_mps, 2) << std::setw(10) << fixed(c.dheading_deg, 0)
           << std::setw(4) << c.n_turns << std::setw(5)
           << std::count(c.outlier.begin(), c.outlier.end(), true) << cell_txt(&c.avk, 14)
           << cell_txt(m, 14) << cell_txt(&c.instantaneous, 14) << pct_txt(&c.avk) << pct_txt(m)
           << "\n";
  }
  for (const bool drop : {false, true}) {
    io.out
        << (drop ? "median without outliers:" : "median:") << " AVK "
        << num(kin::median_mse_m2(cells, kin::PredictionMethod::avk, drop).value_or(NAN))
        << " m^2, model "
        << num(kin::median_mse_m2(cells, kin::PredictionMethod::model, drop).value_or(NAN))
        << " m^2, instantaneous "
        << num(kin::median_mse_m2(cells, kin::PredictionMethod::instantaneous, drop).value_or(NAN))
        << " m^2\n";
  }
  return 0;
}

int predict(const std::vector<std::string>& rest, Io& io) {
  const Args a(rest,
               {"db", "speed", "dheading", "method", "model", "x", "y", "heading", "format",
                "vehicle", "threshold"},
               {"speed-model"});
  store::Store db(a.require("db"));
  const auto speed = a.number("speed");
  const auto dheading = a.number("dheading");
  if (!speed || !(*speed > 0.0)) throw UsageError("--speed (m/s, > 0) is required");
  if (!dheading || !(std::abs(*dheading) > 0.0 && std::abs(*dheading) <= 180.0))
    throw UsageError("--dheading (deg, in [-180, 0) or (0, 180]) is required");
  const std::string method = a.get("method").value_or("avk");
  const auto x = a.number("x"), y = a.number("y"), heading = a.number("heading");
  const bool placed = x || y || heading;
  if (placed && !(x && y && heading))
    throw UsageError("a pose needs all of --x, --y and --heading");
  const std::string format = a.get("format").value_or("json");
  if (format != "json" && format != "csv") throw UsageError("--format must be json or csv");
  const std::string vehicle = vehicle_of(a, db, {});
  kin::Polyline line;  // normalised, already reflected for a left turn
  json extra;
  if (method == "avk") {
    const auto snap = db.latest_ckt_snapshot();
    const kin::Ckt table =
        snap ? snap->table : kin::Ckt::build(db.load_normalized_turns({}, vehicle));
    const auto p = table.query(*speed, *dheading);
    line = p.trajectory;
    extra = {{"advance_m", p.advance_m},
             {"transfer_m", p.transfer_m},
             {"exact_cell", p.exact_cell},
             {"extrapolated", p.extrapolated}};
  } else if (method == "model") {
    const auto m = pick_model(db, a, vehicle);
    // Normalised turns are right turns; a left turn is its mirror image, as the CKT answers.
    if (a.flag("speed-model") && !m.model.speed)
      throw std::runtime_error("model " + std::to_string(m.id) + " has no speed model");
    line = kin::predict_normalized_turn(m.model, *speed, std::abs(*dheading),
                                        a.number("threshold").value_or(5.0), 0.0, 400,
                                        a.flag("speed-model"));
    if (*dheading < 0)
      for (auto& p : line)
        p.x_m = -p.x_m;
    extra = {{"model_id", m.id}, {"speed_model", a.flag("speed-model")}};
  } else if (method == "instantaneous") {
    // The current practice: the vehicle is on the new heading at once. Drawn for 20 s of travel.
    const kin::Point dir = kin::rotate_by_heading({0.0, 1.0}, *dheading);
    line = {{0.0, 0.0}, {dir.x_m * *speed * 20.0, dir.y_m * *speed * 20.0}};
  } else {
    throw UsageError("--method must be avk, model or instantaneous, got '" + method + "'");
  }
  if (placed) line = kin::place_normalized(line, {*x, *y, *heading}, kin::TurnSide::right);
  if (format == "csv") {
    io.out << "vertex_index,x_m,y_m\n";
    for (std::size_t i = 0; i < line.size(); ++i)
      io.out << i << ',' << num(line[i].x_m) << ',' << num(line[i].y_m) << '\n';
    return 0;
  }
  json j = {{"method", method},
            {"vehicle_id", vehicle},
            {"speed_mps", *speed},
            {"dheading_deg", *dheading},
            {"frame", placed ? "world" : "normalized"}};
  if (!extra.is_null()) j.update(extra);
  json pts = json::array();
  for (const auto& p : line)
    pts.push_back({p.x_m, p.y_m});
  j["trajectory"] = std::move(pts);
  io.out << j.dump() << "\n";
  return 0;
}

}  // namespace

int cmd_model(const std::vector<std::string>& args, Io& io) {
  if (args.empty()) throw UsageError("expected 'model fit|sweep|list|show'");
  const std::vector<std::string> rest(args.begin() + 1, args.end());
  if (args[0] == "fit") return model_fit(rest, io);
  if (args[0] == "sweep") return model_sweep(rest, io);
  if (args[0] == "list") return model_list(rest, io);
  if (args[0] == "show") return model_show(rest, io);
  throw UsageError("unknown subcommand 'model " + args[0] + "'");
}

int cmd_compare(const std::vector<std::string>& args, Io& io) {
  return compare(args, io);
}

int cmd_predict(const std::vector<std::string>& args, Io& io) {
  return predict(args, io);
}

}  // namespace avk::server
