#pragma once
// A Kingfisher M200 frontseat on the network: a TCP server speaking the frontseat side of the
// Clearpath protocol (vehicle/nmea.hpp) over a simulated catamaran plant, so that the M200 driver
// is tested over a real socket. It sends $CPNVG, $CPNVR and $GPRMC at nav_hz and $CPRBS at
// battery_hz to every connected client, drives the plant from the $PYDIR it receives (the newest
// valid one from any client), and zeroes the motors when no valid $PYDIR arrived for
// watchdog_s, as the real frontseat does. Faults can be injected for tests: dropped and corrupted
// sentences, delayed navigation, bursts, link cuts. Asio stays inside frontseat_emulator.cpp.
//
// The plant runs on its own clock at realtime_factor x the wall clock; every time in this
// interface (watchdog, cuts, events) is on that clock, seconds from the emulator's start.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sim/sim_vehicle.hpp"
#include "vehicle/local_grid.hpp"

namespace avk::sim {

struct FrontseatFaults {
  double drop_fraction = 0.0;     // of outgoing sentences, each independently
  double corrupt_fraction = 0.0;  // of outgoing sentences: one checksum digit altered
  double nav_delay_s = 0.0;       // navigation sentences leave this much later than measured
  // A link that delivers in bursts (a radio modem, a serial bridge): sentences are held back and
  // written together, each burst 2 to burst_max_lines of them (drawn uniformly). 0 or 1: every
  // sentence is written when it is sent.
  int burst_max_lines = 0;
};

struct FrontseatEmulatorOptions {
  std::string bind_address = "127.0.0.1";
  unsigned short port = 29500;  // 0 picks a free port (see port())
  // A SimVehicleConfig kind with differential thrust: "catamaran:m200" (default, the waterjet
  // M200), "catamaran", "catamaran:heron", "catamaran:otter". Sensor noise and environment come
  // from the config as for the simulator; its PID settings do not apply (the backseat controls).
  SimVehicleConfig vehicle = sim_vehicle_defaults(vehicle::VehicleKind::catamaran_m200);
  vehicle::LatLon datum{42.358456, -71.087589};  // MIT Sailing Pavilion, the MOOS-IvP datum
  double start_x_m = 0.0, start_y_m = 0.0, start_heading_deg = 0.0;
  std::uint64_t seed = 1;
  double realtime_factor = 1.0;
  double plant_hz = 20.0;  // plant integration and watchdog check rate
  double nav_hz = 5.0;     // CPNVG, CPNVR, GPRMC
  double battery_hz = 0.5;
  double watchdog_s = 1.0;
  double battery_v = 14.8;  // stack voltage, sagging slowly with thrust
  // UTC time of day (seconds since midnight) at clock 0: every time field sent is
  // start_of_day_s + the clock time, wrapping at midnight, so a backseat can map it back.
  double start_of_day_s = 12.0 * 3600.0;
  FrontseatFaults faults{};
};

// What the emulated vehicle is doing, for tests and the operator's console.
struct FrontseatStatus {
  double t_s = 0.0;
  TruthSample truth;
  double left_pct = 0.0;  // what the motors are driven with now
  double right_pct = 0.0;
  std::optional<double> last_pydir_s;  // clock time of the newest valid $PYDIR
  std::uint64_t watchdog_trips = 0;
  std::optional<double> last_watchdog_trip_s;  // when the motors were last zeroed by it
  std::uint64_t clients = 0;                   // connected now
  std::uint64_t connections = 0;               // accepted since start
  std::uint64_t sentences_sent = 0;            // put on the link, once however many clients listen
  std::uint64_t sentences_dropped = 0;
  std::uint64_t sentences_corrupted = 0;
  std::uint64_t bursts = 0;  // groups of held-back sentences written at once
  std::uint64_t lines_received = 0;
  std::uint64_t pydir_received = 0;      // valid $PYDIR: commands taken
  std::uint64_t bad_lines_received = 0;  // failed to parse (typed error counted, line ignored)
  bool link_cut = false;
};

class FrontseatEmulator {
 public:
  // Binds and listens (throws std::runtime_error naming the address and port when it cannot) and
  // starts the plant and network thread.
  explicit FrontseatEmulator(FrontseatEmulatorOptions options);
  ~FrontseatEmulator();  // stop()
  FrontseatEmulator(const FrontseatEmulator&) = delete;
  FrontseatEmulator& operator=(const FrontseatEmulator&) = delete;

  unsigned short port() const;
  double now_s() const;  // the emulator's clock
  FrontseatStatus status() const;

  // Closes every client connection now and refuses (accepts and closes at once) new ones for
  // duration_s of the emulator's clock: a radio link going down.
  void cut_link(double duration_s);
  // Changes the injected faults from now on.
  void set_faults(const FrontseatFaults& faults);

  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace avk::sim
