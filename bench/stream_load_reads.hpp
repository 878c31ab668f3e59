#pragma once
// Requests beside the stream in bench_stream_load: one call on its own connection, and the heavy
// reads an analyst's page asks while the operator watches. Used by one program only, so defined
// here whole.

#include <atomic>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <chrono>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "stream_load_clients.hpp"

namespace avk::bench {

inline constexpr const char* kStreamLoadVehicle = "sim-usim";
inline constexpr const char* kStreamLoadToken = "bench-stream-load-token";

// One request on its own connection; the deadline keeps a stuck server from hanging the bench.
inline std::pair<int, std::string> http_call(unsigned short port, http::verb method,
                                             const std::string& target,
                                             const std::string& body = "",
                                             std::chrono::seconds limit = 10s) {
  net::io_context ioc;
  beast::tcp_stream stream(ioc);
  stream.expires_after(limit);
  stream.connect(loopback(port));
  http::request<http::string_body> req{method, target, 11};
  req.set(http::field::host, "127.0.0.1:" + std::to_string(port));
  req.set(http::field::authorization, std::string("Bearer ") + kStreamLoadToken);
  if (method == http::verb::post) {
    req.set(http::field::content_type, "application/json");
    req.body() = body;
    req.prepare_payload();
  }
  beast::flat_buffer buffer;
  http::response<http::string_body> res;
  beast::error_code ec;
  http::async_write(stream, req, [&](beast::error_code e, std::size_t) {
    if (e) {
      ec = e;
      return;
    }
    http::async_read(stream, buffer, res, [&](beast::error_code e2, std::size_t) { ec = e2; });
  });
  ioc.run();
  if (ec) throw beast::system_error(ec);
  return {static_cast<int>(res.result_int()), res.body()};
}

// Heavy reads beside the stream, until `stop`: each loop asks for a model fit, the comparison and
// a held-out prediction (another turn each time) in turn, as an analyst's page would.
struct HeavyReads {
  std::mutex mutex;
  std::map<int, int> statuses;  // 0: no answer (a transport error or the deadline)
  std::atomic<bool> stop{false};
  std::atomic<int> next_turn{1};
  std::vector<std::thread> loops;

  void start(unsigned short port, int n, std::int64_t mission) {
    for (int l = 0; l < n; ++l)
      loops.emplace_back([this, port, l, mission] {
        for (int i = l; !stop; ++i) {
          int status = 0;
          try {
            const std::string vehicle = std::string("/api/v1/vehicles/") + kStreamLoadVehicle;
            if (i % 3 == 0)
              status = http_call(port, http::verb::post, vehicle + "/models",
                                 R"({"missions":[)" + std::to_string(mission) + "]}", 120s)
                           .first;
            else if (i % 3 == 1)
              status = http_call(port, http::verb::get, vehicle + "/compare", "", 120s).first;
            else
              status = http_call(port, http::verb::get,
                                 vehicle + "/predict?speed=1&dheading=70&without_turn=" +
                                     std::to_string(next_turn++),
                                 "", 120s)
                           .first;
          } catch (const std::exception&) {
            status = 0;
          }
          {
            std::lock_guard lock(mutex);
            ++statuses[status];
          }
          if (status == 429 || status == 503) std::this_thread::sleep_for(1s);
        }
      });
  }
  std::string finish() {
    stop = true;
    for (auto& t : loops)
      t.join();
    std::string out;
    for (const auto& [status, count] : statuses)
      out += " " + (status ? std::to_string(status) : std::string("none")) + " x" +
             std::to_string(count);
    return out.empty() ? " none" : out;
  }
};

}  // namespace avk::bench
