#include "exhaustion_attacks.hpp"

#include <poll.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <map>
#include <mutex>
#include <sstream>
#include <thread>
#include <vector>

#include "exhaustion_client.hpp"
#include "support/mcap_bytes.hpp"
#include "support/spawn_avk.hpp"

namespace avk::bench {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

namespace {

// The heaviest maneuver question the API takes: every 0.5 deg candidate against 50 contacts.
std::string evaluate_request() {
  std::string contacts;
  for (int i = 0; i < 50; ++i) {
    const double bearing = i * 7.2 * M_PI / 180.0;
    char c[160];
    std::snprintf(c, sizeof c, R"(%s{"x_m":%.1f,"y_m":%.1f,"course_deg":%d,"speed_mps":%.2f})",
                  i ? "," : "", 60.0 * std::sin(bearing), 60.0 * std::cos(bearing), (i * 37) % 360,
                  0.5 + 0.02 * i);
    contacts += c;
  }
  const std::string body =
      R"({"own":{"x_m":0,"y_m":0,"heading_deg":0,"speed_mps":1.0},"candidate_step_deg":0.5,)"
      R"("horizon_s":120,"contacts":[)" +
      contacts + "]}";
  return std::string("POST /api/v1/vehicles/sim-usim/maneuvers/evaluate HTTP/1.1\r\n") +
         "Host: 127.0.0.1\r\nConnection: close\r\nContent-Type: application/json\r\n"
         "Content-Length: " +
         std::to_string(body.size()) + "\r\n\r\n" + body;
}

}  // namespace

std::string slow_bodies(unsigned short port, std::chrono::seconds length) {
  struct Conn {
    int fd;
    bool authorised;
    bool open = true;
    Clock::time_point start;
    double cut_s = -1;
    std::string seen;
  };
  std::vector<Conn> conns;
  // Under the per-address cap (64), so that what cuts them is the request deadline.
  for (int i = 0; i < 50; ++i) {
    const bool authorised = i % 2 == 1;
    const int fd = connect_loopback(port);
    if (fd < 0) continue;
    const std::string header =
        std::string("POST ") + kImport +
        " HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: text/csv\r\n" +
        (authorised ? std::string("Authorization: Bearer ") + kToken + "\r\n" : std::string()) +
        "Content-Length: 1000000\r\n\r\n";
    send_all(fd, header);
    conns.push_back({fd, authorised, true, Clock::now(), -1, {}});
  }
  const auto end = Clock::now() + length;
  auto next_byte = Clock::now();
  while (Clock::now() < end) {
    const bool send_now = Clock::now() >= next_byte;
    if (send_now) next_byte += 10s;
    for (auto& c : conns) {
      if (!c.open) continue;
      if ((send_now && !send_all(c.fd, "s")) || !still_open(c.fd, &c.seen)) {
        c.open = false;
        c.cut_s = std::chrono::duration<double>(Clock::now() - c.start).count();
      }
    }
    std::this_thread::sleep_for(100ms);
  }
  int unauth_401 = 0, unauth_open = 0, auth_cut = 0, auth_open = 0;
  std::vector<double> auth_cut_s;
  for (auto& c : conns) {
    if (c.authorised) {
      if (c.open)
        ++auth_open;
      else {
        ++auth_cut;
        auth_cut_s.push_back(c.cut_s);
      }
    } else {
      if (c.seen.starts_with("HTTP/1.1 401")) ++unauth_401;
      if (c.open) ++unauth_open;
    }
    ::close(c.fd);
  }
  std::ostringstream s;
  s << "without token: " << unauth_401 << "/25 got 401, " << unauth_open
    << " still open; with token: " << auth_cut << "/25 cut (median at "
    << percentile(auth_cut_s, 0.5) << " s), " << auth_open << " still open";
  return s.str();
}

std::string slow_connections(unsigned short port, int count, std::chrono::seconds length) {
  std::vector<int> fds;
  std::vector<std::string> seen;
  int connect_failures = 0;
  for (int i = 0; i < count; ++i) {
    const int fd = connect_loopback(port);
    if (fd < 0) {
      ++connect_failures;
      continue;
    }
    send_all(fd, "GET /api/v1/health HTTP/1.1\r\nHost: 127.0.0.1\r\n");
    fds.push_back(fd);
    seen.emplace_back();
  }
  const auto end = Clock::now() + length;
  auto next_byte = Clock::now() + 10s;
  std::vector<bool> open(fds.size(), true);
  while (Clock::now() < end) {
    const bool send_now = Clock::now() >= next_byte;
    if (send_now) next_byte += 10s;
    for (std::size_t i = 0; i < fds.size(); ++i)
      if (open[i] && ((send_now && !send_all(fds[i], "X")) || !still_open(fds[i], &seen[i])))
        open[i] = false;
    std::this_thread::sleep_for(200ms);
  }
  int refused = 0, closed = 0, still = 0;
  for (std::size_t i = 0; i < fds.size(); ++i) {
    if (seen[i].starts_with("HTTP/1.1 503"))
      ++refused;
    else if (!open[i])
      ++closed;
    else
      ++still;
    ::close(fds[i]);
  }
  std::ostringstream s;
  s << count << " opened (" << connect_failures << " connect failures): " << refused
    << " refused with 503, " << closed << " closed by the server, " << still
    << " still open at the end";
  return s.str();
}

std::string oversized_bodies(unsigned short port) {
  std::vector<std::thread> threads;
  std::vector<long long> sent(8, 0);
  std::vector<std::string> status(8);
  for (int i = 0; i < 8; ++i)
    threads.emplace_back([&, i] {
      const int fd = connect_loopback(port);
      if (fd < 0) return;
      const std::string header = std::string("POST ") + kImport +
                                 " HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: text/csv\r\n"
                                 "Content-Length: 62000000\r\n\r\n";
      send_all(fd, header);
      const std::string chunk(64 * 1024, '1');
      const auto deadline = Clock::now() + 10s;
      while (sent[i] < 62000000 && Clock::now() < deadline) {
        pollfd p{fd, POLLOUT, 0};
        if (::poll(&p, 1, 200) <= 0) {
          if (!still_open(fd, &status[i])) break;
          continue;
        }
        const auto n = ::send(fd, chunk.data(), chunk.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
        if (n <= 0) break;
        sent[i] += n;
      }
      still_open(fd, &status[i]);
      ::close(fd);
    });
  for (auto& t : threads)
    t.join();
  int got401 = 0;
  long long most = 0;
  for (int i = 0; i < 8; ++i) {
    if (status[i].starts_with("HTTP/1.1 401")) ++got401;
    most = std::max(most, sent[i]);
  }
  std::ostringstream s;
  s << got401 << "/8 got 401; the most any client got into the socket before the server closed: "
    << most / 1024 << " KiB of 60,547 KiB";
  return s.str();
}

std::string mcap_bombs(const fs::path& dir, std::chrono::seconds length, bool& refused_small) {
  namespace mb = avk::testing::mcap_bytes;
  struct Bomb {
    std::string name;
    fs::path file;
    std::size_t bytes = 0;
    int imports = 0;
    int refused = 0;
    double max_s = 0;
    long max_rss_kb = 0;
    std::string answer;  // the first line of an import's output
  };
  std::string many;
  for (int i = 0; i < 45; ++i)
    many += mb::zero_chunk(std::uint64_t{9} * 7'456'540);  // 64 MiB - 4 bytes, a multiple of 9
  const std::pair<const char*, std::string> files[] = {
      {"1 GiB in one chunk", mb::hand_built_file(mb::zero_chunk(std::uint64_t{9} * 119'304'647))},
      {"45 x 64 MiB chunks", mb::hand_built_file(many)},
  };
  std::vector<Bomb> bombs;
  for (const auto& [name, bytes] : files) {
    Bomb b;
    b.name = name;
    b.file = dir / ("bomb" + std::to_string(bombs.size()) + ".mcap");
    b.bytes = bytes.size();
    std::ofstream(b.file, std::ios::binary) << bytes;
    bombs.push_back(b);
  }
  const std::string db = (dir / "bench.db").string();
  const auto end = Clock::now() + length;
  while (Clock::now() < end) {
    for (Bomb& b : bombs) {
      std::vector<pid_t> pids;
      std::vector<std::string> logs;
      const auto t0 = Clock::now();
      for (int i = 0; i < 4; ++i) {
        logs.push_back((dir / ("import" + std::to_string(i) + ".log")).string());
        pids.push_back(
            avk::testing::spawn_avk({"import", "mcap", b.file.string(), "--db", db}, logs.back()));
      }
      for (std::size_t i = 0; i < pids.size(); ++i) {
        rusage ru{};
        int status = 0;
        if (pids[i] <= 0 || ::wait4(pids[i], &status, 0, &ru) != pids[i]) continue;
        std::ifstream f(logs[i]);
        std::getline(f, b.answer);
        ++b.imports;
        b.max_s = std::max(b.max_s, std::chrono::duration<double>(Clock::now() - t0).count());
        b.max_rss_kb = std::max(b.max_rss_kb, ru.ru_maxrss);
        if (WIFEXITED(status) && WEXITSTATUS(status) != 0 &&
            b.answer.find("chunk at offset") != std::string::npos)
          ++b.refused;
      }
    }
  }
  std::ostringstream notes;
  for (const Bomb& b : bombs) {
    refused_small =
        refused_small && b.imports > 0 && b.refused == b.imports && b.max_rss_kb < 100 * 1024;
    notes << (notes.tellp() > 0 ? "; " : "") << b.name << " (" << b.bytes / 1024
          << " KiB): " << b.refused << "/" << b.imports << " imports refused, each within "
          << b.max_s << " s and " << b.max_rss_kb / 1024 << " MB: \"" << b.answer << "\"";
    fs::remove(b.file);
  }
  return notes.str();
}

std::string heavy_reads(unsigned short port, int n, bool spread, std::chrono::seconds length,
                        const std::set<std::string>& without) {
  const std::string evaluate = evaluate_request();
  std::atomic<int> next_turn{1};
  std::mutex m;
  std::map<int, int> statuses;
  std::map<std::string, std::vector<double>> answered_s;  // 200s, by kind
  const auto end = Clock::now() + length;
  std::vector<std::thread> clients;
  for (int c = 0; c < n; ++c)
    clients.emplace_back([&, c] {
      const std::string from = spread ? "127.0.0." + std::to_string(2 + c) : "127.0.0.1";
      for (int i = c; Clock::now() < end && without.size() < 5; ++i) {
        std::string kind, request;
        switch (i % 5) {
          case 0:
            kind = "evaluate";
            request = evaluate;
            break;
          case 1:
            kind = "predict held out";
            request =
                get_request("/api/v1/vehicles/sim-usim/predict?speed=1&dheading=70&without_turn=" +
                            std::to_string(next_turn++));
            break;
          case 2:
            kind = "mcap export";
            request = get_request("/api/v1/missions/1/export?format=mcap");
            break;
          case 3:
            kind = "sweep";
            request = get_request("/api/v1/vehicles/sim-usim/models/sweep?mission=1");
            break;
          default:
            kind = "compare";
            request = get_request("/api/v1/vehicles/sim-usim/compare");
        }
        if (without.contains(kind)) continue;
        const auto t0 = Clock::now();
        const int status = exchange(from, port, request, 120s);
        const double s = std::chrono::duration<double>(Clock::now() - t0).count();
        {
          std::lock_guard lock(m);
          ++statuses[status];
          if (status == 200) answered_s[kind].push_back(s);
        }
        // A refused client waits as Retry-After asks, as a well-behaved one would.
        if (status == 429 || status == 503) std::this_thread::sleep_for(1s);
      }
    });
  for (auto& t : clients)
    t.join();
  std::ostringstream out;
  out << "answers:";
  for (const auto& [status, count] : statuses)
    out << " " << (status ? std::to_string(status) : std::string("none")) << " x" << count;
  out << "; 200s by kind (count, median s):";
  for (const auto& [kind, times] : answered_s)
    out << " " << kind << " " << times.size() << " (" << percentile(times, 0.5) << ")";
  return out.str();
}

}  // namespace avk::bench
