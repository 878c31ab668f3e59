// Load on GET /api/v1/vehicles/{vid}/predict: the real station and HTTP server
// in-process on loopback, K client threads with one keep-alive connection each, requests back to
// back. The target is >= 20,000 requests/s on 2 cores with p99 < 5 ms. A third pass reads the
// dashboard's index.html (the repository's web/) the same way. A plain program rather than a
// Google Benchmark: a load generator measures throughput and a latency distribution over a fixed
// time, not the time of one repeated call.
//
//   bench_http_load [--clients K] [--seconds D] [--io-threads N]
//   bench_http_load --compare-url http://127.0.0.1:PORT/index.html [--rounds R] [...]
//
// --compare-url measures another server (nginx, say, serving the same web/) on the same file
// instead of the predict passes: R rounds of this server's index.html pass then the other's, with
// the same clients and duration, so that both see the same machine load; it prints each round's
// requests/s, their ratio and the median ratio, and fails if the two bodies differ in size.
//
// The clients share the machine with the server, so the figures are for both together; the
// table shows how much CPU the clients took, and how busy the whole machine was.

#include <sys/socket.h>
#include <time.h>

#include <algorithm>
#include <atomic>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <charconv>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
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

// Where a pass sends its requests: a numeric address (nothing is resolved, so that a name
// lookup cannot differ between the two servers), a port and, for the static pass, the path.
struct Endpoint {
  net::ip::address address = net::ip::make_address("127.0.0.1");
  unsigned short port = 0;
  std::string path = "/index.html";
  int pid = 0;  // the process that serves it, for its CPU time; 0: this one
};

struct Options {
  int clients = 4;
  double seconds = 10.0;
  int io_threads = 2;
  int rounds = 3;
  std::optional<Endpoint> compare;
};

// http://ADDRESS:PORT/PATH, ADDRESS an IPv4 literal or a bracketed IPv6 one.
Endpoint parse_url(const std::string& url) {
  const auto bad = [&](std::string_view why) {
    return std::invalid_argument("--compare-url '" + url + "': " + std::string(why) +
                                 " (expected http://ADDRESS:PORT/PATH, ADDRESS numeric)");
  };
  constexpr std::string_view scheme = "http://";
  if (!url.starts_with(scheme)) throw bad("not http://");
  std::string_view rest = std::string_view(url).substr(scheme.size());
  const auto slash = rest.find('/');
  if (slash == std::string_view::npos) throw bad("no path");
  const std::string_view authority = rest.substr(0, slash);
  const auto colon = authority.rfind(':');
  if (colon == std::string_view::npos || colon == 0) throw bad("no port");
  std::string_view host = authority.substr(0, colon);
  if (host.size() >= 2 && host.front() == '[' && host.back() == ']')
    host = host.substr(1, host.size() - 2);
  const std::string_view port_text = authority.substr(colon + 1);
  unsigned port = 0;
  const auto [end, ec] =
      std::from_chars(port_text.data(), port_text.data() + port_text.size(), port);
  if (ec != std::errc() || end != port_text.data() + port_text.size() || port == 0 || port > 65535)
    throw bad("the port is not 1..65535");
  Endpoint e;
  beast::error_code address_ec;
  e.address = net::ip::make_address(std::string(host), address_ec);
  if (address_ec) throw bad("the address is not numeric");
  e.port = static_cast<unsigned short>(port);
  e.path = std::string(rest.substr(slash));
  return e;
}

Options parse_options(int argc, char** argv) {
  Options o;
  int compare_pid = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto text = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
      return argv[++i];
    };
    const auto value = [&]() -> double { return std::stod(text()); };
    if (a == "--clients")
      o.clients = static_cast<int>(value());
    else if (a == "--seconds")
      o.seconds = value();
    else if (a == "--io-threads")
      o.io_threads = static_cast<int>(value());
    else if (a == "--rounds")
      o.rounds = static_cast<int>(value());
    else if (a == "--compare-url")
      o.compare = parse_url(text());
    else if (a == "--compare-pid")
      compare_pid = static_cast<int>(value());
    else
      throw std::invalid_argument("unknown option " + a +
                                  " (--clients K, --seconds D, --io-threads N, --compare-url URL, "
                                  "--compare-pid PID, --rounds R)");
  }
  if (compare_pid != 0) {
    if (!o.compare) throw std::invalid_argument("--compare-pid needs --compare-url");
    if (compare_pid < 0) throw std::invalid_argument("--compare-pid: a process id");
    o.compare->pid = compare_pid;
  }
  // Bounded so that a typo cannot start an endless or machine-filling run.
  if (o.clients < 1 || o.clients > 256) throw std::invalid_argument("--clients: 1..256");
  if (!(o.seconds > 0.0 && o.seconds <= 120.0)) throw std::invalid_argument("--seconds: (0, 120]");
  if (o.io_threads < 1 || o.io_threads > 64) throw std::invalid_argument("--io-threads: 1..64");
  if (o.rounds < 1 || o.rounds > 20) throw std::invalid_argument("--rounds: 1..20");
  return o;
}

// The whole machine's busy share of its CPU time since the last call (all processes: this one,
// another server, other users), from /proc/stat's first line.
struct MachineCpu {
  unsigned long long busy = 0, total = 0;
  static MachineCpu now() {
    std::ifstream in("/proc/stat");
    std::string cpu;
    unsigned long long v[8] = {};
    in >> cpu;
    for (auto& x : v)
      in >> x;
    MachineCpu m;
    for (const auto x : v)
      m.total += x;
    m.busy = m.total - v[3] - v[4];  // less idle and iowait
    return m;
  }
  static double busy_share(const MachineCpu& a, const MachineCpu& b) {
    return b.total > a.total
               ? static_cast<double>(b.busy - a.busy) / static_cast<double>(b.total - a.total)
               : 0.0;
  }
};

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

// Another process's CPU time (user + system, /proc/PID/stat fields 14 and 15), or -1 if it
// cannot be read.
double other_process_cpu_s(int pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string stat;
  std::getline(in, stat);
  // The command name (field 2) may hold spaces: the fields are counted after its ')'.
  const auto close = stat.rfind(')');
  if (close == std::string::npos) return -1.0;
  std::istringstream fields(stat.substr(close + 2));
  std::string skip;
  for (int field = 3; field < 14; ++field)
    fields >> skip;
  unsigned long long utime = 0, stime = 0;
  if (!(fields >> utime >> stime)) return -1.0;
  return static_cast<double>(utime + stime) / static_cast<double>(sysconf(_SC_CLK_TCK));
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

void run_client(const Endpoint& endpoint, Target target, std::uint64_t seed,
                Clock::time_point measure_from, Clock::time_point stop, std::atomic<int>& fd_out,
                ClientResult& out) {
  net::io_context ioc;
  beast::tcp_stream stream(ioc);
  Lcg rng{seed};
  double cpu0 = 0.0;
  bool measuring = false;
  try {
    stream.connect(tcp::endpoint(endpoint.address, endpoint.port));
    stream.socket().set_option(tcp::no_delay(true));
    fd_out = stream.socket().native_handle();
    beast::flat_buffer buffer;
    http::request<http::empty_body> req{http::verb::get, "/", 11};
    req.set(http::field::host, (endpoint.address.is_v6() ? "[" + endpoint.address.to_string() + "]"
                                                         : endpoint.address.to_string()) +
                                   ":" + std::to_string(endpoint.port));
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
                     ? endpoint.path
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
  double machine_busy = 0.0;   // share of the whole machine's CPU time, 0..1
  double server_cpu_s = -1.0;  // the serving process's alone (-1: unknown)
  std::vector<std::string> failures;
  std::vector<double> slow_at_s;
};

PassResult run_pass(const std::string& name, const Endpoint& endpoint, const Options& o,
                    Target target) {
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
    threads.emplace_back(run_client, std::cref(endpoint), target,
                         0x9e3779b97f4a7c15ULL * (i + 1) + static_cast<std::uint64_t>(target),
                         measure_from, stop, std::ref(fds[static_cast<std::size_t>(i)]),
                         std::ref(results[static_cast<std::size_t>(i)]));
  std::this_thread::sleep_until(measure_from);
  const double cpu0 = process_cpu_s();
  const double other0 = endpoint.pid ? other_process_cpu_s(endpoint.pid) : 0.0;
  const auto machine0 = MachineCpu::now();
  std::this_thread::sleep_until(stop);
  const double cpu1 = process_cpu_s();
  const double other1 = endpoint.pid ? other_process_cpu_s(endpoint.pid) : 0.0;
  const auto machine1 = MachineCpu::now();
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
  r.machine_busy = MachineCpu::busy_share(machine0, machine1);
  if (endpoint.pid && other0 >= 0.0 && other1 >= 0.0) r.server_cpu_s = other1 - other0;
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
  // This process: the server's threads are what the clients did not take (with the station's
  // own, such as its simulated vehicle's, which an idle station keeps small).
  if (!endpoint.pid) r.server_cpu_s = r.process_cpu_s - r.client_cpu_s;
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

double server_us_per_request(const PassResult& p) {
  return p.server_cpu_s < 0.0 || p.requests == 0
             ? -1.0
             : 1e6 * p.server_cpu_s / static_cast<double>(p.requests);
}

void print_table(const std::vector<PassResult>& passes) {
  std::printf("\n%-30s %9s %6s %9s %7s %7s %7s %7s %7s %7s %7s %8s %7s %7s\n", "pass", "requests",
              "errors", "req/s", "p50 ms", "p90 ms", "p99 ms", "max ms", ">5 ms", "body B", "cpu s",
              "client s", "busy %", "srv us");
  for (const auto& p : passes)
    std::printf(
        "%-30s %9llu %6llu %9.0f %7.3f %7.3f %7.3f %7.2f %7zu %7.0f %7.2f %8.2f %7.0f %7.1f\n",
        p.name.c_str(), static_cast<unsigned long long>(p.requests),
        static_cast<unsigned long long>(p.errors), static_cast<double>(p.requests) / p.seconds,
        p.p50, p.p90, p.p99, p.max, p.slow_at_s.size(), p.mean_body_bytes, p.process_cpu_s,
        p.client_cpu_s, 100.0 * p.machine_busy, server_us_per_request(p));
  for (const auto& p : passes) {
    if (p.slow_at_s.empty()) continue;
    std::printf("%s: requests over 5 ms started at (s into the window):", p.name.c_str());
    for (std::size_t i = 0; i < p.slow_at_s.size() && i < 24; ++i)
      std::printf(" %.3f", p.slow_at_s[i]);
    std::printf("%s\n", p.slow_at_s.size() > 24 ? " ..." : "");
  }
  std::printf(
      "\ncpu s: this process (the station's server + the clients) during the measured window; "
      "client s: the client threads alone; busy %%: the whole machine (every process), of its %u "
      "hardware threads; srv us: the serving process's CPU per request (this process less its "
      "clients, or --compare-pid's; -1: unknown).\n",
      std::thread::hardware_concurrency());
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const auto n = v.size();
  return n == 0 ? 0.0 : n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// Alternate rounds, so that a change in the machine's load during the run falls on both servers.
// Returns false if the other server's answers were not the same file's.
bool compare_static(const Endpoint& station, const Endpoint& other, const Options& o,
                    std::vector<PassResult>& passes) {
  std::vector<double> ratios;
  for (int r = 1; r <= o.rounds; ++r) {
    passes.push_back(
        run_pass("avk " + station.path + " r" + std::to_string(r), station, o, Target::index_html));
    passes.push_back(
        run_pass("other " + other.path + " r" + std::to_string(r), other, o, Target::index_html));
  }
  print_table(passes);
  std::printf("\n%-6s %11s %11s %7s %10s %12s\n", "round", "avk req/s", "other req/s", "ratio",
              "avk srv us", "other srv us");
  std::vector<double> avk_rates, other_rates, avk_us, other_us;
  bool same_file = true;
  for (int r = 0; r < o.rounds; ++r) {
    const auto& a = passes[static_cast<std::size_t>(2 * r)];
    const auto& b = passes[static_cast<std::size_t>(2 * r + 1)];
    const double ra = static_cast<double>(a.requests) / a.seconds;
    const double rb = static_cast<double>(b.requests) / b.seconds;
    avk_rates.push_back(ra);
    other_rates.push_back(rb);
    ratios.push_back(rb > 0.0 ? ra / rb : 0.0);
    avk_us.push_back(server_us_per_request(a));
    other_us.push_back(server_us_per_request(b));
    std::printf("%-6d %11.0f %11.0f %7.2f %10.1f %12.1f\n", r + 1, ra, rb, ratios.back(),
                avk_us.back(), other_us.back());
    if (a.mean_body_bytes != b.mean_body_bytes) same_file = false;
  }
  std::printf("%-6s %11.0f %11.0f %7.2f %10.1f %12.1f   (medians; ratio = avk / other)\n", "median",
              median(avk_rates), median(other_rates), median(ratios), median(avk_us),
              median(other_us));
  std::printf(
      "avk: %d io threads in this process, beside the clients and its simulated vehicle; the "
      "other server: what it was started with.\n",
      o.io_threads);
  if (!same_file)
    std::printf("the two servers' bodies differ in size: not the same file, no comparison\n");
  return same_file;
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
  avk::bench::BenchStation bench_station("avk_bench_http_load", "bench-http-load-token", 1.0, 1,
                                         o.io_threads);
  auto& station = *bench_station.station;
  auto& server = *bench_station.http;
  const double setup_s = std::chrono::duration<double>(Clock::now() - t_setup).count();
  Endpoint self;
  self.port = server.port();

  double load1 = 0.0;
  std::ifstream("/proc/loadavg") >> load1;
  std::printf(
      "bench_http_load: %d clients x %.1f s per pass (+1 s warm-up), server: %d io threads, "
      "%u hardware threads, load average %.2f at the start, setup %.1f s\n",
      o.clients, o.seconds, o.io_threads, std::thread::hardware_concurrency(), load1, setup_s);
  std::vector<PassResult> passes;
  bool failed = false;
  if (o.compare) {
    failed = !compare_static(self, *o.compare, o, passes);
  } else {
    passes.push_back(run_pass("predict (normalized)", self, o, Target::predict));
    passes.push_back(run_pass("predict (placed x,y,heading)", self, o, Target::predict_placed));
    passes.push_back(run_pass("static /index.html", self, o, Target::index_html));
    print_table(passes);
    std::printf("target: >= 20000 req/s with p99 < 5 ms\n");
  }
  for (const auto& p : passes)
    for (const auto& f : p.failures) {
      std::printf("%s: client: %s\n", p.name.c_str(), f.c_str());
      failed = true;
    }

  server.stop();
  station.shutdown();
  return failed ? 1 : 0;
}
