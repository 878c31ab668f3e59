#pragma once
// A mission runner's tests run it without a simulator: a scriptable kinematic point vehicle, an
// observer that records everything the runner reports, and the loop that steps them (nav at 10 Hz,
// the helm at 5 Hz).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "kinematics/angles.hpp"
#include "mission/container.hpp"
#include "mission/direction_chooser.hpp"
#include "mission/mission_runner.hpp"
#include "mission/turn_checks.hpp"
#include "mission/turn_monitor.hpp"
#include "mission/turn_plan.hpp"

namespace avk::testing::mission_sim {

using namespace avk::mission;
namespace k = avk::kinematics;
using avk::vehicle::DesiredCommand;
using avk::vehicle::NavSample;
using k::TurnSide;
using k::TurnStatus;

inline bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

// ---- Configuration --------------------------------------------------------------------------

inline OperatingRegion square_region(double half_m, double buffer_m,
                                     k::Point return_point = {0, 0}) {
  OperatingRegion r;
  r.polygon = {{-half_m, -half_m}, {half_m, -half_m}, {half_m, half_m}, {-half_m, half_m}};
  r.buffer_m = buffer_m;
  r.return_point = return_point;
  return r;
}

inline MissionConfig turns_config(std::vector<double> speeds, std::vector<double> dheadings,
                                  DirectionPolicy direction, OperatingRegion region) {
  MissionConfig c;
  c.name = "test";
  c.turn_array.speeds_mps = std::move(speeds);
  c.turn_array.dheadings_deg = std::move(dheadings);
  c.turn_array.direction = direction;
  c.region = std::move(region);
  return c;
}

inline NavSample nav_at(double t, double heading, double speed = 1.0, double x = 0.0,
                        double y = 0.0) {
  return {t, x, y, heading, speed, {}, {}, {}};
}

// ---- A scriptable kinematic point vehicle ---------------------------------------------------

class FakeVehicle final : public avk::vehicle::Vehicle {
 public:
  FakeVehicle(double x_m, double y_m, double heading_deg, double speed_mps = 0.0)
      : info_{"fake", "fake", 2.0, {}},
        x_(x_m),
        y_(y_m),
        heading_(heading_deg),
        speed_(speed_mps) {}

  double yaw_rate_dps = 10.0;
  double accel_mps2 = 0.5;
  std::optional<double> speed_cap;  // never faster than this
  bool deliver_nav = true;          // false: the link is silent
  bool wrong_way = false;           // takes a heading step of over 20 deg the long way round

  int all_stops = 0;
  std::vector<DesiredCommand> commands;

  double x() const { return x_; }
  double y() const { return y_; }
  double heading() const { return heading_; }
  double speed() const { return speed_; }
  void teleport(double x_m, double y_m) { x_ = x_m, y_ = y_m; }
  void set_heading(double deg) { heading_ = k::wrap360_deg(deg); }

  // Integrates from the previous step to t and (if the link is up) reports a sample at t.
  void step(double t_s) {
    const double dt = last_t_ ? t_s - *last_t_ : 0.0;
    last_t_ = t_s;
    double target_speed = 0.0;
    if (cmd_ && !stopped_) {
      turn_towards(cmd_->heading_deg, dt);
      target_speed = cmd_->speed_mps;
    }
    if (speed_cap) target_speed = std::min(target_speed, *speed_cap);
    speed_ += std::clamp(target_speed - speed_, -accel_mps2 * dt, accel_mps2 * dt);
    x_ += speed_ * dt * std::sin(k::deg_to_rad(heading_));
    y_ += speed_ * dt * std::cos(k::deg_to_rad(heading_));
    if (!deliver_nav) return;
    last_ = nav_at(t_s, heading_, speed_, x_, y_);
    pending_.push_back(*last_);
  }

  const avk::vehicle::VehicleInfo& info() const override { return info_; }
  std::vector<NavSample> take_nav() override { return std::exchange(pending_, {}); }
  std::optional<NavSample> last_nav() const override { return last_; }
  avk::vehicle::LinkState link_state(double now_s) const override {
    return avk::vehicle::link_state_from(last_, true, now_s, 2.0);
  }
  void command(const DesiredCommand& d) override {
    cmd_ = d;
    stopped_ = false;
    commands.push_back(d);
  }
  void all_stop(double) override {
    stopped_ = true;
    ++all_stops;
  }
  std::optional<DesiredCommand> last_command() const override { return cmd_; }
  std::optional<avk::vehicle::ActuatorCommand> last_actuators() const override { return {}; }

 private:
  void turn_towards(double target_deg, double dt) {
    if (wrong_way && last_target_ && std::abs(k::angle180_deg(target_deg - *last_target_)) > 20.0)
      turn_dir_ = k::angle180_deg(target_deg - heading_) >= 0.0 ? -1.0 : 1.0;  // the long way
    last_target_ = target_deg;
    const double err = k::angle180_deg(target_deg - heading_);
    const double dir = turn_dir_ != 0.0 ? turn_dir_ : (err >= 0.0 ? 1.0 : -1.0);
    const double left = k::wrap360_deg(dir * (target_deg - heading_));  // to turn that way
    const double step = std::min(left, yaw_rate_dps * dt);
    heading_ = step == left ? target_deg : k::wrap360_deg(heading_ + dir * step);
    if (step == left) turn_dir_ = 0.0;
  }

  avk::vehicle::VehicleInfo info_;
  double x_, y_, heading_, speed_;
  std::optional<double> last_t_;
  std::optional<DesiredCommand> cmd_;
  bool stopped_ = false;
  std::optional<double> last_target_;
  double turn_dir_ = 0.0;  // -1 / +1 while taking a heading step the long way
  std::vector<NavSample> pending_;
  std::optional<NavSample> last_;
};

// ---- Recording observer ---------------------------------------------------------------------

struct Recorder : MissionObserver {
  struct ModeChange {
    HelmMode from, to;
    double t_s;
    std::size_t nav_index;  // navs recorded before the change
  };
  struct Started {
    TurnTask task;
    RunningTurn turn;
    double goal_heading_deg;
  };
  std::vector<NavRecord> navs;
  std::vector<ModeChange> modes;
  std::vector<Started> started;
  std::vector<TurnOutcome> turns;
  std::vector<ConditionSetEpisode> episodes;
  std::vector<MissionEventRecord> events;
  std::vector<MissionState> states;
  void on_nav(const NavRecord& r) override { navs.push_back(r); }
  void on_turn_started(const TurnTask& t, const RunningTurn& turn) override {
    started.push_back({t, turn, turn.goal_heading_deg});
  }
  void on_turn(TurnOutcome& o) override { turns.push_back(o); }
  void on_condition_set(const ConditionSetEpisode& e) override { episodes.push_back(e); }
  void on_event(const MissionEventRecord& e) override { events.push_back(e); }
  void on_state(MissionState s, const std::string&, double) override { states.push_back(s); }
  void on_mode(HelmMode from, HelmMode to, double t_s) override {
    modes.push_back({from, to, t_s, navs.size()});
  }

  std::vector<HelmMode> mode_path() const {
    std::vector<HelmMode> out{HelmMode::containing};
    for (const auto& m : modes)
      out.push_back(m.to);
    return out;
  }
  int count(TurnStatus s) const {
    return static_cast<int>(
        std::count_if(turns.begin(), turns.end(), [&](const auto& t) { return t.status == s; }));
  }
  const MissionEventRecord* event(EventKind kind, const std::string& part = "") const {
    for (const auto& e : events)
      if (e.kind == kind && contains(e.message, part)) return &e;
    return nullptr;
  }
};

// ---- The loop: navigation at 10 Hz, the helm at 5 Hz ----------------------------------------

using Hook = std::function<void(double)>;

struct Sim {
  MissionConfig config;
  FakeVehicle vehicle;
  Recorder rec;
  MissionRunner runner;
  long k = 0;

  Sim(MissionConfig c, FakeVehicle v)
      : config(std::move(c)),
        vehicle(std::move(v)),
        runner(config, vehicle, plan_turns(config), {"fake", "test"}) {
    runner.add_observer(rec);
  }

  double now() const { return static_cast<double>(k) * 0.1; }

  // Steps until stop() holds or max_s has passed; before(t) runs ahead of each navigation step.
  bool run_until(const std::function<bool()>& stop, double max_s, const Hook& before = {}) {
    const long end = k + std::lround(max_s * 10.0);
    while (k < end) {
      const double t = now();
      if (before) before(t);
      vehicle.step(t);
      if (k % 2 == 0) runner.tick(t);
      ++k;
      if (stop()) return true;
    }
    return stop();
  }
  void run_for(double s, const Hook& before = {}) {
    run_until([] { return false; }, s, before);
  }
  bool finish(double max_s = 600.0, const Hook& before = {}) {
    return run_until([&] { return runner.finished(); }, max_s, before);
  }
  bool until_mode(HelmMode m, double max_s = 300.0) {
    return run_until([&] { return runner.mode() == m; }, max_s);
  }
};

}  // namespace avk::testing::mission_sim
