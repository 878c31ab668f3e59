#pragma once
// A backseat's end of the frontseat emulator's link for tests: a raw non-blocking TCP client, waits
// that poll the emulator's clock or status() against a wall-clock deadline (nothing sleeps and
// hopes), and readers of the sentences by type, time field and window.

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

namespace avk::testing::frontseat_link {

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

inline FrontseatEmulatorOptions fast_options(double factor) {
  FrontseatEmulatorOptions o;
  o.port = 0;
  o.realtime_factor = factor;
  o.seed = 7;
  return o;
}

// Polls the clients (and runs `each`) until done() holds or the wall-clock timeout passes.
inline bool run_until(FrontseatEmulator& emu, const std::vector<RawClient*>& clients,
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

inline bool run_until_clock(FrontseatEmulator& emu, const std::vector<RawClient*>& clients,
                            double t_s, const std::function<void()>& each = {}) {
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

inline std::string type_of(const veh::NmeaSentence& s) {
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

inline double time_field(const veh::NmeaSentence& s) {
  if (const auto* v = std::get_if<veh::Cpnvg>(&s)) return v->time_s;
  if (const auto* v = std::get_if<veh::Cpnvr>(&s)) return v->time_s;
  if (const auto* v = std::get_if<veh::Cprbs>(&s)) return v->time_s;
  if (const auto* v = std::get_if<veh::Gprmc>(&s)) return v->time_s.value_or(-1.0);
  return -1.0;
}

inline veh::NmeaParseResult parse_fs(const std::string& line) {
  return veh::parse_sentence(line, veh::NmeaDirection::frontseat_to_backseat);
}

// The same sentence with a checksum that does not match its body.
inline std::string with_bad_checksum(const std::string& line) {
  std::string out = line;
  const auto star = out.rfind('*');
  const unsigned wrong = veh::nmea_checksum(std::string_view(out).substr(1, star - 1)) ^ 0x5Au;
  char hex[3];
  std::snprintf(hex, sizeof hex, "%02X", wrong);
  out.replace(star + 1, 2, hex);
  return out;
}

// Sentences by type whose time field, on the emulator's clock, lies in [from_s, to_s).
inline std::map<std::string, int> count_in_window(const std::vector<Received>& lines,
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

}  // namespace avk::testing::frontseat_link
