#pragma once
// Several live feeds as one: the station tells its own stream and the Foxglove connection the
// same things, in the order the feeds were given.

#include <memory>
#include <utility>
#include <vector>

#include "app/live_feed.hpp"

namespace avk::app {

class LiveFeeds final : public LiveFeed {
 public:
  explicit LiveFeeds(std::vector<LiveFeed*> feeds) : feeds_(std::move(feeds)) {}

  void telemetry(const VehicleSnapshot& s) override {
    for (auto* f : feeds_)
      f->telemetry(s);
  }
  void station_event(double t_s, mission::EventKind kind, const std::string& message) override {
    for (auto* f : feeds_)
      f->station_event(t_s, kind, message);
  }
  std::unique_ptr<mission::MissionObserver> follow(std::int64_t mission_id,
                                                   const mission::MissionRunner& runner) override {
    auto all = std::make_unique<Observers>();
    for (auto* f : feeds_)
      all->list.push_back(f->follow(mission_id, runner));
    return all;
  }
  void current(const std::string& vehicle_id, const CurrentView& c) override {
    for (auto* f : feeds_)
      f->current(vehicle_id, c);
  }

 private:
  struct Observers final : mission::MissionObserver {
    std::vector<std::unique_ptr<mission::MissionObserver>> list;
    void on_nav(const mission::NavRecord& r) override {
      for (auto& o : list)
        o->on_nav(r);
    }
    void on_turn_started(const mission::TurnTask& t, const mission::RunningTurn& r) override {
      for (auto& o : list)
        o->on_turn_started(t, r);
    }
    void on_turn(mission::TurnOutcome& t) override {
      for (auto& o : list)
        o->on_turn(t);
    }
    void on_condition_set(const mission::ConditionSetEpisode& e) override {
      for (auto& o : list)
        o->on_condition_set(e);
    }
    void on_event(const mission::MissionEventRecord& e) override {
      for (auto& o : list)
        o->on_event(e);
    }
    void on_state(mission::MissionState s, const std::string& reason, double t_s) override {
      for (auto& o : list)
        o->on_state(s, reason, t_s);
    }
    void on_mode(mission::HelmMode from, mission::HelmMode to, double t_s) override {
      for (auto& o : list)
        o->on_mode(from, to, t_s);
    }
  };
  std::vector<LiveFeed*> feeds_;
};

}  // namespace avk::app
