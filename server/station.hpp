#pragma once
// The ground station behind /api/v1: vehicles, missions, turns, the CKT, predictions, models and
// the comparison, over the store; missions run on the station's vehicle loop. Handlers parse and
// validate, call the layers below and serialise; every error is problem+json (RFC 9457).

#include <memory>
#include <optional>
#include <string>

#include "server/api_types.hpp"
#include "server/stream_hub.hpp"
#include "server/vehicle_loop.hpp"

namespace avk::server {

struct StationOptions {
  std::string db_path;
  std::string token;  // bearer token for control endpoints (and for any non-loopback client)
  std::string server_version;
  // The vehicle missions run on (simulated, or an M200 over its link); none: no vehicle.
  std::optional<VehicleLoopOptions> vehicle;
};

class Station final : public Api {
 public:
  Station(StationOptions options, StreamHub& hub);
  ~Station() override;

  // Marks missions whose process died as interrupted and starts the vehicle loop.
  void start();
  // Interrupts a running mission (stored, resumable), flushes and stops the vehicle.
  void shutdown();

  ApiResponse handle(const ApiRequest& request) override;
  // The rule of a GET: open on loopback, the bearer token from anywhere else.
  bool may_open_stream(const ApiRequest& request) override;
  // From the header: the token (401 before any body is read) and the route's body limit.
  Admission admit(const ApiRequest& head) override;

  VehicleLoop* vehicle_loop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace avk::server
