// avk frontseat-emulator: a Kingfisher M200 frontseat on a TCP port over the simulated catamaran
// (docs/frontseat-emulator.md), so a backseat (the M200 driver, or nc) can be tried without a boat.
#include <signal.h>

#include <cmath>
#include <ostream>

#include "server/cli/args.hpp"
#include "server/cli/commands.hpp"
#include "server/cli/m200_options.hpp"
#include "server/cli/sim_options.hpp"
#include "sim/frontseat_emulator.hpp"

namespace avk::server {

namespace {

double fraction(const Args& a, const std::string& name) {
  const double f = a.number(name).value_or(0.0);
  if (!(f >= 0.0 && f <= 1.0)) throw UsageError("--" + name + " must be a fraction in [0, 1]");
  return f;
}

}  // namespace

int cmd_frontseat_emulator(const std::vector<std::string>& args, Io& io) {
  const Args a(args, {"port", "bind", "vehicle", "sim-config", "datum", "seed", "realtime-factor",
                      "start", "drop", "corrupt", "nav-delay", "burst", "watchdog"});
  if (!a.positional().empty()) throw UsageError("unexpected argument '" + a.positional()[0] + "'");
  const sim::SimSetup setup = sim_setup_from(a, io, "catamaran:m200");
  if (!vehicle::has_differential_drive(setup.vehicle.kind)) {
    throw UsageError(std::string("vehicle ") + vehicle::to_string(setup.vehicle.kind) +
                     " cannot be a frontseat: $PYDIR drives left and right thrusters, which only "
                     "the differential-drive kinds have (" +
                     vehicle::vehicle_kind_names(vehicle::can_emulate_frontseat) + ")");
  }

  sim::FrontseatEmulatorOptions o;
  o.vehicle = setup.vehicle;
  o.seed = setup.scheduler.seed;
  o.bind_address = a.get("bind").value_or("127.0.0.1");
  const double port = a.number("port").value_or(29500);
  if (port < 0 || port > 65535 || port != std::floor(port))
    throw UsageError("--port must be a whole number from 0 to 65535");
  o.port = static_cast<unsigned short>(port);
  o.realtime_factor = realtime_factor_from(a);
  if (const auto d = datum_from(a)) o.datum = *d;
  if (const auto s = a.number_list("start", 3, "X,Y,HEADING (m east, m north, deg)")) {
    o.start_x_m = (*s)[0];
    o.start_y_m = (*s)[1];
    o.start_heading_deg = (*s)[2];
  }
  o.faults.drop_fraction = fraction(a, "drop");
  o.faults.corrupt_fraction = fraction(a, "corrupt");
  o.faults.nav_delay_s = a.number("nav-delay").value_or(0.0);
  if (!(o.faults.nav_delay_s >= 0.0 && o.faults.nav_delay_s <= 3600.0))
    throw UsageError("--nav-delay must be in [0, 3600] seconds");
  const double burst = a.number("burst").value_or(0.0);
  if (!(burst >= 0.0 && burst <= 100.0 && burst == std::floor(burst)))
    throw UsageError("--burst must be a whole number of sentences from 0 to 100");
  o.faults.burst_max_lines = static_cast<int>(burst);
  o.watchdog_s = a.number("watchdog").value_or(o.watchdog_s);
  if (!(o.watchdog_s > 0.0)) throw UsageError("--watchdog must be positive (seconds)");

  // Signals are taken by this thread alone (sigwait), so block them before the emulator's
  // thread starts: it inherits the mask.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);

  sim::FrontseatEmulator emulator(o);
  io.out << "frontseat emulator (" << vehicle::to_string(o.vehicle.kind) << ") listening on "
         << o.bind_address << ":" << emulator.port() << ", datum " << num(o.datum.lat_deg) << ","
         << num(o.datum.lon_deg) << ", clock x" << num(o.realtime_factor) << ", watchdog "
         << num(o.watchdog_s) << " s" << std::endl;
  int signal_number = 0;
  sigwait(&signals, &signal_number);
  emulator.stop();
  const sim::FrontseatStatus s = emulator.status();
  io.err << "frontseat-emulator: " << (signal_number == SIGINT ? "SIGINT" : "SIGTERM") << " at "
         << num(std::round(s.t_s * 10.0) / 10.0) << " s: " << s.sentences_sent
         << " sentences sent (" << s.sentences_dropped << " dropped, " << s.sentences_corrupted
         << " corrupted), " << s.pydir_received << " $PYDIR received (" << s.bad_lines_received
         << " bad lines), " << s.watchdog_trips << " watchdog trips, " << s.connections
         << " connections\n";
  pthread_sigmask(SIG_UNBLOCK, &signals, nullptr);
  return 0;
}

}  // namespace avk::server
