#pragma once
// The Kingfisher M200 over its frontseat network protocol: a TCP client to the frontseat (port
// 29500) behind the Vehicle interface. Lines go to an M200Session; $PYDIR goes out at the
// controller rate. When the link drops it reconnects with exponential backoff; meanwhile the
// vehicle reports LinkState::disconnected, which the mission answers by aborting the turn in
// progress, re-queuing it and holding until navigation is back. Asio stays in m200.cpp.
//
// Every time here is on the run's ScaledClock (factor 1 against a real boat).

#include <chrono>
#include <memory>
#include <optional>
#include <string>

#include "vehicle/m200_session.hpp"
#include "vehicle/scaled_clock.hpp"
#include "vehicle/vehicle.hpp"

namespace avk::vehicle {

struct M200Endpoint {
  std::string host;
  unsigned short port = 29500;
};

// "HOST:PORT" or "HOST" (port 29500). Throws std::invalid_argument naming what is wrong.
M200Endpoint parse_m200_endpoint(const std::string& text);

struct M200Options {
  M200Endpoint endpoint;
  M200Config config;
  // Reconnect backoff on the mission clock: first retry after the minimum, doubling to the
  // maximum while attempts fail.
  double reconnect_min_s = 0.5;
  double reconnect_max_s = 8.0;
};

struct M200Status {
  bool connected = false;
  LinkState link = LinkState::disconnected;
  Failsafe failsafe = Failsafe::none;
  std::optional<M200Battery> battery;
  M200Counters counters;
  std::string last_link_error;  // why the last connection failed or closed
};

class M200 final : public Vehicle {
 public:
  // Starts connecting at once, in the background. The clock must outlive this.
  M200(M200Options options, const ScaledClock& clock);
  ~M200() override;  // stop()
  M200(const M200&) = delete;
  M200& operator=(const M200&) = delete;

  const VehicleInfo& info() const override { return info_; }
  std::vector<NavSample> take_nav() override;
  std::optional<NavSample> last_nav() const override;
  LinkState link_state(double now_s) const override;
  void command(const DesiredCommand& desired) override;
  void all_stop(double now_s) override;
  std::optional<DesiredCommand> last_command() const override;
  std::optional<ActuatorCommand> last_actuators() const override;

  M200Status status() const;
  // Blocks until navigation has arrived (true) or the wall-clock timeout passed (false).
  bool wait_for_nav(std::chrono::milliseconds timeout) const;
  // Closes the link and stops reconnecting; the frontseat's watchdog stops the motors.
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  VehicleInfo info_;
};

}  // namespace avk::vehicle
