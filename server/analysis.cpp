#include "server/analysis.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "kinematics/angles.hpp"
#include "kinematics/yaw_model_json.hpp"
#include "mission/helm_mode.hpp"
#include "server/number_text.hpp"

namespace avk::server {

namespace kin = avk::kinematics;
using nlohmann::json;

namespace {

// Navigation of the vehicle under guidance: samples while the helm commanded motion (or imported
// logs, whose helm state is unknown). All-stop stretches are left out, so they split segments.
bool guided(const std::string& helm_mode) {
  if (helm_mode == "IMPORTED") return true;
  const auto m = mission::helm_mode_from_string(helm_mode);
  return m && mission::commands_motion(*m);
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

}  // namespace

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

ModelHeadings model_headings(store::Store& db, const kin::YawModel& model, std::int64_t mission,
                             std::size_t max_samples, double restart_step_deg) {
  kin::ResampleOptions resample;
  resample.rate_hz = model.rate_hz;  // the model steps at its own rate only
  const auto data = identification_data(db, {mission}, resample);
  ModelHeadings out;
  out.dt_s = model.dt_s();
  out.warmup = model.warmup();
  out.restart_step_deg = restart_step_deg;
  const std::size_t w = model.warmup();
  kin::PredictOptions one;
  one.steps = 1;
  // predict() with one step from a history ending at k, the desired heading of sample k held:
  // exactly the model's next-sample equation on that history.
  const auto next = [&](const kin::YawHistory& h, double desired) {
    return predict(model, h, desired, kin::Pose{}, 0.0, one)[1].heading_deg;
  };
  const auto finite = [](double v) { return std::isfinite(v) ? std::optional(v) : std::nullopt; };
  std::size_t left = max_samples;
  for (const auto& full : data) {
    if (left == 0) break;
    kin::IdentSegment s = full;
    const std::size_t n = std::min(s.size(), left);
    s.heading_deg.resize(n);
    s.desired_heading_deg.resize(n);
    left -= n;
    HeadingSegment seg;
    seg.t0_s = s.t0_s;
    seg.heading_deg = s.heading_deg;
    // Shown within 180 deg of the measured heading at the same sample: the resampled desired
    // heading is unwrapped on its own and may drift whole turns away after long turns one way,
    // which the model never sees (it uses the wrapped error) but a plot would.
    seg.desired_heading_deg.resize(n);
    for (std::size_t k = 0; k < n; ++k)
      seg.desired_heading_deg[k] =
          s.heading_deg[k] + kin::angle180_deg(s.desired_heading_deg[k] - s.heading_deg[k]);
    seg.one_step_deg.assign(n, std::nullopt);
    seg.simulated_deg.assign(n, std::nullopt);
    if (n > w) {
      std::vector<double> sim = s.heading_deg;  // the free run's own history
      kin::YawHistory h;
      for (std::size_t k = w - 1; k + 1 < n; ++k) {
        seg.one_step_deg[k + 1] =
            finite(next(kin::history_at(model, s, k), s.desired_heading_deg[k]));
        const bool step = k >= 1 && std::abs(s.desired_heading_deg[k] -
                                             s.desired_heading_deg[k - 1]) >= restart_step_deg;
        if (step || !std::isfinite(sim[k]))
          std::copy_n(s.heading_deg.begin() + (k + 1 - w), w, sim.begin() + (k + 1 - w));
        h.heading_deg.assign(sim.begin() + (k + 1 - w), sim.begin() + k + 1);
        h.desired_heading_deg.assign(s.desired_heading_deg.begin() + (k + 1 - w),
                                     s.desired_heading_deg.begin() + k + 1);
        sim[k + 1] = next(h, s.desired_heading_deg[k]);
        seg.simulated_deg[k + 1] = finite(sim[k + 1]);
      }
    }
    out.segments.push_back(std::move(seg));
  }
  return out;
}

json model_headings_json(const ModelHeadings& h) {
  const auto optional_array = [](const std::vector<std::optional<double>>& v) {
    json a = json::array();
    for (const auto& x : v)
      a.push_back(x ? json(*x) : json());
    return a;
  };
  json segments = json::array();
  for (const auto& s : h.segments)
    segments.push_back({{"t0_s", s.t0_s},
                        {"heading_deg", s.heading_deg},
                        {"desired_heading_deg", s.desired_heading_deg},
                        {"one_step_deg", optional_array(s.one_step_deg)},
                        {"simulated_deg", optional_array(s.simulated_deg)}});
  return {{"dt_s", h.dt_s},
          {"warmup_samples", h.warmup},
          {"restart_step_deg", h.restart_step_deg},
          {"segments", segments}};
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

FittedModel fit_and_store_model(store::Store& db, const std::string& vehicle_id,
                                const std::vector<std::int64_t>& missions,
                                const kin::IdentificationOptions& options,
                                const kin::ResampleOptions& resample) {
  FittedModel f;
  f.result = kin::identify_yaw_model(identification_data(db, missions, resample), options);
  store::StoredModel& m = f.stored;
  m.vehicle_id = vehicle_id;
  m.training_missions = missions;
  m.model = f.result.model;
  m.train_one_step_rms_deg = f.result.train_one_step_rms_deg;
  if (f.result.validation.windows) {
    m.validation_mse_m2 = f.result.validation.position_mse_m2;
    m.validation_heading_rms_deg = f.result.validation.heading_rms_deg;
  }
  m.id = db.save_model(m);
  return f;
}

kin::Polyline model_turn(const kin::YawModel& m, double speed_mps, double dheading_deg,
                         double completion_threshold_deg, bool use_speed_model) {
  kin::Polyline line = kin::predict_normalized_turn(
      m, speed_mps, std::abs(dheading_deg), completion_threshold_deg, 0.0, 400, use_speed_model);
  if (dheading_deg < 0)
    for (auto& p : line)
      p.x_m = -p.x_m;
  return line;
}

kin::Polyline instantaneous_turn_ray(double speed_mps, double dheading_deg) {
  const kin::Point d = kin::rotate_by_heading({0.0, 1.0}, dheading_deg);
  return {{0.0, 0.0}, {d.x_m * speed_mps * 20.0, d.y_m * speed_mps * 20.0}};
}

Comparison compare_from_store(store::Store& db, const std::string& vehicle_id,
                              const std::vector<std::int64_t>& missions,
                              std::optional<store::StoredModel> model,
                              double completion_threshold_deg) {
  Comparison c;
  c.vehicle_id = vehicle_id;
  c.model = std::move(model);
  const auto turns = db.load_normalized_turns(missions, vehicle_id);
  if (turns.empty()) throw std::runtime_error("no ok turns of " + vehicle_id + " to compare");
  c.table = kin::Ckt::build(turns);
  kin::TurnPredictor predictor;
  if (c.model) {
    predictor = [&](double u, double d) {
      return kin::predict_normalized_turn(c.model->model, u, d, completion_threshold_deg,
                                          cell_course_deg(c.table, u, d));
    };
  }
  c.cells = kin::compare_predictions(c.table, c.model ? &predictor : nullptr);
  return c;
}

namespace {
json opt(const std::optional<double>& v) {
  return v ? json(*v) : json();
}
json err_json(const kin::MethodError& e) {
  return json{{"mse_m2", e.mse_m2},
              {"improvement_pct", opt(e.improvement_pct)},
              {"advance_error_m", e.advance_error_m},
              {"transfer_error_m", e.transfer_error_m}};
}
}  // namespace

json comparison_json(const Comparison& c) {
  json out = {{"vehicle_id", c.vehicle_id}, {"model_id", c.model ? json(c.model->id) : json()}};
  json jc = json::array();
  for (const auto& cell : c.cells) {
    json j = {{"speed_mps", cell.speed_mps},
              {"dheading_deg", cell.dheading_deg},
              {"n_turns", cell.n_turns},
              {"avk", err_json(cell.avk)},
              {"instantaneous", err_json(cell.instantaneous)}};
    j["model"] = cell.model ? err_json(*cell.model) : json();
    j["outliers"] = std::count(cell.outlier.begin(), cell.outlier.end(), true);
    if (cell.without_outliers) {
      const auto& w = *cell.without_outliers;
      j["without_outliers"] = {{"n_turns", w.n_turns},
                               {"avk", err_json(w.avk)},
                               {"instantaneous", err_json(w.instantaneous)},
                               {"model", w.model ? err_json(*w.model) : json()}};
    }
    jc.push_back(std::move(j));
  }
  out["cells"] = std::move(jc);
  for (const auto& [name, method] : {std::pair{"avk", kin::PredictionMethod::avk},
                                     {"model", kin::PredictionMethod::model},
                                     {"instantaneous", kin::PredictionMethod::instantaneous}}) {
    out["median_mse_m2"][name] = opt(kin::median_mse_m2(c.cells, method));
    out["median_mse_without_outliers_m2"][name] = opt(kin::median_mse_m2(c.cells, method, true));
  }
  return out;
}

std::string comparison_csv(const Comparison& c) {
  const auto mse = [](const kin::MethodError* e) { return e ? num(e->mse_m2) : std::string(); };
  const auto pct = [](const kin::MethodError* e) {
    return e && e->improvement_pct ? num(*e->improvement_pct) : std::string();
  };
  std::string out =
      "speed_mps,dheading_deg,n_turns,outliers,avk_mse_m2,model_mse_m2,"
      "instantaneous_mse_m2,avk_improvement_pct,model_improvement_pct,"
      "avk_advance_error_m,model_advance_error_m,instantaneous_advance_error_m,"
      "avk_transfer_error_m,model_transfer_error_m,instantaneous_transfer_error_m\n";
  for (const auto& cell : c.cells) {
    const kin::MethodError* m = cell.model ? &*cell.model : nullptr;
    out += num(cell.speed_mps) + ',' + num(cell.dheading_deg) + ',' + std::to_string(cell.n_turns) +
           ',' + std::to_string(std::count(cell.outlier.begin(), cell.outlier.end(), true)) + ',' +
           mse(&cell.avk) + ',' + mse(m) + ',' + mse(&cell.instantaneous) + ',' + pct(&cell.avk) +
           ',' + pct(m) + ',' + num(cell.avk.advance_error_m) + ',' +
           (m ? num(m->advance_error_m) : std::string()) + ',' +
           num(cell.instantaneous.advance_error_m) + ',' + num(cell.avk.transfer_error_m) + ',' +
           (m ? num(m->transfer_error_m) : std::string()) + ',' +
           num(cell.instantaneous.transfer_error_m) + '\n';
  }
  return out;
}

}  // namespace avk::server
