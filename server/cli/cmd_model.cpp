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
#include "server/analysis.hpp"
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

int model_fit(const std::vector<std::string>& rest, Io& io) {
  const Args a(rest, {"db", "form", "history", "ridge", "rate", "vehicle"}, {"refine"},
               {"mission"});
  store::Store db(a.require("db"));
  const auto missions = mission_ids(a);
  if (missions.empty()) throw UsageError("give the training data: --mission ID (repeatable)");
  const std::string vehicle = vehicle_of(a, db, missions);
  const FittedModel fitted =
      fit_and_store_model(db, vehicle, missions, identification_options(a), resample_options(a));
  const auto& r = fitted.result;
  const auto& m = fitted.stored;
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

int compare(const std::vector<std::string>& rest, Io& io) {
  const Args a(rest, {"db", "model", "vehicle", "format", "threshold"}, {"no-model"}, {"mission"});
  store::Store db(a.require("db"));
  const std::string format = a.get("format").value_or("table");
  if (format != "table" && format != "csv" && format != "json")
    throw UsageError("--format must be table, csv or json");
  const double threshold = a.number("threshold").value_or(5.0);
  const auto missions = mission_ids(a);
  const std::string vehicle = vehicle_of(a, db, missions);
  std::optional<store::StoredModel> chosen;
  if (!a.flag("no-model")) chosen = pick_model(db, a, vehicle);
  const Comparison comparison = compare_from_store(db, vehicle, missions, chosen, threshold);
  const auto& cells = comparison.cells;
  const auto& model = comparison.model;
  if (format == "json") {
    io.out << comparison_json(comparison).dump(2) << "\n";
    return 0;
  }
  if (format == "csv") {
    io.out << comparison_csv(comparison);
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
    if (a.flag("speed-model") && !m.model.speed)
      throw std::runtime_error("model " + std::to_string(m.id) + " has no speed model");
    line = model_turn(m.model, *speed, *dheading, a.number("threshold").value_or(5.0),
                      a.flag("speed-model"));
    extra = {{"model_id", m.id}, {"speed_model", a.flag("speed-model")}};
  } else if (method == "instantaneous") {
    line = instantaneous_turn_ray(*speed, *dheading);
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
