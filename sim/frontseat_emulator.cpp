// The frontseat emulator's network and plant loop. The only place besides realtime_pacer.cpp that
// includes Asio in sim/: one thread runs one io_context, so the plant, the watchdog, the accept
// loop and every client's reads and writes are serialised on it. The mutex is there only for the
// callers of status(), set_faults() and cut_link() on other threads.
#include "sim/frontseat_emulator.hpp"

#include <algorithm>
#include <boost/asio/buffers_iterator.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/read_until.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/asio/streambuf.hpp>
#include <boost/asio/write.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <list>
#include <mutex>
#include <random>
#include <stdexcept>
#include <thread>
#include <utility>
#include <variant>

#include "kinematics/angles.hpp"
#include "sim/catamaran.hpp"
#include "sim/sensors.hpp"
#include "vehicle/nmea.hpp"
#include "vehicle/scaled_clock.hpp"

namespace avk::sim {

namespace {

namespace net = boost::asio;
using tcp = net::ip::tcp;
using boost::system::error_code;

// A backseat line is at most kNmeaMaxLineBytes; a client that sends this much without a newline
// is broken or hostile, and buffering more would let it grow the emulator's memory at will.
constexpr std::size_t kReceiveLimitBytes = 4096;
// About 30 s of everything the emulator sends at the default rates. Beyond that the client is not
// reading: its oldest unsent lines are dropped rather than the client closed, since stale
// navigation is worthless to a backseat anyway, and a serial frontseat link overruns the same way.
constexpr std::size_t kMaxQueuedLines = 512;
// A burst longer than this would be most of the queue, and seconds of navigation held back.
constexpr int kMaxBurstLines = 100;
// After the thread was starved (a debugger, a loaded machine) the plant catches up at most this
// much of its own time per wake and skips the rest, rather than spinning to replay it.
constexpr double kMaxCatchUpS = 1.0;
constexpr double kEps = 1e-9;
constexpr double kSecondsPerDay = 86400.0;
// The M200's pack is 4S lithium: about 3.7 V a cell.
constexpr double kNominalCellV = 3.7;
// How far the stack voltage drops at full thrust on both sides, and how fast it follows the load.
constexpr double kSagAtFullThrustV = 0.6;
constexpr double kSagTimeConstantS = 5.0;

const std::chrono::sys_days kClockZeroDate{std::chrono::year{2024} / std::chrono::June / 1};

std::string endpoint_text(const std::string& address, unsigned short port) {
  const bool v6 = address.find(':') != std::string::npos;
  return (v6 ? "[" + address + "]" : address) + ":" + std::to_string(port);
}

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("frontseat emulator: " + what);
}

void check_faults(const FrontseatFaults& f) {
  require(f.drop_fraction >= 0.0 && f.drop_fraction <= 1.0, "drop_fraction must be in [0, 1]");
  require(f.corrupt_fraction >= 0.0 && f.corrupt_fraction <= 1.0,
          "corrupt_fraction must be in [0, 1]");
  require(f.nav_delay_s >= 0.0 && f.nav_delay_s <= 3600.0, "nav_delay_s must be in [0, 3600]");
  require(f.burst_max_lines >= 0 && f.burst_max_lines <= kMaxBurstLines,
          "burst_max_lines must be in [0, " + std::to_string(kMaxBurstLines) + "]");
}

FrontseatEmulatorOptions checked(FrontseatEmulatorOptions o) {
  if (!vehicle::can_emulate_frontseat(o.vehicle.kind)) {
    throw std::invalid_argument(std::string("frontseat emulator: vehicle kind ") +
                                vehicle::to_string(o.vehicle.kind) +
                                " has no simulated left and right thrusters for $PYDIR; use " +
                                vehicle::vehicle_kind_names(vehicle::can_emulate_frontseat));
  }
  o.vehicle = with_kind_defaults(std::move(o.vehicle));
  require(o.plant_hz > 0.0 && o.plant_hz <= 1000.0, "plant_hz must be in (0, 1000]");
  // Sentences go out on plant steps, so they cannot come faster than the plant.
  require(o.nav_hz > 0.0 && o.nav_hz <= o.plant_hz, "nav_hz must be in (0, plant_hz]");
  require(o.battery_hz > 0.0 && o.battery_hz <= o.plant_hz, "battery_hz must be in (0, plant_hz]");
  require(o.watchdog_s > 0.0 && std::isfinite(o.watchdog_s), "watchdog_s must be positive");
  require(o.battery_v > 0.0 && o.battery_v <= 100.0, "battery_v must be in (0, 100]");
  require(o.start_of_day_s >= 0.0 && o.start_of_day_s < kSecondsPerDay,
          "start_of_day_s must be in [0, 86400)");
  require(std::isfinite(o.start_x_m) && std::isfinite(o.start_y_m) &&
              std::isfinite(o.start_heading_deg),
          "start pose must be finite");
  check_faults(o.faults);
  return o;
}

// The simulator's vehicle config at the emulator's start pose and seed.
SimVehicleConfig plant_config(const FrontseatEmulatorOptions& o) {
  SimVehicleConfig c = o.vehicle;
  c.start_x_m = o.start_x_m;
  c.start_y_m = o.start_y_m;
  c.start_heading_deg = kinematics::wrap360_deg(o.start_heading_deg);
  c.start_speed_mps = 0.0;
  c.seed = o.seed;
  return c;
}

struct Client {
  explicit Client(tcp::socket s) : socket(std::move(s)), in(kReceiveLimitBytes) {}
  tcp::socket socket;
  net::streambuf in;
  std::deque<std::string> pending;  // waiting for the write in progress to finish
  std::string writing;              // what async_write is sending: must outlive it
  bool busy = false;
  bool open = true;
};

struct Delayed {
  double release_s = 0.0;
  std::string line;
};

}  // namespace

struct FrontseatEmulator::Impl {
  explicit Impl(FrontseatEmulatorOptions o)
      : opt(checked(std::move(o))),
        grid(opt.datum.lat_deg, opt.datum.lon_deg),
        plant(make_catamaran_plant(plant_config(opt))),
        sensor(make_nav_sensor(plant_config(opt))),
        fault_rng(opt.seed * 0xBF58476D1CE4E5B9ULL + 3),
        faults(opt.faults),
        clock(opt.realtime_factor) {
    truth = truth_now(0.0);
    error_code ec;
    const auto fail = [&](const char* what) {
      throw std::runtime_error("frontseat emulator cannot listen on " +
                               endpoint_text(opt.bind_address, opt.port) + ": " + what + ": " +
                               ec.message());
    };
    const auto address = net::ip::make_address(opt.bind_address, ec);
    if (ec) fail("bad address");
    const tcp::endpoint endpoint(address, opt.port);
    acceptor.open(endpoint.protocol(), ec);
    if (ec) fail("open");
    acceptor.set_option(net::socket_base::reuse_address(true), ec);
    if (ec) fail("set_option");
    acceptor.bind(endpoint, ec);
    if (ec) fail("bind");
    acceptor.listen(net::socket_base::max_listen_connections, ec);
    if (ec) fail("listen");
    bound_port = acceptor.local_endpoint(ec).port();
    if (ec) fail("local_endpoint");
  }

  // ---- Plant, watchdog and the sentences it sends (io thread) ------------------------------

  TruthSample truth_now(double t) const {
    TruthSample s = plant.truth();
    s.t_s = t;  // the emulator's clock, which the plant's own time may trail by a partial step
    return s;
  }

  double period() const { return 1.0 / opt.plant_hz; }
  double time_of_day(double t) const { return opt.start_of_day_s + std::max(0.0, t); }

  void schedule_tick() {
    timer.expires_at(clock.wall_time(static_cast<double>(step + 1) * period()));
    timer.async_wait([this](error_code ec) {
      if (ec) return;
      tick();
    });
  }

  void tick() {
    {
      std::lock_guard lock(m);
      if (stopped) return;
      const auto target = static_cast<long long>(std::floor(clock.now_s() * opt.plant_hz + kEps));
      const auto cap = std::max<long long>(1, std::llround(kMaxCatchUpS * opt.plant_hz));
      // Skipped time is time the plant never sees: it is as if the boat froze. The watchdog
      // still trips on its grid time (see check_watchdog), so its timing is not starved too.
      if (target - step > cap) step = target - cap;
      try {
        while (step < target)
          plant_step(++step);
      } catch (const std::exception& e) {
        // A formatter rejecting a value is a bug here, but one bad step must not stop the
        // emulator that a test or a driver is talking to.
        std::fprintf(stderr, "frontseat emulator: step at %.3f s: %s\n",
                     static_cast<double>(step) * period(), e.what());
      }
    }
    schedule_tick();
  }

  void plant_step(long long k) {
    const double t = static_cast<double>(k) * period();
    if (k > 0) {
      plant.advance(period(), left_pct, right_pct);
      const double load = (std::abs(left_pct) + std::abs(right_pct)) / 200.0;
      battery_load += (load - battery_load) * std::min(1.0, period() / kSagTimeConstantS);
    }
    check_watchdog(t);
    truth = truth_now(t);
    sensor.measure(truth);
    for (const vehicle::NavSample& s : sensor.deliver(t))
      last_nav = s;
    if (t >= static_cast<double>(nav_index) / opt.nav_hz - kEps) {
      if (last_nav) send_nav(t);
      nav_index = static_cast<long long>(std::floor(t * opt.nav_hz + kEps)) + 1;
    }
    if (t >= static_cast<double>(battery_index) / opt.battery_hz - kEps) {
      send_battery(t);
      battery_index = static_cast<long long>(std::floor(t * opt.battery_hz + kEps)) + 1;
    }
    while (!delayed.empty() && delayed.front().release_s <= t + kEps) {
      broadcast(std::move(delayed.front().line));
      delayed.pop_front();
    }
  }

  void check_watchdog(double t) {
    if (!last_pydir_s || watchdog_tripped) return;
    const double deadline = *last_pydir_s + opt.watchdog_s;
    if (t < deadline - kEps) return;
    left_pct = right_pct = 0.0;
    watchdog_tripped = true;  // once per silence: the next valid $PYDIR re-arms it
    ++watchdog_trips;
    // The first plant step at or after the deadline: the step just taken, unless a starved
    // thread skipped steps, in which case it is where the trip belonged.
    last_watchdog_trip_s = std::ceil(deadline * opt.plant_hz - kEps) * period();
  }

  void send_nav(double t) {
    const vehicle::NavSample& s = *last_nav;
    const vehicle::LatLon p = grid.to_geodetic(s.x_m, s.y_m);
    const double tod = time_of_day(t);

    vehicle::Cpnvg nvg;
    nvg.time_s = tod;
    nvg.lat_deg = p.lat_deg;
    nvg.lon_deg = p.lon_deg;
    nvg.position_ok = true;
    nvg.heading_deg = s.heading_deg;
    // The sample's stamp is when it arrived; the pose is from latency_s before.
    nvg.nav_time_s = time_of_day(s.t_s - opt.vehicle.sensors.latency_s);

    vehicle::Cpnvr nvr;
    nvr.time_s = tod;
    const double course_rad = kinematics::deg_to_rad(truth.course_over_ground_deg);
    nvr.v_east_mps = truth.speed_over_ground_mps * std::sin(course_rad);
    nvr.v_north_mps = truth.speed_over_ground_mps * std::cos(course_rad);
    nvr.yaw_rate_dps = truth.yaw_rate_dps;

    vehicle::Gprmc rmc;
    rmc.time_s = tod;
    rmc.valid = true;
    rmc.lat_deg = p.lat_deg;
    rmc.lon_deg = p.lon_deg;
    rmc.speed_knots = s.speed_mps / vehicle::kMetresPerSecondPerKnot;
    rmc.course_deg = kinematics::wrap360_deg(truth.course_over_ground_deg);
    const auto days = static_cast<int>(std::floor((opt.start_of_day_s + t) / kSecondsPerDay));
    const std::chrono::year_month_day ymd{kClockZeroDate + std::chrono::days{days}};
    rmc.date = vehicle::NmeaDate{static_cast<int>(ymd.year()),
                                 static_cast<int>(static_cast<unsigned>(ymd.month())),
                                 static_cast<int>(static_cast<unsigned>(ymd.day()))};
    rmc.mode = 'A';

    // Delayed as a group and in order: a late navigation solution, not a reordered one.
    const double release = t + faults.nav_delay_s;
    for (std::string line :
         {vehicle::format_cpnvg(nvg), vehicle::format_cpnvr(nvr), vehicle::format_gprmc(rmc)}) {
      delayed.push_back(Delayed{release, std::move(line)});
    }
  }

  void send_battery(double t) {
    vehicle::Cprbs b;
    b.time_s = time_of_day(t);
    b.stack_v = opt.battery_v - kSagAtFullThrustV * battery_load;
    const double cells = std::max(1.0, std::round(opt.battery_v / kNominalCellV));
    const double cell = b.stack_v / cells;
    // Cells drift apart a little under load, as a real pack's do.
    b.min_v = cell - 0.01 - 0.02 * battery_load;
    b.max_v = cell + 0.01;
    b.temperature_c = 25.0 + 3.0 * battery_load;
    broadcast(vehicle::format_cprbs(b));
  }

  // Faults are drawn once per sentence, not per client: every listener sees the same link.
  void broadcast(std::string line) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const double u_drop = unit(fault_rng), u_corrupt = unit(fault_rng);
    const auto digit_shift = std::uniform_int_distribution<int>(1, 15)(fault_rng);
    if (u_drop < faults.drop_fraction) {
      ++sentences_dropped;
      return;
    }
    if (u_corrupt < faults.corrupt_fraction) {
      const auto star = line.rfind('*');
      if (star != std::string::npos && star + 2 < line.size()) {
        static constexpr char kHex[] = "0123456789ABCDEF";
        char& c = line[star + 1];
        const int v = c >= 'A' ? c - 'A' + 10 : c - '0';
        c = kHex[(v + digit_shift) % 16];
        ++sentences_corrupted;
      }
    }
    ++sentences_sent;
    held.push_back(std::move(line));
    if (faults.burst_max_lines < 2) {
      release_held();
      return;
    }
    if (burst_lines == 0)
      burst_lines = std::uniform_int_distribution<int>(2, faults.burst_max_lines)(fault_rng);
    if (static_cast<int>(held.size()) >= burst_lines) {
      ++bursts;
      burst_lines = 0;
      release_held();
    }
  }

  // Every held sentence to every client, queued before any is written so that a burst goes out
  // in one write.
  void release_held() {
    for (const auto& c : clients) {
      if (!c->open) continue;
      for (const std::string& l : held) {
        c->pending.push_back(l);
        if (c->pending.size() > kMaxQueuedLines) c->pending.pop_front();
      }
      if (!c->busy) start_write(c);
    }
    held.clear();
  }

  // ---- Clients (io thread) ------------------------------------------------------------------

  void start_write(const std::shared_ptr<Client>& c) {
    // Everything queued goes out in one write: one system call per wake, not per sentence.
    c->writing.clear();
    for (const std::string& l : c->pending)
      c->writing += l;
    c->pending.clear();
    c->busy = true;
    net::async_write(c->socket, net::buffer(c->writing), [this, c](error_code ec, std::size_t) {
      std::lock_guard lock(m);
      c->busy = false;
      if (!c->open) return;
      if (ec) {
        close_client(c);
      } else if (!c->pending.empty()) {
        start_write(c);
      }
    });
  }

  void start_accept() {
    acceptor.async_accept([this](error_code ec, tcp::socket s) {
      {
        std::lock_guard lock(m);
        if (stopped || ec == net::error::operation_aborted) return;
        if (ec) {
          // Out of file descriptors, typically: retrying at once would spin a core.
          accept_retry.expires_after(std::chrono::milliseconds(50));
          accept_retry.async_wait([this](error_code wait_ec) {
            if (!wait_ec) start_accept();
          });
          return;
        }
        ++connections;
        if (link_cut_now()) {
          error_code ignored;
          s.shutdown(tcp::socket::shutdown_both, ignored);
          s.close(ignored);
        } else {
          // Five sentences a second must not wait on the peer's delayed ACK.
          error_code ignored;
          s.set_option(tcp::no_delay(true), ignored);
          auto c = std::make_shared<Client>(std::move(s));
          clients.push_back(c);
          start_read(c);
        }
      }
      start_accept();
    });
  }

  void start_read(const std::shared_ptr<Client>& c) {
    net::async_read_until(c->socket, c->in, '\n', [this, c](error_code ec, std::size_t n) {
      std::lock_guard lock(m);
      if (!c->open) return;
      if (ec == net::error::not_found) {
        // kReceiveLimitBytes without a newline: no line can be that long.
        ++lines_received;
        ++bad_lines_received;
        close_client(c);
        return;
      }
      if (ec) {  // end of file or a reset; a partial last line is not a line
        close_client(c);
        return;
      }
      const auto data = c->in.data();
      const std::string line(net::buffers_begin(data),
                             net::buffers_begin(data) + static_cast<std::ptrdiff_t>(n));
      c->in.consume(n);
      handle_line(line);
      start_read(c);
    });
  }

  void handle_line(const std::string& line) {
    ++lines_received;
    const vehicle::NmeaParseResult r =
        vehicle::parse_sentence(line, vehicle::NmeaDirection::backseat_to_frontseat);
    const vehicle::NmeaSentence* s = r.sentence();
    if (!s) {
      ++bad_lines_received;
      return;
    }
    if (const auto* d = std::get_if<vehicle::Pydir>(s)) {
      ++pydir_received;
      left_pct = d->left_pct;
      right_pct = d->right_pct;
      last_pydir_s = clock.now_s();
      watchdog_tripped = false;
    }
    // $PYDEV, $PYDEP and $PYCLT are well-formed and counted, and change nothing: the M200's
    // frontseat has no heading or speed controller of its own (the backseat closes those loops
    // and sends thrust), and the emulator has no lights. Anything else that parses is ignored.
  }

  void close_client(const std::shared_ptr<Client>& c) {
    if (!c->open) return;
    c->open = false;
    error_code ignored;
    // Shut down first so the peer sees an orderly end of stream (FIN), not just a vanished fd.
    c->socket.shutdown(tcp::socket::shutdown_both, ignored);
    c->socket.close(ignored);
    c->pending.clear();
    clients.remove(c);
  }

  void close_all_clients() {
    const auto all = clients;
    for (const auto& c : all)
      close_client(c);
  }

  bool link_cut_now() const { return cut_until_s && clock.now_s() < *cut_until_s; }

  // Declared first: destroyed last, after every socket and timer that uses it.
  net::io_context io;
  FrontseatEmulatorOptions opt;
  vehicle::LocalGrid grid;
  CatamaranPlant plant;
  NavSensor sensor;
  std::mt19937_64 fault_rng;
  tcp::acceptor acceptor{io};
  net::steady_timer timer{io};
  net::steady_timer accept_retry{io};
  unsigned short bound_port = 0;
  std::thread thread;
  std::mutex stop_mutex;  // serialises stop() callers; never held by the io thread

  mutable std::mutex m;  // everything below
  FrontseatFaults faults;
  vehicle::ScaledClock clock;  // last: it starts when the emulator is otherwise ready
  bool stopped = false;
  long long step = -1;  // the newest plant step taken; step k is at clock time k / plant_hz
  long long nav_index = 0;
  long long battery_index = 0;
  TruthSample truth;
  std::optional<vehicle::NavSample> last_nav;
  double left_pct = 0.0, right_pct = 0.0;
  double battery_load = 0.0;  // mean |thrust| / 100, low-pass filtered
  std::optional<double> last_pydir_s;
  bool watchdog_tripped = false;
  std::uint64_t watchdog_trips = 0;
  std::optional<double> last_watchdog_trip_s;
  std::optional<double> cut_until_s;
  std::deque<Delayed> delayed;
  std::vector<std::string> held;  // sentences sent but not yet written: a burst in the making
  int burst_lines = 0;            // the size of the burst in the making; 0 until drawn
  std::list<std::shared_ptr<Client>> clients;
  std::uint64_t connections = 0;
  std::uint64_t sentences_sent = 0, sentences_dropped = 0, sentences_corrupted = 0, bursts = 0;
  std::uint64_t lines_received = 0, bad_lines_received = 0, pydir_received = 0;
};

FrontseatEmulator::FrontseatEmulator(FrontseatEmulatorOptions options)
    : impl_(std::make_unique<Impl>(std::move(options))) {
  Impl& i = *impl_;
  net::post(i.io, [&i] {
    i.start_accept();
    i.tick();
  });
  i.thread = std::thread([&i] {
    for (;;) {
      try {
        i.io.run();
        return;
      } catch (const std::exception& e) {
        // Nothing on the thread is meant to throw; log and carry on serving.
        std::fprintf(stderr, "frontseat emulator: %s\n", e.what());
      }
    }
  });
}

FrontseatEmulator::~FrontseatEmulator() {
  stop();
}

unsigned short FrontseatEmulator::port() const {
  return impl_->bound_port;
}

double FrontseatEmulator::now_s() const {
  return impl_->clock.now_s();
}

FrontseatStatus FrontseatEmulator::status() const {
  const Impl& i = *impl_;
  std::lock_guard lock(i.m);
  FrontseatStatus s;
  s.t_s = i.clock.now_s();
  s.truth = i.truth;
  s.left_pct = i.left_pct;
  s.right_pct = i.right_pct;
  s.last_pydir_s = i.last_pydir_s;
  s.watchdog_trips = i.watchdog_trips;
  s.last_watchdog_trip_s = i.last_watchdog_trip_s;
  s.clients = i.clients.size();
  s.connections = i.connections;
  s.sentences_sent = i.sentences_sent;
  s.sentences_dropped = i.sentences_dropped;
  s.sentences_corrupted = i.sentences_corrupted;
  s.bursts = i.bursts;
  s.lines_received = i.lines_received;
  s.bad_lines_received = i.bad_lines_received;
  s.pydir_received = i.pydir_received;
  s.link_cut = i.link_cut_now();
  return s;
}

void FrontseatEmulator::cut_link(double duration_s) {
  if (!(duration_s >= 0.0 && std::isfinite(duration_s)))
    throw std::invalid_argument("cut_link: duration must be finite and >= 0");
  Impl& i = *impl_;
  {
    // Set here rather than on the io thread, so status() reports the cut as soon as this returns
    // and a connection accepted in between is already refused.
    std::lock_guard lock(i.m);
    const double until = i.clock.now_s() + duration_s;
    i.cut_until_s = i.cut_until_s ? std::max(*i.cut_until_s, until) : until;
  }
  net::post(i.io, [&i] {
    std::lock_guard lock(i.m);
    i.close_all_clients();
  });
}

void FrontseatEmulator::set_faults(const FrontseatFaults& faults) {
  check_faults(faults);
  std::lock_guard lock(impl_->m);
  impl_->faults = faults;
}

void FrontseatEmulator::stop() {
  Impl& i = *impl_;
  std::lock_guard stop_lock(i.stop_mutex);
  if (!i.thread.joinable()) return;
  net::post(i.io, [&i] {
    std::lock_guard lock(i.m);
    i.stopped = true;
    error_code ignored;
    i.acceptor.close(ignored);
    i.timer.cancel();
    i.accept_retry.cancel();
    i.close_all_clients();
    // Handlers of the operations just cancelled still hold clients; dropping them unrun is fine.
    i.io.stop();
  });
  i.thread.join();
}

}  // namespace avk::sim
