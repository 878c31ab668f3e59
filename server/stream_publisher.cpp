#include "server/stream_publisher.hpp"

#include <nlohmann/json.hpp>

#include "app/missions.hpp"
#include "server/serialize.hpp"

namespace avk::server {

using nlohmann::json;

void StreamPublisher::on_turn_started(const mission::TurnTask&, const mission::RunningTurn& turn) {
  json j = running_turn_json(turn);
  j["event"] = "started";
  j["mission_id"] = mission_id_;
  hub_.publish("turn", turn.start.t_s, j.dump());
}

void StreamPublisher::on_turn(mission::TurnOutcome& t) {
  json j = {{"event",
             t.status == kinematics::TurnStatus::ok ? "finished" : kinematics::to_string(t.status)},
            {"mission_id", mission_id_},
            {"status", kinematics::to_string(t.status)},
            {"reason", t.reason},
            {"speed_mps", t.task.speed_mps},
            {"goal_dheading_deg", t.raw.meta().goal_dheading_deg},
            {"requeued", t.requeued},
            {"given_up", t.given_up}};
  j["id"] = t.stored_id ? json(*t.stored_id) : json();
  j["advance_m"] = t.advance_m ? json(*t.advance_m) : json();
  j["transfer_m"] = t.transfer_m ? json(*t.transfer_m) : json();
  j["condition_set_time_s"] = t.condition_set_time_s ? json(*t.condition_set_time_s) : json();
  const double t_s = t.raw.samples().empty() ? 0.0 : t.raw.samples().back().t_s;
  hub_.publish("turn", t_s, j.dump());
  publish_progress(t_s, state_);
}

void StreamPublisher::on_event(const mission::MissionEventRecord& e) {
  hub_.status(e.t_s, e.kind, e.message);
}

void StreamPublisher::on_state(mission::MissionState s, const std::string& reason, double t_s) {
  state_ = mission::to_string(s);
  publish_progress(t_s, state_);
  if (!reason.empty()) hub_.status(t_s, mission::state_change_kind(s), reason);
}

void StreamPublisher::on_mode(mission::HelmMode, mission::HelmMode, double t_s) {
  publish_progress(t_s, state_);
}

void StreamPublisher::publish_progress(double t_s, const std::string& state) {
  hub_.publish("mission", t_s,
               json{{"mission_id", mission_id_},
                    {"state", state},
                    {"helm_mode", mission::to_string(runner_.mode())},
                    {"cells", cells_json(app::cell_reports(runner_.cells()))}}
                   .dump());
}

}  // namespace avk::server
