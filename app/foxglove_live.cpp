#include "app/foxglove_live.hpp"

#include <exception>
#include <utility>

namespace avk::app::foxglove {

namespace {

NavigationState navigation_state(const VehicleSnapshot& s) {
  const auto& n = *s.nav;
  NavigationState out;
  out.t_s = n.t_s;
  out.x_m = n.x_m;
  out.y_m = n.y_m;
  out.heading_deg = n.heading_deg;
  out.speed_mps = n.speed_mps;
  out.yaw_rate_dps = n.yaw_rate_dps;
  out.desired_heading_deg = s.desired_heading_deg;
  out.desired_speed_mps = s.desired_speed_mps;
  if (s.helm_mode) out.helm_mode = mission::to_string(*s.helm_mode);
  out.mission_id = s.mission_id;
  if (n.lat_deg && n.lon_deg) out.position = vehicle::LatLon{*n.lat_deg, *n.lon_deg};
  return out;
}

LogLevel level_of(mission::EventKind kind) {
  return mission::severity(kind) == mission::Severity::warning ? LogLevel::warning : LogLevel::info;
}

std::string turn_state(kinematics::TurnStatus s) {
  return s == kinematics::TurnStatus::ok ? "finished" : kinematics::to_string(s);
}

}  // namespace

// Follows one mission: its region when it starts, its turns, its events and state changes.
class FoxgloveLive::MissionChannels final : public mission::MissionObserver {
 public:
  MissionChannels(FoxgloveLive& live, std::int64_t mission_id)
      : live_(live), mission_id_(mission_id) {}

  void on_turn_started(const mission::TurnTask&, const mission::RunningTurn& turn) override {
    live_.turn_started(turn);
  }
  void on_turn(mission::TurnOutcome& t) override { live_.turn_ended(t); }
  void on_event(const mission::MissionEventRecord& e) override {
    live_.log(e.t_s, e.kind, "mission " + std::to_string(mission_id_) + ": " + e.message);
  }
  void on_state(mission::MissionState s, const std::string& reason, double t_s) override {
    std::string text = "mission " + std::to_string(mission_id_) + " " + mission::to_string(s);
    if (!reason.empty()) text += ": " + reason;
    live_.log(t_s, mission::state_change_kind(s), text);
  }

 private:
  FoxgloveLive& live_;
  std::int64_t mission_id_;
};

FoxgloveLive::FoxgloveLive(FoxgloveSink& sink, TurnPredictor predictor,
                           std::optional<vehicle::LatLon> datum)
    : sink_(sink), predictor_(std::move(predictor)) {
  if (datum) grid_.emplace(datum->lat_deg, datum->lon_deg);
}

FoxgloveLive::~FoxgloveLive() {
  if (predicting_.valid()) predicting_.wait();
}

void FoxgloveLive::telemetry(const VehicleSnapshot& s) {
  std::lock_guard lock(mutex_);
  const std::string& vid = s.info.id;
  // A vehicle that lost its link is gone for a viewer until it reports again; the channels come
  // back with the same ids.
  const bool present = s.link != vehicle::LinkState::disconnected;
  if (advertised_ && (!present || *advertised_ != vid)) {
    sink_.unadvertise(*advertised_);
    advertised_.reset();
  }
  if (!present || vid.empty()) return;
  if (!advertised_) {
    sink_.advertise(vid, live_channels(vid));
    advertised_ = vid;
  }
  sink_.time(to_ns(s.t_s));
  if (!s.nav) return;
  last_nav_ = *s.nav;
  auto state = navigation_state(s);
  if (!state.position && grid_) {
    try {
      state.position = grid_->to_geodetic(state.x_m, state.y_m);
    } catch (const std::exception&) {
      // Off the earth as seen from the datum: no fix rather than a wrong one.
    }
  }
  const std::uint64_t t_ns = to_ns(state.t_s);
  const auto send = [&](ChannelKind k, auto&& build) {
    const std::string t = topic(vid, k);
    if (sink_.wanted(t)) sink_.publish(t, t_ns, build());
  };
  send(ChannelKind::pose, [&] { return pose_message(state); });
  send(ChannelKind::transform, [&] { return transform_message(state, vid); });
  send(ChannelKind::navigation, [&] { return navigation_message(state); });
  if (state.position) send(ChannelKind::location, [&] { return location_message(state, vid); });
  if (turn_ && turn_running_) {
    turn_->measured.push_back({state.x_m, state.y_m});
    if (state.t_s - turn_drawn_t_s_ >= turn_redraw_interval_s) {
      turn_->t_s = state.t_s;
      publish_turn_scene();
    }
  }
}

void FoxgloveLive::station_event(double t_s, mission::EventKind kind, const std::string& message) {
  std::lock_guard lock(mutex_);
  log(t_s, kind, message);
}

std::unique_ptr<mission::MissionObserver> FoxgloveLive::follow(
    std::int64_t mission_id, const mission::MissionRunner& runner) {
  std::lock_guard lock(mutex_);
  if (advertised_) {
    const std::string t = topic(*advertised_, ChannelKind::region);
    const double t_s = last_nav_ ? last_nav_->t_s : 0.0;
    // Latched: sent even with no client now, so a viewer that connects later sees the region.
    sink_.publish(t, to_ns(t_s), region_scene_message(t_s, runner.container().region()));
  }
  return std::make_unique<MissionChannels>(*this, mission_id);
}

void FoxgloveLive::withdraw() {
  if (predicting_.valid()) predicting_.wait();
  std::lock_guard lock(mutex_);
  if (advertised_) sink_.unadvertise(*advertised_);
  advertised_.reset();
}

void FoxgloveLive::turn_started(const mission::RunningTurn& turn) {
  // The last turn's predictions, long finished in practice; waited for outside the lock they take.
  if (predicting_.valid()) predicting_.wait();
  std::lock_guard lock(mutex_);
  if (!advertised_) return;
  TurnScene scene;
  scene.t_s = turn.start.t_s;
  scene.start = {turn.start.x_m, turn.start.y_m, turn.start.heading_deg};
  scene.speed_mps = turn.speed_mps;
  scene.dheading_deg = turn.dheading_deg;
  scene.goal_heading_deg = turn.goal_heading_deg;
  scene.state = "running";
  scene.measured.push_back({scene.start.x_m, scene.start.y_m});
  const bool predict = predictor_ && sink_.wanted(topic(*advertised_, ChannelKind::turn));
  const std::uint64_t number = ++turn_number_;
  // Predicting takes the vehicle's table (rebuilt after each new turn): only when someone looks,
  // and on a thread of its own; the scene is drawn now and again when the predictions arrive.
  if (predict) {
    predicting_ =
        std::async(std::launch::async, [this, number, vid = *advertised_, speed = scene.speed_mps,
                                        dheading = scene.dheading_deg, start = scene.start] {
          auto p = predictor_(vid, speed, dheading, start);
          std::lock_guard lock(mutex_);
          if (!turn_ || turn_number_ != number || !advertised_) return;  // a newer turn is shown
          turn_->predictions = std::move(p.predictions);
          turn_->cell_label = std::move(p.cell_label);
          publish_turn_scene();
        });
  }
  turn_ = std::move(scene);
  turn_running_ = true;
  publish_turn_scene();
}

void FoxgloveLive::turn_ended(const mission::TurnOutcome& t) {
  std::lock_guard lock(mutex_);
  if (!turn_ || !advertised_) return;
  turn_running_ = false;
  turn_->state = turn_state(t.status);
  if (!t.raw.samples().empty()) {
    turn_->measured.clear();
    for (const auto& s : t.raw.samples())
      turn_->measured.push_back({s.x_m, s.y_m});
    turn_->t_s = t.raw.samples().back().t_s;
  }
  publish_turn_scene();
}

void FoxgloveLive::publish_turn_scene() {
  turn_drawn_t_s_ = turn_->t_s;
  // Latched like the region: a viewer that connects mid-turn sees the turn at once.
  sink_.publish(topic(*advertised_, ChannelKind::turn), to_ns(turn_->t_s),
                turn_scene_message(*turn_));
}

void FoxgloveLive::log(double t_s, mission::EventKind kind, const std::string& message) {
  sink_.status(level_of(kind), message);
  if (!advertised_) return;
  const std::string t = topic(*advertised_, ChannelKind::log);
  if (sink_.wanted(t))
    sink_.publish(t, to_ns(t_s),
                  log_message(t_s, level_of(kind),
                              *advertised_ + "/" + std::string(mission::to_string(kind)), message));
}

}  // namespace avk::app::foxglove
