#pragma once
// A running mission as the live stream tells it: turns started and ended (with the stored id to
// fetch over REST), mission progress and state, and the events an operator must read.

#include <cstdint>
#include <string>

#include "mission/mission_observer.hpp"
#include "mission/mission_runner.hpp"
#include "server/stream_hub.hpp"

namespace avk::server {

class StreamPublisher final : public mission::MissionObserver {
 public:
  StreamPublisher(StreamHub& hub, std::int64_t mission_id, const mission::MissionRunner& runner,
                  std::string vehicle_id = {})
      : hub_(hub), mission_id_(mission_id), runner_(runner), vehicle_id_(std::move(vehicle_id)) {}

  void on_turn_started(const mission::TurnTask& task, const mission::RunningTurn& turn) override;
  void on_turn(mission::TurnOutcome& t) override;
  void on_event(const mission::MissionEventRecord& e) override;
  void on_state(mission::MissionState s, const std::string& reason, double t_s) override;
  void on_mode(mission::HelmMode from, mission::HelmMode to, double t_s) override;

  // The mission topic's payload: state, mode and per-cell progress.
  void publish_progress(double t_s, const std::string& state);

 private:
  StreamHub& hub_;
  std::int64_t mission_id_;
  const mission::MissionRunner& runner_;
  std::string vehicle_id_;  // named in every message (left out when empty)
  std::string state_ = "running";
};

}  // namespace avk::server
