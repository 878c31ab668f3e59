// The frontseat emulator over real sockets: a raw TCP client on the test's thread reads what the
// emulator sends and writes backseat lines. Every wait polls the emulator's clock or status()
// against a wall-clock deadline; nothing sleeps and hopes. The emulators run at 5-20x real time.
#include <gtest/gtest.h>

#include <algorithm>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <iostream>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <string_view>
#include <thread>
#include <type_traits>
#include <variant>
#include <vector>

#include "kinematics/angles.hpp"
#include "sim/frontseat_emulator.hpp"
#include "support/nmea_sentence.hpp"
#include "vehicle/local_grid.hpp"
#include "vehicle/nmea.hpp"

namespace {

namespace net = boost::asio;
using tcp = net::ip::tcp;
using avk::sim::FrontseatEmulator;
using avk::sim::FrontseatEmulatorOptions;
using avk::sim::FrontseatFaults;
using avk::sim::FrontseatStatus;
namespace veh = avk::vehicle;
namespace kin = avk::kinematics;

struct Received {
  std::string line;
  double at_s = 0.0;  // the emulator's clock when the test read it
};

// A backseat at the byte level: non-blocking, so one thread can poll several of them and the
// emulator between reads.
class RawClient {
 public:
  explicit RawClient(unsigned short port) : socket_(io_) {
    socket_.connect(tcp::endpoint(net::ip::make_address("127.0.0.1"), port));
    socket_.non_blocking(true);
  }

  // Reads whatever has arrived and splits it into lines stamped with now_s.
  void poll(double now_s) {
    if (closed_) return;
    char buf[8192];
    for (;;) {
      boost::system::error_code ec;
      const std::size_t n = socket_.read_some(net::buffer(buf), ec);
      if (ec == net::error::would_block) return;
      if (ec) {
        closed_ = true;
        close_error_ = ec;
        return;
      }
      partial_.append(buf, n);
      for (auto nl = partial_.find('\n'); nl != std::string::npos; nl = partial_.find('\n')) {
        lines_.push_back({partial_.substr(0, nl + 1), now_s});
        partial_.erase(0, nl + 1);
      }
    }
  }

  // Returns false when the emulator has closed the connection.
  bool send(const std::string& text) {
    std::size_t done = 0;
    while (done < text.size()) {
      boost::system::error_code ec;
      done += socket_.write_some(net::buffer(text.data() + done, text.size() - done), ec);
      if (ec == net::error::would_block) {
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      } else if (ec) {
        return false;
      }
    }
    return true;
  }

  bool closed() const { return closed_; }
  const boost::system::error_code& close_error() const { return close_error_; }
  const std::vector<Received>& lines() const { return lines_; }

 private:
  net::io_context io_;
  tcp::socket socket_;
  std::string partial_;
  std::vector<Received> lines_;
  bool closed_ = false;
  boost::system::error_code close_error_;
};

FrontseatEmulatorOptions fast_options(double factor) {
  FrontseatEmulatorOptions o;
  o.port = 0;
  o.realtime_factor = factor;
  o.seed = 7;
  return o;
}

// Polls the clients (and runs `each`) until done() holds or the wall-clock timeout passes.
bool run_until(FrontseatEmulator& emu, const std::vector<RawClient*>& clients,
               const std::function<bool()>& done, const std::function<void()>& each = {},
               double wall_timeout_s = 10.0) {
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                            std::chrono::duration<double>(wall_timeout_s));
  for (;;) {
    for (RawClient* c : clients)
      c->poll(emu.now_s());
    if (each) each();
    if (done()) return true;
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::microseconds(500));
  }
}

bool run_until_clock(FrontseatEmulator& emu, const std::vector<RawClient*>& clients, double t_s,
                     const std::function<void()>& each = {}) {
  return run_until(
      emu, clients, [&] { return emu.now_s() >= t_s; }, each);
}

// Sends a line every period_s of the emulator's clock from the first call on.
struct Repeater {
  RawClient& client;
  std::string line;
  double period_s;
  double next_s = -1.0;
  int sent = 0;
  void operator()(double now_s) {
    if (next_s < 0.0) next_s = now_s;
    if (now_s >= next_s) {
      client.send(line);
      ++sent;
      next_s += period_s;
    }
  }
};

std::string type_of(const veh::NmeaSentence& s) {
  return std::visit(
      [](const auto& v) -> std::string {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, veh::Cpnvg>) return "CPNVG";
        if constexpr (std::is_same_v<T, veh::Cpnvr>) return "CPNVR";
        if constexpr (std::is_same_v<T, veh::Cprbs>) return "CPRBS";
        if constexpr (std::is_same_v<T, veh::Gprmc>) return "GPRMC";
        return "other";
      },
      s);
}

double time_field(const veh::NmeaSentence& s) {
  if (const auto* v = std::get_if<veh::Cpnvg>(&s)) return v->time_s;
  if (const auto* v = std::get_if<veh::Cpnvr>(&s)) return v->time_s;
  if (const auto* v = std::get_if<veh::Cprbs>(&s)) return v->time_s;
  if (const auto* v = std::get_if<veh::Gprmc>(&s)) return v->time_s.value_or(-1.0);
  return -1.0;
}

veh::NmeaParseResult parse_fs(const std::string& line) {
  return veh::parse_sentence(line, veh::NmeaDirection::frontseat_to_backseat);
}

// The same sentence with a checksum that does not match its body.
std::string with_bad_checksum(const std::string& line) {
  std::string out = line;
  const auto star = out.rfind('*');
  const unsigned wrong = veh::nmea_checksum(std::string_view(out).substr(1, star - 1)) ^ 0x5Au;
  char hex[3];
  std::snprintf(hex, sizeof hex, "%02X", wrong);
  out.replace(star + 1, 2, hex);
  return out;
}

// Sentences by type whose time field, on the emulator's clock, lies in [from_s, to_s).
std::map<std::string, int> count_in_window(const std::vector<Received>& lines,
                                           const FrontseatEmulatorOptions& o, double from_s,
                                           double to_s) {
  std::map<std::string, int> n;
  for (const auto& r : lines) {
    const auto p = parse_fs(r.line);
    if (!p.ok()) continue;
    const double t = time_field(*p.sentence()) - o.start_of_day_s;
    if (t >= from_s && t < to_s) ++n[type_of(*p.sentence())];
  }
  return n;
}

double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

TEST(FrontseatEmulator, SendsEverySentenceAtItsRateWellFormed) {
  FrontseatEmulatorOptions o = fast_options(10.0);
  o.start_x_m = 25.0;
  o.start_y_m = -40.0;
  o.start_heading_deg = 30.0;
  FrontseatEmulator emu(o);
  RawClient c(emu.port());
  ASSERT_TRUE(run_until_clock(emu, {&c}, 12.5));

  // Ticks fall on the plant's grid (k / 20 s): windows start half a period off it.
  const double from = 1.9, to = 11.9;
  auto n = count_in_window(c.lines(), o, from, to);
  const double span = to - from;
  std::cout << "rates over " << span << " s of emulator clock: CPNVG " << n["CPNVG"] / span
            << " Hz, CPNVR " << n["CPNVR"] / span << " Hz, GPRMC " << n["GPRMC"] / span
            << " Hz, CPRBS " << n["CPRBS"] / span << " Hz\n";
  EXPECT_NEAR(n["CPNVG"], o.nav_hz * span, 1.0);
  EXPECT_NEAR(n["CPNVR"], o.nav_hz * span, 1.0);
  EXPECT_NEAR(n["GPRMC"], o.nav_hz * span, 1.0);
  EXPECT_NEAR(n["CPRBS"], o.battery_hz * span, 1.0);
  EXPECT_EQ(n["other"], 0);

  const veh::LocalGrid grid(o.datum.lat_deg, o.datum.lon_deg);
  int positions = 0;
  for (const auto& r : c.lines()) {
    ASSERT_GE(r.line.size(), 2u);
    EXPECT_EQ(r.line.substr(r.line.size() - 2), "\r\n") << r.line;
    const auto p = parse_fs(r.line);
    ASSERT_TRUE(p.ok()) << r.line << ": " << p.error()->message;
    EXPECT_EQ(p.checksum, veh::NmeaChecksum::upper_case) << r.line;
    if (const auto* nvg = std::get_if<veh::Cpnvg>(p.sentence())) {
      const veh::GridPoint g = grid.to_grid(nvg->lat_deg, nvg->lon_deg);
      EXPECT_NEAR(g.x_m, o.start_x_m, 2.0) << r.line;
      EXPECT_NEAR(g.y_m, o.start_y_m, 2.0) << r.line;
      EXPECT_NEAR(kin::angle180_deg(nvg->heading_deg - o.start_heading_deg), 0.0, 6.0);
      EXPECT_TRUE(nvg->position_ok);
      EXPECT_FALSE(nvg->altitude_m.has_value());
      EXPECT_FALSE(nvg->depth_m.has_value());
      EXPECT_DOUBLE_EQ(nvg->nav_time_s, nvg->time_s);
      ++positions;
    } else if (const auto* rmc = std::get_if<veh::Gprmc>(p.sentence())) {
      EXPECT_TRUE(rmc->valid);
      ASSERT_TRUE(rmc->lat_deg && rmc->lon_deg && rmc->speed_knots && rmc->date);
      const veh::GridPoint g = grid.to_grid(*rmc->lat_deg, *rmc->lon_deg);
      EXPECT_NEAR(g.x_m, o.start_x_m, 2.0);
      EXPECT_NEAR(g.y_m, o.start_y_m, 2.0);
      EXPECT_NEAR(*rmc->speed_knots, 0.0, 0.01);
    } else if (const auto* bs = std::get_if<veh::Cprbs>(p.sentence())) {
      EXPECT_NEAR(bs->stack_v, o.battery_v, 0.01);  // no thrust, no sag
      EXPECT_LT(bs->min_v, bs->max_v);
      EXPECT_NEAR(bs->max_v, o.battery_v / 4.0, 0.1);
      EXPECT_NEAR(bs->temperature_c, 25.0, 1.0);
    }
  }
  EXPECT_GE(positions, 50);
  const FrontseatStatus s = emu.status();
  EXPECT_EQ(s.connections, 1u);
  EXPECT_EQ(s.clients, 1u);
  EXPECT_EQ(s.watchdog_trips, 0u);  // never commanded: idle motors are not a trip
  EXPECT_FALSE(s.last_pydir_s.has_value());
  EXPECT_EQ(s.left_pct, 0.0);
  EXPECT_EQ(s.right_pct, 0.0);
  EXPECT_GE(s.sentences_sent, 3u * 60u);
}

TEST(FrontseatEmulator, PydirDrivesForwardAndLeftOverRightTurnsToStarboard) {
  FrontseatEmulatorOptions o = fast_options(10.0);
  o.start_heading_deg = 90.0;
  FrontseatEmulator emu(o);
  RawClient c(emu.port());
  Repeater forward{c, veh::format_pydir(60, 60), 0.1};
  ASSERT_TRUE(run_until_clock(emu, {&c}, 6.0, [&] { forward(emu.now_s()); }));
  FrontseatStatus s = emu.status();
  EXPECT_EQ(s.left_pct, 60.0);
  EXPECT_EQ(s.right_pct, 60.0);
  EXPECT_GT(s.truth.speed_over_ground_mps, 0.3);
  EXPECT_GT(s.truth.x_m, 1.0);  // heading 90: east
  EXPECT_NEAR(s.truth.y_m, 0.0, 0.5);
  EXPECT_EQ(s.watchdog_trips, 0u);
  // What it says on the wire agrees: the newest CPNVR moves east.
  veh::Cpnvr last_nvr;
  for (const auto& r : c.lines())
    if (const auto p = parse_fs(r.line); p.ok())
      if (const auto* v = std::get_if<veh::Cpnvr>(p.sentence())) last_nvr = *v;
  EXPECT_GT(last_nvr.v_east_mps, 0.3);

  Repeater turn{c, veh::format_pydir(60, -60), 0.1};
  double previous = s.truth.heading_deg, turned = 0.0, max_rate = 0.0;
  ASSERT_TRUE(run_until_clock(emu, {&c}, 8.0, [&] {
    turn(emu.now_s());
    const FrontseatStatus now = emu.status();
    turned += kin::angle180_deg(now.truth.heading_deg - previous);
    previous = now.truth.heading_deg;
    max_rate = std::max(max_rate, now.truth.yaw_rate_dps);
  }));
  std::cout << "60/-60 for 2 s: heading changed " << turned << " deg, yaw rate up to " << max_rate
            << " deg/s\n";
  // Clockwise: the heading increases. The M200's jets at ±60 % give about 11 N of differential
  // thrust (8 N ahead, 2.8 N through the reversing bucket), so 2 s turn it some 12°.
  EXPECT_GT(turned, 8.0);
  EXPECT_GT(max_rate, 6.0);
  EXPECT_EQ(emu.status().left_pct, 60.0);
  EXPECT_EQ(emu.status().right_pct, -60.0);
}

TEST(FrontseatEmulator, WatchdogZeroesTheMotorsOncePerSilence) {
  FrontseatEmulatorOptions o = fast_options(10.0);
  FrontseatEmulator emu(o);
  RawClient c(emu.port());
  ASSERT_TRUE(run_until_clock(emu, {&c}, 2.0));
  EXPECT_EQ(emu.status().watchdog_trips, 0u);

  // Commands for a second, then silence.
  Repeater drive{c, veh::format_pydir(50, 50), 0.1};
  bool saw_drive = false;
  ASSERT_TRUE(run_until_clock(emu, {&c}, 3.0, [&] {
    drive(emu.now_s());
    saw_drive = saw_drive || emu.status().left_pct == 50.0;
  }));
  ASSERT_TRUE(run_until(emu, {&c}, [&] { return emu.status().watchdog_trips >= 1; }));
  FrontseatStatus s = emu.status();
  EXPECT_TRUE(saw_drive);
  EXPECT_EQ(s.left_pct, 0.0);
  EXPECT_EQ(s.right_pct, 0.0);
  ASSERT_TRUE(s.last_pydir_s && s.last_watchdog_trip_s);
  const double first_trip = *s.last_watchdog_trip_s;
  std::cout << "watchdog tripped " << first_trip - *s.last_pydir_s << " s after the last $PYDIR\n";
  EXPECT_GE(first_trip - *s.last_pydir_s, o.watchdog_s);
  EXPECT_LE(first_trip - *s.last_pydir_s, o.watchdog_s + 0.1);
  // Staying silent does not trip it again.
  ASSERT_TRUE(run_until_clock(emu, {&c}, first_trip + 2.5));
  EXPECT_EQ(emu.status().watchdog_trips, 1u);
  EXPECT_EQ(*emu.status().last_watchdog_trip_s, first_trip);

  // A $PYDIR with a bad checksum is not a command: it neither drives nor feeds the watchdog.
  ASSERT_TRUE(c.send(veh::format_pydir(30, 30)));
  ASSERT_TRUE(run_until(emu, {&c}, [&] { return emu.status().left_pct == 30.0; }));
  const double fed_at = *emu.status().last_pydir_s;
  const std::uint64_t bad_before = emu.status().bad_lines_received;
  Repeater bad{c, with_bad_checksum(veh::format_pydir(20, 20)), 0.1};
  bool obeyed_bad = false;
  ASSERT_TRUE(run_until(
      emu, {&c}, [&] { return emu.status().watchdog_trips >= 2; },
      [&] {
        bad(emu.now_s());
        obeyed_bad = obeyed_bad || emu.status().left_pct == 20.0;
      }));
  s = emu.status();
  EXPECT_FALSE(obeyed_bad);
  EXPECT_EQ(s.watchdog_trips, 2u);
  EXPECT_EQ(*s.last_pydir_s, fed_at);
  EXPECT_GE(*s.last_watchdog_trip_s - fed_at, o.watchdog_s);
  EXPECT_LE(*s.last_watchdog_trip_s - fed_at, o.watchdog_s + 0.1);
  EXPECT_GE(s.bad_lines_received - bad_before, 5u);
  // All but the last few sent, which may still be on their way.
  EXPECT_GE(static_cast<int>(s.bad_lines_received - bad_before), bad.sent - 3);

  // Older backseats leave the checksum out, or its digits: both are commands.
  std::uint64_t trips = 2;
  for (const std::string line : {"$PYDIR,10,10\r\n", "$PYDIR,10,10*\r\n"}) {
    ASSERT_TRUE(c.send(line));
    ASSERT_TRUE(run_until(emu, {&c}, [&] { return emu.status().left_pct == 10.0; })) << line;
    ASSERT_TRUE(run_until(emu, {&c}, [&] { return emu.status().watchdog_trips > trips; })) << line;
    s = emu.status();
    ++trips;
    EXPECT_EQ(s.watchdog_trips, trips) << line;
    EXPECT_EQ(s.left_pct, 0.0);
    EXPECT_GE(*s.last_watchdog_trip_s - *s.last_pydir_s, o.watchdog_s) << line;
    EXPECT_LE(*s.last_watchdog_trip_s - *s.last_pydir_s, o.watchdog_s + 0.1) << line;
  }
}

TEST(FrontseatEmulator, DropsAboutTheConfiguredFraction) {
  FrontseatEmulatorOptions o = fast_options(20.0);
  o.faults.drop_fraction = 0.2;
  FrontseatEmulator emu(o);
  RawClient c(emu.port());
  ASSERT_TRUE(run_until_clock(emu, {&c}, 41.5));
  auto n = count_in_window(c.lines(), o, 0.95, 40.95);
  const int expected = static_cast<int>(std::lround(40.0 * (3 * o.nav_hz + o.battery_hz)));
  const int received = n["CPNVG"] + n["CPNVR"] + n["GPRMC"] + n["CPRBS"];
  const double kept = static_cast<double>(received) / expected;
  std::cout << "drop 0.2: received " << received << " of " << expected << " (" << kept << ")\n";
  // 620 sentences: the binomial sd of the kept fraction is 0.016, so this is 6 sd wide.
  EXPECT_GT(kept, 0.7);
  EXPECT_LT(kept, 0.9);
  for (const auto& r : c.lines())
    EXPECT_TRUE(parse_fs(r.line).ok()) << r.line;
  const FrontseatStatus s = emu.status();
  const double dropped =
      static_cast<double>(s.sentences_dropped) / (s.sentences_sent + s.sentences_dropped);
  EXPECT_GT(dropped, 0.1);
  EXPECT_LT(dropped, 0.3);
  EXPECT_EQ(s.sentences_corrupted, 0u);
}

TEST(FrontseatEmulator, CorruptsAboutTheConfiguredFractionInTheChecksumOnly) {
  FrontseatEmulatorOptions o = fast_options(20.0);
  o.faults.corrupt_fraction = 0.2;
  FrontseatEmulator emu(o);
  RawClient c(emu.port());
  ASSERT_TRUE(run_until_clock(emu, {&c}, 41.0));
  int bad = 0;
  for (const auto& r : c.lines()) {
    const auto p = parse_fs(r.line);
    if (p.ok()) continue;
    ++bad;
    EXPECT_EQ(p.error()->code, veh::NmeaError::Code::bad_checksum) << r.line;
    // Only the checksum was touched: with the right one the sentence reads again.
    const std::string fixed =
        avk::testing::nmea_sentence(std::string_view(r.line).substr(1, r.line.rfind('*') - 1));
    EXPECT_TRUE(parse_fs(fixed).ok()) << fixed;
  }
  const double fraction = static_cast<double>(bad) / c.lines().size();
  std::cout << "corrupt 0.2: " << bad << " of " << c.lines().size() << " fail (" << fraction
            << ")\n";
  EXPECT_GT(c.lines().size(), 550u);
  EXPECT_GT(fraction, 0.1);
  EXPECT_LT(fraction, 0.3);
  const FrontseatStatus s = emu.status();
  EXPECT_EQ(s.sentences_dropped, 0u);
  EXPECT_NEAR(static_cast<double>(s.sentences_corrupted) / s.sentences_sent, 0.2, 0.1);
}

TEST(FrontseatEmulator, NavDelayHoldsNavigationBackButNotTheBattery) {
  FrontseatEmulatorOptions o = fast_options(10.0);
  FrontseatEmulator emu(o);
  RawClient c(emu.port());
  ASSERT_TRUE(run_until_clock(emu, {&c}, 4.0));
  const double switched = emu.now_s();
  emu.set_faults(FrontseatFaults{0.0, 0.0, 1.0});
  ASSERT_TRUE(run_until_clock(emu, {&c}, 12.0));

  // Age of each sentence when read: the emulator's clock minus its time field.
  std::vector<double> nav_before, nav_after, battery_after;
  for (const auto& r : c.lines()) {
    const auto p = parse_fs(r.line);
    ASSERT_TRUE(p.ok());
    const double t = time_field(*p.sentence()) - o.start_of_day_s;
    const double age = r.at_s - t;
    const std::string type = type_of(*p.sentence());
    if (type == "CPNVG" && t >= 1.0 && t < switched - 0.3) nav_before.push_back(age);
    if (type == "CPNVG" && t > switched + 0.3) nav_after.push_back(age);
    if (type == "CPRBS" && t > switched + 0.3) battery_after.push_back(age);
  }
  ASSERT_GE(nav_before.size(), 10u);
  ASSERT_GE(nav_after.size(), 20u);
  ASSERT_GE(battery_after.size(), 2u);
  const double before = median(nav_before), after = median(nav_after);
  std::cout << "CPNVG age when read: " << before << " s undelayed, " << after
            << " s with nav_delay_s 1; CPRBS " << median(battery_after) << " s\n";
  // A loaded machine reads late, which only adds to an age: the bounds from below hold on any
  // machine, and those from above use the freshest sentence of each kind (a reader that was late
  // for every one of dozens of sentences would be a stall of the whole test, not load).
  const auto freshest = [](const std::vector<double>& v) {
    return *std::min_element(v.begin(), v.end());
  };
  EXPECT_GE(freshest(nav_before), -1e-9);
  EXPECT_LT(freshest(nav_before), 0.5);
  // Held back by the delay: never released early, and released when due.
  EXPECT_GE(freshest(nav_after), 1.0 - 1e-9);
  EXPECT_LT(freshest(nav_after), 1.5);
  EXPECT_GT(after - before, 0.5);
  EXPECT_GE(freshest(battery_after), -1e-9);
  EXPECT_LT(freshest(battery_after), 0.5);
  // Time fields still increase: delayed, not reordered.
  double last = -1.0;
  for (const auto& r : c.lines()) {
    const auto p = parse_fs(r.line);
    if (!std::holds_alternative<veh::Cpnvg>(*p.sentence())) continue;
    EXPECT_GT(time_field(*p.sentence()), last);
    last = time_field(*p.sentence());
  }
}

TEST(FrontseatEmulator, BurstsHoldSentencesBackAndWriteTwoToTwentyAtOnce) {
  FrontseatEmulatorOptions o = fast_options(20.0);
  o.faults.burst_max_lines = 20;
  FrontseatEmulator emu(o);
  RawClient c(emu.port());
  ASSERT_TRUE(run_until_clock(emu, {&c}, 30.0));
  const FrontseatStatus s = emu.status();
  ASSERT_GT(c.lines().size(), 300u);
  // Bursts of 2 to 20: between a twentieth and a half as many bursts as sentences.
  EXPECT_GE(s.bursts * 20, s.sentences_sent);
  EXPECT_LE(s.bursts * 2, s.sentences_sent);
  // A burst is one write, so it is read whole: never more reads than bursts, where a sentence
  // at a time would take a read for each plant step.
  std::set<double> reads;
  for (const auto& r : c.lines())
    reads.insert(r.at_s);
  EXPECT_LE(reads.size(), s.bursts);
  // Held back, not reordered: the time fields of each kind still increase.
  std::map<std::string, double> last;
  for (const auto& r : c.lines()) {
    const auto p = parse_fs(r.line);
    ASSERT_TRUE(p.ok()) << r.line;
    const std::string type = type_of(*p.sentence());
    const double t = time_field(*p.sentence());
    if (last.count(type)) {
      EXPECT_GT(t, last[type]) << type;
    }
    last[type] = t;
  }
  EXPECT_THROW(emu.set_faults(FrontseatFaults{0.0, 0.0, 0.0, 101}), std::invalid_argument);
}

TEST(FrontseatEmulator, CutLinkClosesAndRefusesUntilItEnds) {
  FrontseatEmulatorOptions o = fast_options(5.0);
  FrontseatEmulator emu(o);
  RawClient a(emu.port());
  ASSERT_TRUE(run_until(emu, {&a}, [&] { return a.lines().size() >= 3; }));
  EXPECT_EQ(emu.status().clients, 1u);
  EXPECT_FALSE(emu.status().link_cut);

  // A cut of 10 s of emulator clock (2 s of wall time): long enough that closing the open
  // connection and refusing a new one both fall inside it however late a loaded machine runs
  // this thread.
  constexpr double kCutS = 10.0;
  const double cut_at = emu.now_s();
  emu.cut_link(kCutS);
  EXPECT_TRUE(emu.status().link_cut);
  ASSERT_TRUE(run_until(
      emu, {&a}, [&] { return a.closed(); }, {}, 30.0));
  EXPECT_EQ(a.close_error(), net::error::eof) << a.close_error().message();

  // Connecting during the cut: the connection is taken, then closed at once.
  RawClient b(emu.port());
  ASSERT_TRUE(run_until(
      emu, {&b}, [&] { return b.closed(); }, {}, 30.0));
  // Asserted only when the cut was still on, which it is unless this thread stalled for 2 s.
  if (emu.now_s() < cut_at + kCutS) {
    EXPECT_TRUE(b.lines().empty());
    EXPECT_EQ(emu.status().clients, 0u);
  }

  ASSERT_TRUE(run_until(
      emu, {}, [&] { return !emu.status().link_cut; }, {}, 30.0));
  EXPECT_GE(emu.now_s(), cut_at + kCutS);
  RawClient d(emu.port());
  ASSERT_TRUE(run_until(emu, {&d}, [&] {
    for (const auto& r : d.lines())
      if (r.line.rfind("$CPNVG", 0) == 0) return true;
    return false;
  }));
  EXPECT_FALSE(d.closed());
  const FrontseatStatus s = emu.status();
  EXPECT_EQ(s.connections, 3u);
  EXPECT_EQ(s.clients, 1u);
}

TEST(FrontseatEmulator, BadInputIsCountedAndOtherClientsKeepBeingServed) {
  FrontseatEmulatorOptions o = fast_options(10.0);
  FrontseatEmulator emu(o);
  RawClient good(emu.port());
  RawClient bad(emu.port());
  ASSERT_TRUE(run_until(emu, {&good, &bad}, [&] { return emu.status().clients == 2; }));

  ASSERT_TRUE(bad.send("hello frontseat\r\n"));
  ASSERT_TRUE(bad.send(with_bad_checksum(veh::format_pydir(50, 50))));
  ASSERT_TRUE(bad.send(std::string("$PYDIR,\x01\xff,2\r\n")));
  ASSERT_TRUE(bad.send("$PYDIR,500,500\r\n"));            // out of range
  ASSERT_TRUE(bad.send("$PYDEV,90,1\r\n$PYCLT,1\r\n"));   // well-formed: no effect
  ASSERT_TRUE(bad.send(std::string(300, 'x') + "\r\n"));  // too long for a sentence
  ASSERT_TRUE(run_until(emu, {&good, &bad}, [&] { return emu.status().lines_received >= 7; }));
  FrontseatStatus s = emu.status();
  EXPECT_EQ(s.lines_received, 7u);
  EXPECT_EQ(s.bad_lines_received, 5u);
  EXPECT_EQ(s.left_pct, 0.0);
  EXPECT_FALSE(s.last_pydir_s.has_value());
  EXPECT_FALSE(bad.closed());

  // A line that never ends: the emulator hangs up on that client only.
  bad.send(std::string(10000, 'A'));
  ASSERT_TRUE(run_until(emu, {&good, &bad}, [&] { return bad.closed(); }));
  ASSERT_TRUE(run_until(emu, {&good, &bad}, [&] { return emu.status().clients == 1; }));
  EXPECT_EQ(emu.status().bad_lines_received, 6u);

  const std::size_t before = good.lines().size();
  ASSERT_TRUE(good.send(veh::format_pydir(40, 40)));
  ASSERT_TRUE(run_until(emu, {&good}, [&] {
    return good.lines().size() >= before + 10 && emu.status().left_pct == 40.0;
  }));
  EXPECT_FALSE(good.closed());
  EXPECT_EQ(emu.status().connections, 2u);
}

TEST(FrontseatEmulator, RefusesWhatItCannotRun) {
  FrontseatEmulator first(fast_options(10.0));
  FrontseatEmulatorOptions same = fast_options(10.0);
  same.port = first.port();
  try {
    FrontseatEmulator second(same);
    FAIL() << "bound a port already listened on";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("127.0.0.1:" + std::to_string(first.port())),
              std::string::npos)
        << e.what();
  }
  FrontseatEmulatorOptions usim = fast_options(10.0);
  usim.vehicle = avk::sim::sim_vehicle_defaults("usim");
  EXPECT_THROW(FrontseatEmulator{usim}, std::invalid_argument);
  FrontseatEmulatorOptions bad_faults = fast_options(10.0);
  bad_faults.faults.drop_fraction = 1.5;
  EXPECT_THROW(FrontseatEmulator{bad_faults}, std::invalid_argument);
  EXPECT_THROW(first.set_faults(FrontseatFaults{0.0, -0.1, 0.0}), std::invalid_argument);

  // stop() twice, then the destructor: all fine, and the port is free again.
  first.stop();
  first.stop();
  FrontseatEmulator third(same);
  EXPECT_EQ(third.port(), same.port);
}
