// avk model fit|sweep|list, avk predict, avk compare: the black-box yaw model and the comparison
// of prediction methods (thesis §3.4, §5.2), over the navigation logs and turns in the store.
#include <cmath>
#include <iomanip>
#include <ostream>
#include <set>
#include <sstream>

#include "app/compare.hpp"
#include "app/context.hpp"
#include "app/models.hpp"
#include "app/predict.hpp"
#include "kinematics/prediction_comparison.hpp"
#include "kinematics/yaw_identification.hpp"
#include "server/cli/app_error.hpp"
#include "server/cli/args.hpp"
#include "server/cli/commands.hpp"
#include "server/cli/db_selection.hpp"
#include "server/serialize.hpp"

namespace avk::server {

namespace {

namespace kin = avk::kinematics;

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
  app::Context ctx(a.require("db"));
  const auto missions = mission_ids(a);
  if (missions.empty()) throw UsageError("give the training data: --mission ID (repeatable)");
  const std::string vehicle = vehicle_of(a, ctx, missions);
  const app::FittedModel fitted = value_or_fail(
      app::fit_model(ctx, vehicle, missions, identification_options(a), resample_options(a)));
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
  app::Context ctx(a.require("db"));
  const auto missions = mission_ids(a);
  if (missions.empty()) throw UsageError("give the data: --mission ID (repeatable)");
  const std::string vehicle = vehicle_of(a, ctx, missions);
  const std::string format = a.get("format").value_or("table");
  if (format != "table" && format != "csv" && format != "json")
    throw UsageError("--format must be table, csv or json");
  const auto rows = value_or_fail(app::sweep_model_history(
      ctx, vehicle, missions, identification_options(a), resample_options(a)));
  if (format == "csv") {
    io.out << sweep_csv(rows);
    return 0;
  }
  if (format == "json") {
    io.out << sweep_json(rows).dump(2) << "\n";
    return 0;
  }
  io.out << "history_s  samples  one-step RMS deg  validation MSE m^2  heading RMS deg  turns\n";
  for (const auto& r : rows)
    io.out << std::setw(9) << fixed(r.history_s, 1) << std::setw(9) << r.history << std::setw(18)
           << fixed(r.train_one_step_rms_deg, 3) << std::setw(20)
           << fixed(r.validation.position_mse_m2, 3) << std::setw(17)
           << fixed(r.validation.heading_rms_deg, 2) << std::setw(7) << r.validation.windows
           << "\n";
  return 0;
}

int model_list(const std::vector<std::string>& rest, Io& io) {
  const Args a(rest, {"db", "vehicle"});
  app::Context ctx(a.require("db"));
  io.out << models_json(app::list_models(ctx, a.get("vehicle"))).dump(2) << "\n";
  return 0;
}

int model_show(const std::vector<std::string>& rest, Io& io) {
  const Args a(rest, {"db", "model"});
  app::Context ctx(a.require("db"));
  const auto id = model_option(a);
  if (!id) throw UsageError("give --model ID");
  io.out << model_json(value_or_fail(app::get_model(ctx, *id))).dump(2) << "\n";
  return 0;
}

// One method's mean ± sd over a cell's held-out turns, in a 17-wide column; "-" without it.
std::string held_out_text(const kin::HeldOutScores* s, bool path) {
  std::ostringstream o;
  if (!s) {
    o << std::setw(17) << "-";
    return o.str();
  }
  const kin::MeanSd m = path ? s->path() : s->yx_mse();
  o << std::setw(17) << (fixed(m.mean, path ? 2 : 3) + " ± " + fixed(m.sd, path ? 2 : 3));
  return o.str();
}

// The leave-one-out table: each method's mean ± sd over the held-out turns of every cell.
void print_predictive(const app::Comparison& c, bool path, Io& io) {
  io.out << "vehicle " << c.vehicle_id;
  if (c.model)
    io.out << ", model " << c.model->id << " (" << kin::to_string(c.model->model.form)
           << (c.model->model.refined ? ", refined" : "") << ")";
  io.out << "\nscored on held-out turns (AVK: leave-one-out), "
         << (path ? "mean distance at equal arc length, m" : "thesis y(x) MSE, m^2") << "\n"
         << "  speed  dheading   n              AVK            model    instantaneous   "
            "corridor\n";
  const auto cell_txt = [path](const kin::HeldOutScores* s) { return held_out_text(s, path); };
  for (const auto& cell : c.predictive) {
    std::string cov = "-";
    if (cell.coverage && cell.coverage->total)
      cov = fixed(100.0 * cell.coverage->share(), 0) + " %";
    io.out << std::setw(7) << fixed(cell.speed_mps, 2) << std::setw(10)
           << fixed(cell.dheading_deg, 0) << std::setw(4) << cell.n_turns << cell_txt(&cell.avk)
           << cell_txt(cell.model ? &*cell.model : nullptr) << cell_txt(&cell.instantaneous)
           << std::setw(11) << cov << "\n";
  }
  const auto metric = path ? kin::PathMetric::path_distance : kin::PathMetric::yx_mse;
  io.out
      << "median: AVK "
      << num(kin::median_held_out(c.predictive, kin::PredictionMethod::avk, metric).value_or(NAN))
      << ", model "
      << num(kin::median_held_out(c.predictive, kin::PredictionMethod::model, metric).value_or(NAN))
      << ", instantaneous "
      << num(kin::median_held_out(c.predictive, kin::PredictionMethod::instantaneous, metric)
                 .value_or(NAN))
      << (path ? " m" : " m^2") << "\n";
  const kin::Coverage cov = kin::total_coverage(c.predictive, app::kCoverageMinTurns);
  if (cov.total)
    io.out << "corridor " << fixed(100.0 * c.corridor_share, 0)
           << " %: " << fixed(100.0 * cov.share(), 1)
           << " % of held-out points inside (cells with >= " << app::kCoverageMinTurns
           << " turns)\n";
}

// The table judged on turns from missions it was not built from, on and off its grid.
void print_test_cells(const app::Comparison& c, bool path, Io& io) {
  io.out << "\nthe table on the test missions' turns (" << (path ? "m" : "m^2") << ")\n"
         << "  speed  dheading   n  grid              AVK            model    instantaneous\n";
  for (const auto& cell : c.test_cells) {
    const auto txt = [path](const kin::HeldOutScores* s) { return held_out_text(s, path); };
    io.out << std::setw(7) << fixed(cell.speed_mps, 2) << std::setw(10)
           << fixed(cell.dheading_deg, 0) << std::setw(4) << cell.n_turns << std::setw(6)
           << (cell.on_grid ? "on" : "off") << txt(&cell.avk)
           << txt(cell.model ? &*cell.model : nullptr) << txt(&cell.instantaneous) << "\n";
  }
}

// Turns with a speed change, each predictor on turns it was not built from.
void print_speed_change(const app::Comparison& c, Io& io) {
  using M = kin::SpeedChangeMethod;
  io.out << "\nturns with a speed change, held out, mean distance at equal arc length, m\n"
         << "   u0 -> u1  dheading   n         measured retimed(measured)    retimed(model)"
            "            model   constant speed    instantaneous\n";
  for (const auto& cell : c.speed_change) {
    io.out << std::setw(5) << fixed(cell.from_mps, 2) << " -> " << fixed(cell.to_mps, 2)
           << std::setw(8) << fixed(cell.dheading_deg, 0) << std::setw(4) << cell.n_turns;
    for (const M m : kin::kSpeedChangeMethods)
      io.out << held_out_text(kin::scores_of(cell, m), true);
    io.out << "\n";
  }
  io.out << "median:";
  for (const M m : kin::kSpeedChangeMethods)
    io.out << " " << kin::to_string(m) << " "
           << fixed(kin::median_speed_change_path_m(c.speed_change, m).value_or(NAN), 2);
  io.out << " m\n";
}

int compare(const std::vector<std::string>& rest, Io& io) {
  const Args a(rest,
               {"db", "model", "vehicle", "format", "threshold", "metric", "scoring", "corridor"},
               {"no-model"}, {"mission", "test-mission"});
  app::Context ctx(a.require("db"));
  const std::string format = a.get("format").value_or("table");
  if (format != "table" && format != "csv" && format != "json")
    throw UsageError("--format must be table, csv or json");
  app::CompareQuery q;
  q.completion_threshold_deg = a.number("threshold").value_or(5.0);
  q.missions = mission_ids(a);
  q.vehicle_id = vehicle_of(a, ctx, q.missions);
  q.model_id = model_option(a);
  q.without_model = a.flag("no-model");
  for (const auto& v : a.all("test-mission"))
    q.test_missions.push_back(parse_id(v, "--test-mission"));
  const std::string scoring = a.get("scoring").value_or("predictive");
  if (scoring != "predictive" && scoring != "in_sample")
    throw UsageError("--scoring must be predictive or in_sample");
  const std::string metric = a.get("metric").value_or("path");
  if (metric != "path" && metric != "thesis_mse")
    throw UsageError("--metric must be path or thesis_mse");
  if (const auto share = a.number("corridor")) {
    if (!(*share > 0.0 && *share < 1.0)) throw UsageError("--corridor must be within (0, 1)");
    q.corridor_share = *share;
  }
  const std::string& vehicle = q.vehicle_id;
  const app::Comparison comparison = value_or_fail(app::compare(ctx, q));
  const auto& cells = comparison.cells;
  const auto& model = comparison.model;
  if (format == "json") {
    io.out << comparison_json(comparison).dump(2) << "\n";
    return 0;
  }
  if (format == "csv") {
    io.out << (scoring == "in_sample" ? comparison_csv(comparison) : predictive_csv(comparison));
    return 0;
  }
  if (scoring == "predictive") {
    print_predictive(comparison, metric == "path", io);
    if (!comparison.test_cells.empty()) print_test_cells(comparison, metric == "path", io);
    if (!comparison.speed_change.empty()) print_speed_change(comparison, io);
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
                "vehicle", "threshold", "corridor", "current", "initial-yaw-rate", "speed-after",
                "without-mission", "speed-reference"},
               {"speed-model"});
  app::Context ctx(a.require("db"));
  app::PredictQuery q;
  const auto speed = a.number("speed");
  const auto dheading = a.number("dheading");
  if (!speed || !(*speed > 0.0)) throw UsageError("--speed (m/s, > 0) is required");
  if (!dheading || !(std::abs(*dheading) > 0.0 && std::abs(*dheading) <= 180.0))
    throw UsageError("--dheading (deg, in [-180, 0) or (0, 180]) is required");
  q.speed_mps = *speed;
  q.dheading_deg = *dheading;
  q.method = method_option(a);
  const auto x = a.number("x"), y = a.number("y"), heading = a.number("heading");
  if ((x || y || heading) && !(x && y && heading))
    throw UsageError("a pose needs all of --x, --y and --heading");
  if (x) q.pose = kin::Pose{*x, *y, *heading};
  const std::string format = a.get("format").value_or("json");
  if (format != "json" && format != "csv") throw UsageError("--format must be json or csv");
  q.model_id = model_option(a);
  q.use_speed_model = a.flag("speed-model");
  if (const auto after = a.number("speed-after")) {
    if (!(*after > 0.0)) throw UsageError("--speed-after (m/s) must be > 0");
    q.speed_after_mps = *after;
  }
  q.completion_threshold_deg = a.number("threshold").value_or(5.0);
  if (const auto share = a.number("corridor")) {
    if (!(*share > 0.0 && *share < 1.0)) throw UsageError("--corridor must be within (0, 1)");
    q.corridor_share = *share;
  }
  const CurrentOption current = current_option(a);
  q.current = current.current;
  q.live_current = current.live;
  q.no_current = current.none;
  q.speed_over_ground = speed_reference_option(a);
  q.initial_yaw_rate_dps = a.number("initial-yaw-rate");
  if (const auto held_out = a.get("without-mission"))
    q.without_mission_id = parse_id(*held_out, "--without-mission");
  q.vehicle_id = vehicle_of(a, ctx, {});
  const app::Prediction p = value_or_fail(app::predict(ctx, q));
  io.out << (format == "csv" ? trajectory_csv(p.trajectory) : prediction_json(p).dump() + "\n");
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
