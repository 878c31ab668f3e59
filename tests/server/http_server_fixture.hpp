#pragma once
// The bench of the HTTP/WebSocket transport's tests: an Api that echoes what the transport made of
// a request, HTTP and raw-byte clients whose every exchange has a deadline, and the fixture that
// serves them on loopback.

#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <boost/asio/connect.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/write.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <chrono>
#include <condition_variable>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "app/foxglove/channels.hpp"
#include "server/api_types.hpp"
#include "server/http/http_server.hpp"
#include "server/http/static_files.hpp"
#include "server/stream_hub.hpp"
#include "support/ws_client.hpp"

namespace avk::testing::http_transport {

namespace beast = boost::beast;
namespace http = boost::beast::http;
namespace websocket = boost::beast::websocket;
namespace net = boost::asio;
namespace fs = std::filesystem;
using tcp = boost::asio::ip::tcp;
using json = nlohmann::json;
using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

using avk::server::Api;
using avk::server::ApiRequest;
using avk::server::ApiResponse;
using avk::server::HttpServer;
using avk::server::HttpServerOptions;
using avk::server::StreamHub;
using avk::testing::WsClient;

// Echoes what the transport made of the request; /throw throws, /status/N answers N, /block
// waits until open_gate() (a request worker held busy).
class EchoApi final : public Api {
 public:
  ApiResponse handle(const ApiRequest& r) override {
    ++calls;
    if (r.path == "/api/v1/throw") throw std::runtime_error("boom");
    if (r.path == "/api/v1/block") {
      ++blocked;
      std::unique_lock lock(gate_mutex_);
      gate_.wait(lock, [&] { return gate_open_; });
      --blocked;
    }
    ApiResponse res;
    if (r.path.starts_with("/api/v1/status/")) {
      res.status = std::stoi(r.path.substr(std::string("/api/v1/status/").size()));
      res.headers = {{"Location", "/api/v1/things/1"}};
    }
    json multi = json::array();
    for (const auto& [k, v] : r.multi_query)
      multi.push_back({k, v});
    res.body = json{{"method", r.method},
                    {"path", r.path},
                    {"query", r.query},
                    {"multi_query", multi},
                    {"body", r.body},
                    {"content_type", r.content_type},
                    {"accept", r.accept},
                    {"authorization", r.authorization},
                    {"origin", r.origin},
                    {"host", r.host},
                    {"remote_address", r.remote_address},
                    {"remote_is_loopback", r.remote_is_loopback}}
                   .dump();
    return res;
  }
  // /api/v1/guarded wants "Authorization: Bearer ok"; /api/v1/small takes 10 bytes,
  // /api/v1/large 4096. /api/v1/health is immediate work, ?cost=expensive expensive.
  avk::server::Admission admit(const ApiRequest& head) override {
    ++admits;
    avk::server::Admission a;
    if (head.path == "/api/v1/health") a.workload = avk::server::Workload::immediate;
    if (const auto it = head.query.find("cost");
        it != head.query.end() && it->second == "expensive")
      a.workload = avk::server::Workload::expensive;
    if (head.path == "/api/v1/small") a.body_limit_bytes = 10;
    if (head.path == "/api/v1/large") a.body_limit_bytes = 4096;
    if (head.path == "/api/v1/guarded" && head.authorization != "Bearer ok")
      a.refusal = ApiResponse{401, "application/problem+json", R"({"status":401})", {}};
    return a;
  }
  void open_gate() {
    {
      std::lock_guard lock(gate_mutex_);
      gate_open_ = true;
    }
    gate_.notify_all();
  }
  std::atomic<int> calls{0};
  std::atomic<int> admits{0};
  std::atomic<int> blocked{0};  // requests waiting at the gate

 private:
  std::mutex gate_mutex_;
  std::condition_variable gate_;
  bool gate_open_ = false;
};

inline tcp::endpoint loopback(unsigned short port) {
  return {net::ip::make_address("127.0.0.1"), port};
}

template <class Predicate>
bool wait_for(Predicate done, std::chrono::milliseconds limit = 5000ms) {
  const auto deadline = Clock::now() + limit;
  while (!done()) {
    if (Clock::now() > deadline) return false;
    std::this_thread::sleep_for(2ms);
  }
  return true;
}

// An HTTP/1.1 client on one connection; every exchange has a deadline.
class HttpClient {
 public:
  // from: the loopback address to connect from (127.0.0.2 is another client to the server).
  explicit HttpClient(unsigned short port, const std::string& from = "")
      : port_(port), stream_(ioc_) {
    if (!from.empty()) {
      stream_.socket().open(tcp::v4());
      stream_.socket().bind({net::ip::make_address(from), 0});
    }
    stream_.connect(loopback(port));
  }

  http::response<http::string_body> request(
      http::verb method, const std::string& target, const std::string& body = "",
      std::vector<std::pair<std::string, std::string>> headers = {}, unsigned version = 11) {
    http::request<http::string_body> req{method, target, version};
    req.set(http::field::host, "127.0.0.1:" + std::to_string(port_));
    for (const auto& [k, v] : headers)
      req.set(k, v);
    req.body() = body;
    if (!body.empty() || method == http::verb::post) req.prepare_payload();

    beast::error_code ec;
    http::response_parser<http::string_body> parser;
    parser.body_limit(64u << 20);
    if (method == http::verb::head) parser.skip(true);
    stream_.expires_after(5s);
    http::async_write(stream_, req, [&](beast::error_code e, std::size_t) {
      if (e) {
        ec = e;
        return;
      }
      http::async_read(stream_, buffer_, parser,
                       [&](beast::error_code e2, std::size_t) { ec = e2; });
    });
    ioc_.restart();
    ioc_.run();
    if (ec) throw beast::system_error(ec);
    return parser.release();
  }

  // Whether the server closed the connection (EOF or reset) within the limit.
  bool closed_by_server(std::chrono::milliseconds limit = 20000ms) {
    std::array<char, 256> b{};
    beast::error_code ec;
    stream_.expires_after(limit);
    std::function<void()> read = [&] {
      stream_.async_read_some(net::buffer(b), [&](beast::error_code e, std::size_t) {
        if (e)
          ec = e;
        else
          read();
      });
    };
    read();
    ioc_.restart();
    ioc_.run();
    return ec && ec != beast::error::timeout;
  }

 private:
  unsigned short port_;
  net::io_context ioc_;
  beast::tcp_stream stream_;
  beast::flat_buffer buffer_;
};

inline http::response<http::string_body> get(unsigned short port, const std::string& target) {
  return HttpClient(port).request(http::verb::get, target);
}

// Raw bytes in, everything until the server closes (or the limit) out.
struct RawResult {
  std::string data;
  beast::error_code ec;  // how the read ended: eof/reset = closed by the server
  bool closed() const { return ec && ec != beast::error::timeout; }
};

class RawClient {
 public:
  explicit RawClient(unsigned short port) : stream_(ioc_) { stream_.connect(loopback(port)); }

  void send(std::string_view bytes) { net::write(stream_.socket(), net::buffer(bytes)); }

  RawResult read_until_closed(std::chrono::milliseconds limit = 20000ms) {
    RawResult result;
    std::array<char, 4096> b{};
    stream_.expires_after(limit);
    std::function<void()> read = [&] {
      stream_.async_read_some(net::buffer(b), [&](beast::error_code e, std::size_t n) {
        result.data.append(b.data(), n);
        if (e)
          result.ec = e;
        else
          read();
      });
    };
    read();
    ioc_.restart();
    ioc_.run();
    return result;
  }

  void close() {
    beast::error_code ec;
    stream_.socket().close(ec);
  }

 private:
  net::io_context ioc_;
  beast::tcp_stream stream_;
};

inline RawResult raw_exchange(unsigned short port, std::string_view bytes) {
  RawClient c(port);
  c.send(bytes);
  return c.read_until_closed();
}

inline int status_of(const std::string& raw) {
  // "HTTP/1.1 400 Bad Request"
  if (raw.size() < 12 || !raw.starts_with("HTTP/1.")) return 0;
  return std::stoi(raw.substr(9, 3));
}

class HttpServerTest : public ::testing::Test {
 protected:
  // A request still at the gate would keep the server's stop waiting for its worker.
  ~HttpServerTest() override { api.open_gate(); }

  // With one request worker: a request held at the gate on it, and another waiting behind it
  // (each on its own connection, answered once the gate opens); null when either never got
  // there.
  std::pair<std::unique_ptr<RawClient>, std::unique_ptr<RawClient>> the_worker_busy_and_one_waiting(
      unsigned short on_port) {
    const auto request = [](const std::string& target) {
      return "GET " + target + " HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n";
    };
    auto busy = std::make_unique<RawClient>(on_port);
    busy->send(request("/api/v1/block"));
    if (!wait_for([&] { return api.blocked.load() == 1; })) return {};
    auto waiting = std::make_unique<RawClient>(on_port);
    waiting->send(request("/api/v1/echo"));
    if (!wait_for([&] { return server->waiting_requests() == 1; })) return {};
    return {std::move(busy), std::move(waiting)};
  }

  void start(HttpServerOptions options = {}) {
    options.server_version = "test-1";
    server = std::make_unique<HttpServer>(std::move(options), api, hub);
    server->start();
    port = server->port();
    ASSERT_NE(port, 0);
  }

  EchoApi api;
  StreamHub hub;  // before server: the server must go first
  std::unique_ptr<HttpServer> server;
  unsigned short port = 0;
};

}  // namespace avk::testing::http_transport
