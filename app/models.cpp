#include "app/models.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "app/context.hpp"
#include "app/store_access.hpp"
#include "kinematics/angles.hpp"
#include "mission/helm_mode.hpp"

namespace avk::app {

namespace kin = avk::kinematics;

namespace {

// Navigation of the vehicle under guidance: samples while the helm commanded motion (or imported
// logs, whose helm state is unknown). All-stop stretches are left out, so they split segments.
bool guided(const std::string& helm_mode) {
  if (helm_mode == mission::kImportedHelmMode) return true;
  const auto m = mission::helm_mode_from_string(helm_mode);
  return m && mission::commands_motion(*m);
}

// The training missions of a fit: at least one, each stored and of the vehicle, so that a model
// never mixes hulls.
std::optional<Error> check_missions(Context& ctx, const std::string& vehicle_id,
                                    const std::vector<std::int64_t>& missions) {
  if (missions.empty()) return invalid_argument("missions", "give at least one mission id");
  for (const auto id : missions) {
    if (id <= 0) return invalid_argument("missions", "holds a bad id: " + std::to_string(id));
    const auto m = store_of(ctx).missions().get(id);
    if (!m) return invalid_argument("missions", "no mission " + std::to_string(id));
    if (m->vehicle_id != vehicle_id)
      return invalid_argument("missions", "mission " + std::to_string(id) + " is of vehicle '" +
                                              m->vehicle_id + "', not '" + vehicle_id + "'");
  }
  return std::nullopt;
}

}  // namespace

Result<std::vector<kin::IdentSegment>> identification_data(
    Context& ctx, const std::vector<std::int64_t>& missions, const kin::ResampleOptions& options) {
  store::Store& db = store_of(ctx);
  std::vector<kin::IdentSegment> out;
  for (const std::int64_t id : missions) {
    if (!db.missions().get(id)) return not_found("no mission " + std::to_string(id));
    kin::NavStreams s;
    // Read row by row into streams reserved to the row count: a long mission's navigation is
    // held once, without the slack of vectors that grow as they are filled.
    const auto rows = static_cast<std::size_t>(db.navigation().count(id));
    for (auto* v : {&s.heading_deg, &s.desired_heading_deg, &s.x_m, &s.y_m, &s.speed_mps,
                    &s.desired_speed_mps})
      v->reserve(rows);
    db.navigation().for_each(id, [&](const store::NavRow& r) {
      if (!guided(r.helm_mode) || !r.desired_heading_deg) return;
      s.heading_deg.push_back({r.t_s, r.heading_deg});
      s.desired_heading_deg.push_back({r.t_s, *r.desired_heading_deg});
      s.x_m.push_back({r.t_s, r.x_m});
      s.y_m.push_back({r.t_s, r.y_m});
      s.speed_mps.push_back({r.t_s, r.speed_mps});
      if (r.desired_speed_mps) s.desired_speed_mps.push_back({r.t_s, *r.desired_speed_mps});
    });
    if (s.desired_speed_mps.size() != s.heading_deg.size()) s.desired_speed_mps.clear();
    for (auto& seg : kin::resample(s, options))
      out.push_back(std::move(seg));
  }
  if (out.empty()) return unsupported("the missions hold no guided navigation to identify from");
  return out;
}

Result<ModelHeadings> model_headings(Context& ctx, std::int64_t model_id, std::int64_t mission,
                                     std::size_t max_samples, double restart_step_deg) {
  const auto stored = get_model(ctx, model_id);
  if (!stored) return stored.error();
  const kin::YawModel& model = stored->model;
  if (!store_of(ctx).missions().get(mission))
    return not_found("no mission " + std::to_string(mission));
  kin::ResampleOptions resample;
  resample.rate_hz = model.rate_hz;  // the model steps at its own rate only
  auto data = identification_data(ctx, {mission}, resample);
  if (!data) return data.error();
  ModelHeadings out;
  out.model_id = model_id;
  out.mission_id = mission;
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
  for (const auto& full : *data) {
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

Result<FittedModel> fit_model(Context& ctx, const std::string& vehicle_id,
                              const std::vector<std::int64_t>& missions,
                              const kin::IdentificationOptions& options,
                              const kin::ResampleOptions& resample) {
  if (auto e = check_missions(ctx, vehicle_id, missions)) return *e;
  auto data = identification_data(ctx, missions, resample);
  if (!data) return data.error();
  FittedModel f;
  try {
    f.result = kin::identify_yaw_model(std::move(*data), options);
  } catch (const std::invalid_argument& e) {
    return unsupported(e.what());
  }
  ModelView& m = f.stored;
  m.vehicle_id = vehicle_id;
  m.training_missions = missions;
  m.model = f.result.model;
  m.train_one_step_rms_deg = f.result.train_one_step_rms_deg;
  if (f.result.validation.windows) {
    m.validation_mse_m2 = f.result.validation.position_mse_m2;
    m.validation_heading_rms_deg = f.result.validation.heading_rms_deg;
  }
  m.id = store_of(ctx).models().save(to_store(m));
  return f;
}

Result<std::vector<kin::HistorySweepRow>> sweep_model_history(
    Context& ctx, const std::string& vehicle_id, const std::vector<std::int64_t>& missions,
    const kin::IdentificationOptions& options, const kin::ResampleOptions& resample) {
  if (auto e = check_missions(ctx, vehicle_id, missions)) return *e;
  auto data = identification_data(ctx, missions, resample);
  if (!data) return data.error();
  try {
    return kin::sweep_history(std::move(*data), options, {2, 4, 6, 8, 10, 12, 14, 16, 18, 20});
  } catch (const std::invalid_argument& e) {
    return unsupported(e.what());
  }
}

std::vector<ModelView> list_models(Context& ctx, const std::optional<std::string>& vehicle_id) {
  return views_of(store_of(ctx).models().list(vehicle_id));
}

Result<ModelView> get_model(Context& ctx, std::int64_t model_id) {
  auto m = store_of(ctx).models().get(model_id);
  if (!m) return not_found("no model " + std::to_string(model_id));
  return view_of(*m);
}

Result<ModelView> model_or_latest(Context& ctx, std::optional<std::int64_t> model_id,
                                  const std::string& vehicle_id) {
  if (model_id) return get_model(ctx, *model_id);
  auto m = store_of(ctx).models().latest(vehicle_id);
  if (!m) return not_found("no model of '" + vehicle_id + "' is stored (fit one first)");
  return view_of(*m);
}

}  // namespace avk::app
