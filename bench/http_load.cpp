// Load on GET /api/v1/vehicles/{vid}/predict: the real station and HTTP server
// in-process on loopback, K client threads with one keep-alive connection each, requests back to
// back. The target is >= 20,000 requests/s on 2 cores with p99 < 5 ms. A third pass reads the
// dashboard's index.html (the repository's web/) the same way, to compare with another server on
// the same file. A plain program rather than a Google Benchmark: a load generator measures
// throughput and a latency distribution over a fixed time, not the time of one repeated call.
//
//   bench_http_load [--clients K] [--seconds D]
//
// The clients share the machine with the server, so the figures are for both together; the
// table shows how much CPU the clients took.

#include <sys/socket.h>
#include <time.h>

#include <algorithm>
#include <atomic>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <iostream>
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
#include "support/temp_db.hpp"

namespace {

namespace beast = boost::beast;
namespace http = beast::http;
namespace net = boost::asio;
using tcp = net::ip::tcp;
using Clock = std::chrono::steady_clock;

constexpr const char* kVehicle = "sim-usim";

struct Options {
  int clients = 4;
  double seconds = 10.0;
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
    else
      throw std::invalid_argument("unknown option " + a + " (--clients K, --seconds D)");
  }
  // Bounded so that a typo cannot start an endless or machine-filling run.
  if (o.clients < 1 || o.clients > 256) throw std::invalid_argument("--clients: 1..256");
  if (!(o.seconds > 0.0 && o.seconds <= 120.0)) throw std::invalid_argument("--seconds: (0, 120]");
  return o;
}

double thread_cpu_s() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + static_cast<double>(ts.tv_nsec) * 1e-9;
}

double process_cpu_s() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + static_cast<double>(ts.tv_nsec) * 1e-9;
}

// Cheap and per thread: the targets must differ from request to request so that nothing along
// the way can serve one cached answer, but the generator must not cost the server its CPU.
struct Lcg {
  std::uint64_t s;
  std::uint32_t next() {
    s = s * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<std::uint32_t>(s >> 33);
  }
  std::uint32_t below(std::uint32_t n) { return next() % n; }
};

std::string predict_target(Lcg& rng, bool placed) {
  char buf[200];
  const double speed = 0.5 + 0.01 * rng.below(101);  // 0.50 .. 1.50
  const int dheading = static_cast<int>(10 + rng.below(151)) * (rng.below(2) ? 1 : -1);
  int n = std::snprintf(buf, sizeof buf,
                        "/api/v1/vehicles/%s/predict?method=avk&speed=%.2f&dheading=%d", kVehicle,
                        speed, dheading);
  if (placed)
    std::snprintf(buf + n, sizeof buf - static_cast<std::size_t>(n), "&x=%.1f&y=%.1f&heading=%u",
                  -100.0 + 0.1 * rng.below(2001), -100.0 + 0.1 * rng.below(2001), rng.below(360));
  return buf;
}

struct ClientResult {
  std::vector<std::int64_t> latency_ns;  // of the measured requests only
  std::uint64_t errors = 0;              // non-200 answers in the measured window
  std::uint64_t bytes = 0;               // response bodies in the measured window
  std::vector<double> slow_at_s;         // when (since measure_from) requests over 5 ms started
  std::string failure;                   // a transport error that ended the client
  double cpu_s = 0.0;                    // this client thread's CPU time in the measured window
};

// One keep-alive connection, synchronous requests back to back until `stop`. Requests that
// start before `measure_from` are the warm-up and are not counted.
// What a pass asks for.
enum class Target { predict, predict_placed, index_html };

void run_client(unsigned short port, Target target, std::uint64_t seed,
                Clock::time_point measure_from, Clock::time_point stop, std::atomic<int>& fd_out,
                ClientResult& out) {
  net::io_context ioc;
  beast::tcp_stream stream(ioc);
  Lcg rng{seed};
  double cpu0 = 0.0;
  bool measuring = false;
  try {
    stream.connect(tcp::endpoint(net::ip::make_address("127.0.0.1"), port));
    stream.socket().set_option(tcp::no_delay(true));
    fd_out = stream.socket().native_handle();
    beast::flat_buffer buffer;
    http::request<http::empty_body> req{http::verb::get, "/", 11};
    req.set(http::field::host, "127.0.0.1:" + std::to_string(port));
    req.keep_alive(true);
    out.latency_ns.reserve(1 << 20);
    for (;;) {
      const auto t0 = Clock::now();
      if (t0 >= stop) break;
      if (!measuring && t0 >= measure_from) {
        measuring = true;
        cpu0 = thread_cpu_s();
      }
      req.target(target == Target::index_html
                     ? std::string("/index.html")
                     : predict_target(rng, target == Target::predict_placed));
      http::write(stream, req);
      http::response<http::string_body> res;
      http::read(stream, buffer, res);
      const auto t1 = Clock::now();
      if (!measuring) continue;
      const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(t1 - t0).count();
      out.latency_ns.push_back(ns);
      // When the slow ones happen tells a periodic server stall from scheduling noise.
      if (ns > 5'000'000)
        out.slow_at_s.push_back(std::chrono::duration<double>(t0 - measure_from).count());
      if (res.result_int() != 200) {
        if (out.errors++ == 0) out.failure = "first non-200: " + res.body().substr(0, 200);
      }
      out.bytes += res.body().size();
      if (!res.keep_alive())
        throw std::runtime_error("the server closed the keep-alive connection");
    }
  } catch (const std::exception& e) {
    out.failure = e.what();
  }
  if (measuring) out.cpu_s = thread_cpu_s() - cpu0;
  fd_out = -1;
  beast::error_code ec;
  stream.socket().shutdown(tcp::socket::shutdown_both, ec);
  stream.socket().close(ec);
}

double percentile_ms(const std::vector<std::int64_t>& sorted, double q) {
  if (sorted.empty()) return 0.0;
  const auto i = static_cast<std::size_t>(q * static_cast<double>(sorted.size() - 1) + 0.5);
  return static_cast<double>(sorted[std::min(i, sorted.size() - 1)]) * 1e-6;
}

struct PassResult {
  std::string name;
  std::uint64_t requests = 0;
  std::uint64_t errors = 0;
  double seconds = 0.0;
  double p50 = 0, p90 = 0, p99 = 0, max = 0;
  double mean_body_bytes = 0.0;
  double process_cpu_s = 0.0;
  double client_cpu_s = 0.0;
  std::vector<std::string> failures;
  std::vector<double> slow_at_s;
};

PassResult run_pass(const std::string& name, unsigned short port, const Options& o, Target target) {
  std::vector<ClientResult> results(static_cast<std::size_t>(o.clients));
  std::vector<std::atomic<int>> fds(static_cast<std::size_t>(o.clients));
  for (auto& f : fds)
    f = -1;
  const auto begin = Clock::now();
  const auto measure_from = begin + std::chrono::seconds(1);
  const auto stop = measure_from + std::chrono::duration_cast<Clock::duration>(
                                       std::chrono::duration<double>(o.seconds));
  std::vector<std::thread> threads;
  for (int i = 0; i < o.clients; ++i)
    threads.emplace_back(run_client, port, target,
                         0x9e3779b97f4a7c15ULL * (i + 1) + static_cast<std::uint64_t>(target),
                         measure_from, stop, std::ref(fds[static_cast<std::size_t>(i)]),
                         std::ref(results[static_cast<std::size_t>(i)]));
  std::this_thread::sleep_until(measure_from);
  const double cpu0 = process_cpu_s();
  std::this_thread::sleep_until(stop);
  const double cpu1 = process_cpu_s();
  // A client blocked on a server that stopped answering would never return on its own: past the
  // grace time its socket is shut down under it, which ends the blocking read with an error.
  const auto grace = stop + std::chrono::seconds(5);
  for (std::size_t i = 0; i < threads.size(); ++i) {
    while (fds[i].load() >= 0 && Clock::now() < grace)
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    if (const int fd = fds[i].load(); fd >= 0) ::shutdown(fd, SHUT_RDWR);
    threads[i].join();
  }

  PassResult r;
  r.name = name;
  r.seconds = o.seconds;
  r.process_cpu_s = cpu1 - cpu0;
  std::vector<std::int64_t> all;
  std::uint64_t bytes = 0;
  for (auto& c : results) {
    all.insert(all.end(), c.latency_ns.begin(), c.latency_ns.end());
    r.errors += c.errors;
    bytes += c.bytes;
    r.client_cpu_s += c.cpu_s;
    r.slow_at_s.insert(r.slow_at_s.end(), c.slow_at_s.begin(), c.slow_at_s.end());
    if (!c.failure.empty()) r.failures.push_back(c.failure);
  }
  std::sort(all.begin(), all.end());
  std::sort(r.slow_at_s.begin(), r.slow_at_s.end());
  r.requests = all.size();
  r.p50 = percentile_ms(all, 0.50);
  r.p90 = percentile_ms(all, 0.90);
  r.p99 = percentile_ms(all, 0.99);
  r.max = all.empty() ? 0.0 : static_cast<double>(all.back()) * 1e-6;
  r.mean_body_bytes =
      all.empty() ? 0.0 : static_cast<double>(bytes) / static_cast<double>(all.size());
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  try {
    o = parse_options(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "bench_http_load: " << e.what() << "\n";
    return 2;
  }

  const auto t_setup = Clock::now();
  avk::bench::BenchStation bench_station("avk_bench_http_load", "bench-http-load-token", 1.0);
  auto& station = *bench_station.station;
  auto& server = *bench_station.http;
  const double setup_s = std::chrono::duration<double>(Clock::now() - t_setup).count();

  std::printf(
      "bench_http_load: %d clients x %.1f s per pass (+1 s warm-up), server: 2 io threads, "
      "%u hardware threads, setup %.1f s\n",
      o.clients, o.seconds, std::thread::hardware_concurrency(), setup_s);
  std::vector<PassResult> passes;
  passes.push_back(run_pass("predict (normalized)", server.port(), o, Target::predict));
  passes.push_back(
      run_pass("predict (placed x,y,heading)", server.port(), o, Target::predict_placed));
  passes.push_back(run_pass("static /index.html", server.port(), o, Target::index_html));

  std::printf("\n%-30s %9s %6s %9s %7s %7s %7s %7s %7s %7s %7s %8s\n", "pass", "requests", "errors",
              "req/s", "p50 ms", "p90 ms", "p99 ms", "max ms", ">5 ms", "body B", "cpu s",
              "client s");
  for (const auto& p : passes)
    std::printf("%-30s %9llu %6llu %9.0f %7.3f %7.3f %7.3f %7.2f %7zu %7.0f %7.2f %8.2f\n",
                p.name.c_str(), static_cast<unsigned long long>(p.requests),
                static_cast<unsigned long long>(p.errors),
                static_cast<double>(p.requests) / p.seconds, p.p50, p.p90, p.p99, p.max,
                p.slow_at_s.size(), p.mean_body_bytes, p.process_cpu_s, p.client_cpu_s);
  for (const auto& p : passes) {
    if (p.slow_at_s.empty()) continue;
    std::printf("%s: requests over 5 ms started at (s into the window):", p.name.c_str());
    for (std::size_t i = 0; i < p.slow_at_s.size() && i < 24; ++i)
      std::printf(" %.3f", p.slow_at_s[i]);
    std::printf("%s\n", p.slow_at_s.size() > 24 ? " ..." : "");
  }
  std::printf(
      "\ncpu s: the whole process (server + clients) during the measured window; "
      "client s: the client threads alone.\ntarget: >= 20000 req/s with p99 < 5 ms\n");
  bool failed = false;
  for (const auto& p : passes)
    for (const auto& f : p.failures) {
      std::printf("%s: client: %s\n", p.name.c_str(), f.c_str());
      failed = true;
    }

  server.stop();
  station.shutdown();
  return failed ? 1 : 0;
}
