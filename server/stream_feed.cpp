#include "server/stream_feed.hpp"

#include "server/serialize.hpp"
#include "server/stream_publisher.hpp"

namespace avk::server {

void StreamFeed::telemetry(const app::VehicleSnapshot& s) {
  if (s.nav) hub_.publish("nav", s.t_s, nav_topic_json(s).dump(), s.info.id);
  hub_.publish("helm", s.t_s, helm_topic_json(s).dump(), s.info.id);
}

void StreamFeed::station_event(double t_s, mission::EventKind kind, const std::string& message) {
  hub_.status(t_s, kind, message, vehicle_id_);
}

void StreamFeed::current(const std::string& vehicle_id, const app::CurrentView& c) {
  hub_.publish("current", c.t_s, current_json(vehicle_id, c).dump(), vehicle_id);
}

std::unique_ptr<mission::MissionObserver> StreamFeed::follow(std::int64_t mission_id,
                                                             const mission::MissionRunner& runner) {
  return std::make_unique<StreamPublisher>(hub_, mission_id, runner, vehicle_id_);
}

}  // namespace avk::server
