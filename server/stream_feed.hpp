#pragma once
// One vehicle's live feed as the stream's topics: telemetry becomes nav and helm, station events
// become status, and each mission the vehicle loop starts is followed by a StreamPublisher. Every
// message names the vehicle, so a client of a fleet station tells the vehicles apart.

#include <string>

#include "app/live_feed.hpp"
#include "server/stream_hub.hpp"

namespace avk::server {

class StreamFeed final : public app::LiveFeed {
 public:
  StreamFeed(StreamHub& hub, std::string vehicle_id)
      : hub_(hub), vehicle_id_(std::move(vehicle_id)) {}
  void telemetry(const app::VehicleSnapshot& s) override;
  void station_event(double t_s, mission::EventKind kind, const std::string& message) override;
  std::unique_ptr<mission::MissionObserver> follow(std::int64_t mission_id,
                                                   const mission::MissionRunner& runner) override;
  void current(const std::string& vehicle_id, const app::CurrentView& c) override;

 private:
  StreamHub& hub_;
  std::string vehicle_id_;
};

}  // namespace avk::server
