// avk traffic: a simulated traffic source for the simulator deployment (docs/ais.md). The
// contacts of a scenario file move on their tracks and are sent as AIVDM sentences over UDP to
// gpsd (`gpsd udp://HOST:PORT`), so the station reads simulated traffic through the same path as
// a real AIS receiver's. Runs until SIGINT/SIGTERM or --duration.
#include <signal.h>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/udp.hpp>
#include <cmath>
#include <ctime>
#include <ostream>

#include "server/cli/args.hpp"
#include "server/cli/commands.hpp"
#include "server/cli/files.hpp"
#include "server/cli/sim_options.hpp"
#include "sim/ais_traffic.hpp"

namespace avk::server {

namespace {

namespace net = boost::asio;

// Static data (names) go out this often: a station that starts later learns the names within it.
constexpr double kStaticEveryS = 30.0;

net::ip::udp::endpoint endpoint_from(const std::string& text) {
  const auto colon = text.rfind(':');
  if (colon == std::string::npos || colon == 0)
    throw UsageError("--udp " + text + ": expected HOST:PORT (e.g. 127.0.0.1:10110)");
  const std::string host = text.substr(0, colon);
  const std::string port = text.substr(colon + 1);
  try {
    net::io_context io;
    net::ip::udp::resolver r(io);
    const auto found = r.resolve(net::ip::udp::v4(), host, port);
    if (found.empty()) throw UsageError("--udp " + text + ": unknown host");
    return *found.begin();
  } catch (const boost::system::system_error& e) {
    throw UsageError("--udp " + text + ": " + e.what());
  }
}

}  // namespace

int cmd_traffic(const std::vector<std::string>& args, Io& io) {
  const Args a(args, {"scenario", "udp", "interval", "realtime-factor", "duration"});
  if (!a.positional().empty()) throw UsageError("unexpected argument '" + a.positional()[0] + "'");
  const auto scenario = a.get("scenario");
  if (!scenario)
    throw UsageError("--scenario FILE is required (e.g. examples/traffic-charles.json)");
  const auto where = a.get("udp");
  if (!where) throw UsageError("--udp HOST:PORT is required: where gpsd listens for AIVDM");
  const double interval_s = a.number("interval").value_or(2.0);
  if (!(interval_s >= 0.1 && interval_s <= 60.0))
    throw UsageError("--interval must be in [0.1, 60] s");
  const double factor = realtime_factor_from(a);
  const double duration_s = a.number("duration").value_or(0.0);
  if (!(duration_s >= 0.0) || !std::isfinite(duration_s))
    throw UsageError("--duration must be a time of 0 s (no end) or more");
  sim::AisTraffic traffic = [&] {
    try {
      return sim::AisTraffic::parse(read_file(*scenario, io.in));
    } catch (const std::exception& e) {
      throw std::runtime_error(*scenario + ": " + e.what());
    }
  }();
  const auto to = endpoint_from(*where);
  net::io_context ioc;
  net::ip::udp::socket socket(ioc, net::ip::udp::v4());
  const auto send = [&](const std::vector<std::string>& lines) {
    for (const auto& line : lines) {
      boost::system::error_code ec;
      socket.send_to(net::buffer(line), to, 0, ec);  // gpsd not there yet: the next round tells
    }
  };

  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  io.out << "traffic: " << traffic.contacts().size() << " contacts of " << *scenario
         << " as AIVDM to udp://" << *where << " every " << interval_s << " s (scenario clock x"
         << factor << ")" << std::endl;
  double last_static_s = -kStaticEveryS;
  int received = 0;
  for (double t = 0.0; duration_s == 0.0 || t <= duration_s; t += interval_s) {
    if (t - last_static_s >= kStaticEveryS) {
      send(traffic.static_sentences());
      last_static_s = t;
    }
    send(traffic.position_sentences(t));
    // The wait is the scenario's interval on the wall clock; a signal ends it at once.
    const double wait_s = interval_s / factor;
    timespec ts{static_cast<time_t>(wait_s),
                static_cast<long>((wait_s - std::floor(wait_s)) * 1e9)};
    received = sigtimedwait(&signals, nullptr, &ts);
    if (received > 0) break;
  }
  pthread_sigmask(SIG_UNBLOCK, &signals, nullptr);
  if (received > 0) io.err << "traffic: " << (received == SIGINT ? "SIGINT" : "SIGTERM") << "\n";
  return 0;
}

}  // namespace avk::server
