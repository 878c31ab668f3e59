// Load on the live stream /api/v1/stream: 100 WebSocket clients subscribed to
// nav while a mission runs, plus one client that subscribes to nav and turn and then never reads.
// The target is p99 delivery latency < 50 ms, and the stalled client must not slow the others.
// A third phase adds heavy reads beside them: --heavy-loops clients on this machine each asking
// for a model fit, the comparison and a held-out prediction one after another (an analyst
// beside the operator); the stream must stay whole (nav per client against nav published, and
// the probes' lag). --repeats R flies the Figure 4-1 mission with R repeats first, so the reads
// have the turns of a long campaign to work on.
//
//   bench_stream_load [--clients N] [--seconds D] [--baseline-seconds B] [--realtime-factor K]
//                     [--quickack] [--heavy-loops L] [--repeats R]
//
// The vehicle loop publishes nav at 10 Hz by itself; its messages carry no send time, so the
// bench publishes its own probes on nav too (10 Hz, {"probe_ns":…}) and the clients take
// receive time - probe_ns. A baseline phase without the stalled client comes first, so its
// effect is a comparison rather than a guess. The clients run asynchronously on one io thread
// in this process, which shares the 2 cores with the server: the latency includes their own
// queueing, as a dashboard's would.
//
// --quickack makes each client acknowledge at once after it sends its subscribe, instead of
// delaying the ACK as Linux does for a peer that just sent data: a diagnostic for whether the
// server's first frames after a client command wait on Nagle's algorithm.

#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/socket.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "bench_station.hpp"
#include "server/cli/cli.hpp"
#include "server/http/http_server.hpp"
#include "server/station.hpp"
#include "sim/sim_config.hpp"
#include "store/store.hpp"
#include "stream_load_clients.hpp"
#include "stream_load_reads.hpp"
#include "support/temp_db.hpp"
#include "support/ws_client.hpp"

namespace {

namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
namespace net = boost::asio;
using tcp = net::ip::tcp;
using json = nlohmann::json;
using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;
using namespace avk::bench;

constexpr const char* kVehicle = kStreamLoadVehicle;
constexpr const char* kToken = kStreamLoadToken;
constexpr int kProbeHz = 10;

struct Options {
  int clients = 100;
  double seconds = 20.0;
  double baseline_seconds = 5.0;
  double realtime_factor = 1.0;
  bool quickack = false;
  int heavy_loops = 4;
  int repeats = 1;
};

Options parse_options(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto value = [&]() -> double {
      if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
      return std::stod(argv[++i]);
    };
    if (a == "--clients")
      o.clients = static_cast<int>(value());
    else if (a == "--seconds")
      o.seconds = value();
    else if (a == "--baseline-seconds")
      o.baseline_seconds = value();
    else if (a == "--realtime-factor")
      o.realtime_factor = value();
    else if (a == "--quickack")
      o.quickack = true;
    else if (a == "--heavy-loops")
      o.heavy_loops = static_cast<int>(value());
    else if (a == "--repeats")
      o.repeats = static_cast<int>(value());
    else
      throw std::invalid_argument("unknown option " + a +
                                  " (--clients N, --seconds D, --baseline-seconds B, "
                                  "--realtime-factor K, --quickack, --heavy-loops L, --repeats R)");
  }
  // Bounded so that a typo cannot start an endless or descriptor-exhausting run.
  if (o.clients < 1 || o.clients > 1000) throw std::invalid_argument("--clients: 1..1000");
  if (!(o.seconds >= 1.0 && o.seconds <= 120.0)) throw std::invalid_argument("--seconds: 1..120");
  if (!(o.baseline_seconds >= 0.0 && o.baseline_seconds <= 60.0))
    throw std::invalid_argument("--baseline-seconds: 0..60");
  if (!(o.realtime_factor > 0.0 && o.realtime_factor <= 1000.0))
    throw std::invalid_argument("--realtime-factor: (0, 1000]");
  if (o.heavy_loops < 0 || o.heavy_loops > 64) throw std::invalid_argument("--heavy-loops: 0..64");
  if (o.repeats < 1 || o.repeats > 200) throw std::invalid_argument("--repeats: 1..200");
  return o;
}

double percentile_ms(const std::vector<std::int64_t>& sorted, double q) {
  if (sorted.empty()) return 0.0;
  const auto i = static_cast<std::size_t>(q * static_cast<double>(sorted.size() - 1) + 0.5);
  return static_cast<double>(sorted[std::min(i, sorted.size() - 1)]) * 1e-6;
}

std::string read_file(const std::string& path) {
  std::ifstream f(path);
  if (!f) throw std::runtime_error("cannot read " + path);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// Publishes probes on nav at kProbeHz for `seconds`, numbering them from `first`.
std::size_t publish_probes(avk::server::StreamHub& hub, int phase, double seconds,
                           std::size_t first, Clock::time_point bench_start) {
  const auto count = static_cast<std::size_t>(seconds * kProbeHz);
  const auto t0 = Clock::now();
  for (std::size_t i = 0; i < count; ++i) {
    std::this_thread::sleep_until(t0 + i * std::chrono::milliseconds(1000 / kProbeHz));
    const std::string data = R"({"probe_ns":)" + std::to_string(now_ns()) + R"(,"probe":)" +
                             std::to_string(first + i) + R"(,"phase":)" + std::to_string(phase) +
                             "}";
    hub.publish("nav", std::chrono::duration<double>(Clock::now() - bench_start).count(), data);
  }
  return count;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  try {
    o = parse_options(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "bench_stream_load: " << e.what() << "\n";
    return 2;
  }
  const auto bench_start = Clock::now();
  const std::string config_path = std::string(AVK_SOURCE_DIR) + "/examples/thesis-fig4-1.json";

  avk::bench::BenchStation bench_station("avk_bench_stream_load", kToken, o.realtime_factor,
                                         o.repeats);
  auto& hub = bench_station.hub;
  auto& station = *bench_station.station;
  auto& server = *bench_station.http;
  const unsigned short port = server.port();

  // The stalled phase, and the heavy-read phase after it when there is one, last o.seconds each.
  const auto probes_total =
      static_cast<std::size_t>(o.baseline_seconds * kProbeHz) +
      static_cast<std::size_t>(o.seconds * kProbeHz) * (o.heavy_loops > 0 ? 2 : 1);
  net::io_context ioc;
  auto work = net::make_work_guard(ioc);
  std::thread io([&] { ioc.run(); });
  std::atomic<int> subscribed{0};
  std::vector<std::shared_ptr<Client>> clients;
  for (int i = 0; i < o.clients; ++i) {
    clients.push_back(std::make_shared<Client>(ioc, port, probes_total, subscribed, o.quickack));
    net::post(ioc, [c = clients.back()] { c->start(); });
  }
  const auto subscribe_deadline = Clock::now() + 15s;
  while (subscribed.load() < o.clients && Clock::now() < subscribe_deadline)
    std::this_thread::sleep_for(5ms);
  const double subscribe_s = std::chrono::duration<double>(Clock::now() - bench_start).count();
  int exit_code = 0;
  if (subscribed.load() < o.clients) {
    std::printf("only %d of %d clients subscribed within 15 s\n", subscribed.load(), o.clients);
    exit_code = 1;
  }

  // The mission makes the server record turns and publish mission/turn events meanwhile.
  const auto [mission_status, mission_body] =
      http_call(port, http::verb::post, std::string("/api/v1/vehicles/") + kVehicle + "/missions",
                read_file(config_path));
  std::int64_t mission_id = 0;
  if (mission_status == 201) {
    mission_id = json::parse(mission_body)["id"].get<std::int64_t>();
  } else {
    std::printf("POST mission: %d %s\n", mission_status, mission_body.c_str());
    exit_code = 1;
  }

  std::size_t probes_sent = 0;
  std::array<std::size_t, kPhases> probes_in_phase{};
  g_phase = 0;
  probes_in_phase[0] = publish_probes(hub, 0, o.baseline_seconds, probes_sent, bench_start);
  probes_sent += probes_in_phase[0];

  std::optional<StalledClient> stalled;
  std::string stalled_failure;
  try {
    stalled.emplace(port);
  } catch (const std::exception& e) {
    stalled_failure = e.what();
    exit_code = 1;
  }
  // The stalled client is the only turn subscriber: the hub's count shows it arrived, and later
  // whether the server dropped it.
  for (const auto until = Clock::now() + 5s;
       hub.subscriber_count("turn") == 0 && Clock::now() < until;)
    std::this_thread::sleep_for(5ms);
  const std::size_t stalled_subscribed = hub.subscriber_count("turn");

  std::array<std::uint64_t, kPhases> nav_in_phase{};
  std::uint64_t nav_before = hub.published("nav");
  nav_in_phase[0] = nav_before;  // the baseline's: since the start (the hub counts from there)
  g_phase = 1;
  probes_in_phase[1] = publish_probes(hub, 1, o.seconds, probes_sent, bench_start);
  probes_sent += probes_in_phase[1];
  nav_in_phase[1] = hub.published("nav") - nav_before;
  nav_before = hub.published("nav");
  HeavyReads heavy;
  std::string heavy_answers = " (none: --heavy-loops 0)";
  if (o.heavy_loops > 0) {
    heavy.start(port, o.heavy_loops, 1);
    g_phase = 2;
    probes_in_phase[2] = publish_probes(hub, 2, o.seconds, probes_sent, bench_start);
    probes_sent += probes_in_phase[2];
    nav_in_phase[2] = hub.published("nav") - nav_before;
  }
  // Let the last probes arrive before the numbers are read.
  std::this_thread::sleep_for(500ms);
  g_phase = -1;
  if (o.heavy_loops > 0) heavy_answers = heavy.finish();
  const std::size_t stalled_still_subscribed = hub.subscriber_count("turn");
  const std::size_t open_sessions = server.open_stream_sessions();
  const auto turns_published = hub.published("turn");
  const auto nav_published = hub.published("nav");
  std::string mission_state = "?";
  std::size_t mission_turns = 0;
  if (mission_id > 0) {
    const auto m =
        http_call(port, http::verb::get, "/api/v1/missions/" + std::to_string(mission_id));
    if (m.first == 200) mission_state = json::parse(m.second).value("status", "?");
    const auto t = http_call(port, http::verb::get,
                             "/api/v1/turns?mission=" + std::to_string(mission_id) + "&limit=1000");
    if (t.first == 200) mission_turns = json::parse(t.second)["items"].size();
  }

  StalledClient::Drain drained;
  if (stalled) drained = stalled->drain(nav_published, 5000ms);

  // Close every client; the websocket's handshake timeout bounds each close, and the io thread
  // is stopped outright if that still does not end it.
  for (auto& c : clients)
    net::post(ioc, [c] { c->close(); });
  work.reset();
  for (const auto until = Clock::now() + 8s; !ioc.stopped() && Clock::now() < until;)
    std::this_thread::sleep_for(10ms);
  ioc.stop();
  io.join();

  std::printf(
      "bench_stream_load: %d clients subscribed to nav %.2f s after the start; mission %lld posted "
      "(%d)\n",
      subscribed.load(), subscribe_s, static_cast<long long>(mission_id), mission_status);
  std::printf("\n%-22s %7s %7s %9s %13s %13s %7s %7s %7s %9s %9s\n", "phase", "seconds", "probes",
              "nav", "msgs/client", "nav/client", "p50 ms", "p99 ms", "max ms", "missed",
              "clients");
  std::printf("%-22s %7s %7s %9s %13s %13s %7s %7s %7s %9s %9s\n", "", "", "sent", "published",
              "min/mean", "min/mean", "", "", "", "probes", "missing");
  // Probe ids run on from phase to phase: where each phase's begin.
  std::array<std::size_t, kPhases + 1> first_probe{};
  for (int p = 0; p < kPhases; ++p)
    first_probe[static_cast<std::size_t>(p) + 1] =
        first_probe[static_cast<std::size_t>(p)] + probes_in_phase[static_cast<std::size_t>(p)];
  for (int p = 0; p < kPhases; ++p) {
    if (probes_in_phase[static_cast<std::size_t>(p)] == 0) continue;
    std::vector<std::int64_t> lat;
    std::uint64_t min_msgs = UINT64_MAX, min_nav = UINT64_MAX, sum_msgs = 0, sum_nav = 0;
    std::size_t missed = 0, clients_missing = 0;
    const std::size_t first = first_probe[static_cast<std::size_t>(p)];
    const std::size_t last = first_probe[static_cast<std::size_t>(p) + 1];
    for (const auto& c : clients) {
      const auto& s = c->phase[static_cast<std::size_t>(p)];
      lat.insert(lat.end(), s.latency_ns.begin(), s.latency_ns.end());
      min_msgs = std::min(min_msgs, s.messages);
      min_nav = std::min(min_nav, s.nav);
      sum_msgs += s.messages;
      sum_nav += s.nav;
      std::size_t m = 0;
      for (std::size_t i = first; i < last; ++i)
        m += c->got_probe[i] ? 0 : 1;
      missed += m;
      clients_missing += m ? 1 : 0;
    }
    std::sort(lat.begin(), lat.end());
    const double n = static_cast<double>(clients.size());
    char msgs[32], nav[32];
    std::snprintf(msgs, sizeof msgs, "%llu/%.1f", static_cast<unsigned long long>(min_msgs),
                  static_cast<double>(sum_msgs) / n);
    std::snprintf(nav, sizeof nav, "%llu/%.1f", static_cast<unsigned long long>(min_nav),
                  static_cast<double>(sum_nav) / n);
    std::printf("%-22s %7.1f %7zu %9llu %13s %13s %7.2f %7.2f %7.2f %9zu %9zu\n", kPhaseNames[p],
                static_cast<double>(probes_in_phase[static_cast<std::size_t>(p)]) / kProbeHz,
                probes_in_phase[static_cast<std::size_t>(p)],
                static_cast<unsigned long long>(nav_in_phase[static_cast<std::size_t>(p)]), msgs,
                nav, percentile_ms(lat, 0.5), percentile_ms(lat, 0.99),
                lat.empty() ? 0.0 : static_cast<double>(lat.back()) * 1e-6, missed,
                clients_missing);
  }
  // Which probes were slow, and for how many clients: one slow publish (all clients late) is a
  // stall on the server or the io thread, scattered ones are scheduling.
  std::vector<std::pair<std::int64_t, std::size_t>> worst;  // (max latency over clients, probe)
  for (std::size_t i = 0; i < probes_sent; ++i) {
    std::int64_t m = -1;
    for (const auto& c : clients)
      m = std::max(m, c->probe_latency_ns[i]);
    worst.emplace_back(m, i);
  }
  std::sort(worst.rbegin(), worst.rend());
  std::printf(
      "\nslowest probes (id, phase, s into the phase: latest client ms, clients over 10 ms):");
  for (std::size_t k = 0; k < worst.size() && k < 5; ++k) {
    const std::size_t i = worst[k].second;
    std::size_t over = 0;
    for (const auto& c : clients)
      over += c->probe_latency_ns[i] > 10'000'000 ? 1 : 0;
    std::size_t p = 0;
    while (p + 1 < kPhases && i >= first_probe[p + 1])
      ++p;
    std::printf("\n  #%zu, %s, %.1f s: %.2f ms, %zu", i, kPhaseNames[p],
                static_cast<double>(i - first_probe[p]) / kProbeHz,
                static_cast<double>(worst[k].first) * 1e-6, over);
  }
  std::printf("\n");
  std::uint64_t gaps = 0, max_gaps = 0;
  std::size_t clients_with_gaps = 0, ended_early = 0;
  for (const auto& c : clients) {
    gaps += c->nav_seq_gaps;
    max_gaps = std::max(max_gaps, c->nav_seq_gaps);
    clients_with_gaps += c->nav_seq_gaps ? 1 : 0;
    if (!c->failure.empty()) {
      ++ended_early;
      if (ended_early == 1) std::printf("client failure: %s\n", c->failure.c_str());
    }
  }
  std::printf(
      "\nnav published: %llu (vehicle + %zu probes); nav seq gaps over the whole run: %llu in "
      "total, %zu clients with any, at most %llu for one client (latest-value-wins may drop)\n",
      static_cast<unsigned long long>(nav_published), probes_sent,
      static_cast<unsigned long long>(gaps), clients_with_gaps,
      static_cast<unsigned long long>(max_gaps));
  std::printf("mission %lld: %s, %zu turns stored, %llu turn events published\n",
              static_cast<long long>(mission_id), mission_state.c_str(), mission_turns,
              static_cast<unsigned long long>(turns_published));
  if (!stalled_failure.empty()) {
    std::printf("stalled client: %s\n", stalled_failure.c_str());
  } else {
    const std::string ended = drained.caught_up ? "it caught up with the live stream (still open)"
                              : drained.end == beast::error::timeout
                                  ? "nothing more within 5 s (still open)"
                                  : "the connection ended: " + drained.end.message();
    std::printf(
        "stalled client: subscribed=%zu, still subscribed after the run=%zu, open stream "
        "sessions=%zu of %d.\n  Reading afterwards: %llu messages buffered (%llu turn; nav seq "
        "%llu..%llu, %llu skipped by latest-value-wins, %llu published); %s",
        stalled_subscribed, stalled_still_subscribed, open_sessions, o.clients + 1,
        static_cast<unsigned long long>(drained.messages),
        static_cast<unsigned long long>(drained.turn_messages),
        static_cast<unsigned long long>(drained.first_nav_seq),
        static_cast<unsigned long long>(drained.last_nav_seq),
        static_cast<unsigned long long>(drained.nav_gaps),
        static_cast<unsigned long long>(nav_published), ended.c_str());
    if (drained.close)
      std::printf(", close code %d \"%s\"", static_cast<int>(drained.close->code),
                  std::string(drained.close->reason.data(), drained.close->reason.size()).c_str());
    std::printf("\n");
  }
  std::printf("heavy reads (%d loops: model fit, compare, held-out predict), answers:%s\n",
              o.heavy_loops, heavy_answers.c_str());
  std::printf(
      "target: p99 < 50 ms, and neither the stalled client nor the heavy reads slow the "
      "others\n");

  server.stop();
  station.shutdown();
  return ended_early > 0 ? 1 : exit_code;
}
