#include "server/stream_publisher.hpp"

#include "app/missions.hpp"
#include "server/serialize.hpp"

namespace avk::server {

namespace {

nlohmann::json with_vehicle(nlohmann::json j, const std::string& vehicle_id) {
  if (!vehicle_id.empty()) j["vehicle_id"] = vehicle_id;
  return j;
}

}  // namespace

void StreamPublisher::on_turn_started(const mission::TurnTask&, const mission::RunningTurn& turn) {
  hub_.publish("turn", turn.start.t_s,
               with_vehicle(turn_started_json(turn, mission_id_), vehicle_id_).dump());
}

void StreamPublisher::on_turn(mission::TurnOutcome& t) {
  const double t_s = t.raw.samples().empty() ? 0.0 : t.raw.samples().back().t_s;
  hub_.publish("turn", t_s, with_vehicle(turn_ended_json(t, mission_id_), vehicle_id_).dump());
  publish_progress(t_s, state_);
}

void StreamPublisher::on_event(const mission::MissionEventRecord& e) {
  hub_.status(e.t_s, e.kind, e.message, vehicle_id_);
}

void StreamPublisher::on_state(mission::MissionState s, const std::string& reason, double t_s) {
  state_ = mission::to_string(s);
  publish_progress(t_s, state_);
  if (!reason.empty()) hub_.status(t_s, mission::state_change_kind(s), reason, vehicle_id_);
}

void StreamPublisher::on_mode(mission::HelmMode, mission::HelmMode, double t_s) {
  publish_progress(t_s, state_);
}

void StreamPublisher::publish_progress(double t_s, const std::string& state) {
  hub_.publish("mission", t_s,
               with_vehicle(mission_progress_json(mission_id_, state, runner_.mode(),
                                                  app::cell_reports(runner_.cells())),
                            vehicle_id_)
                   .dump());
}

}  // namespace avk::server
