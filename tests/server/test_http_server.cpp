// The HTTP/WebSocket transport on real loopback sockets: request decoding, keep-alive, error
// paths (limits, malformed requests, slow and vanishing clients), static files, the live stream
// and its slow-client policy, and shutdown. Every wait is bounded: a broken server fails a test
// instead of hanging it.

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

namespace {

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

tcp::endpoint loopback(unsigned short port) {
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

http::response<http::string_body> get(unsigned short port, const std::string& target) {
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

RawResult raw_exchange(unsigned short port, std::string_view bytes) {
  RawClient c(port);
  c.send(bytes);
  return c.read_until_closed();
}

int status_of(const std::string& raw) {
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

// --- REST ----------------------------------------------------------------------------------

TEST_F(HttpServerTest, DecodesPathAndQueryAndKeepsTheConnection) {
  start();
  HttpClient client(port);
  auto res = client.request(http::verb::get, "/api/v1/echo/a%20b?x=1&y=%2F&y=2&z=a+b%2Bc", "",
                            {{"Accept", "text/csv"}, {"Authorization", "Bearer t0k"}});
  ASSERT_EQ(res.result_int(), 200);
  EXPECT_EQ(res[http::field::content_type], "application/json");
  EXPECT_TRUE(res.keep_alive());
  const auto echo = json::parse(res.body());
  EXPECT_EQ(echo["method"], "GET");
  EXPECT_EQ(echo["path"], "/api/v1/echo/a b");
  EXPECT_EQ(echo["query"]["x"], "1");
  EXPECT_EQ(echo["query"]["y"], "2");  // the last one
  EXPECT_EQ(echo["query"]["z"], "a b+c");
  EXPECT_EQ(echo["multi_query"], json::parse(R"([["x","1"],["y","/"],["y","2"],["z","a b+c"]])"));
  EXPECT_EQ(echo["accept"], "text/csv");
  EXPECT_EQ(echo["authorization"], "Bearer t0k");
  EXPECT_EQ(echo["host"], "127.0.0.1:" + std::to_string(port));
  EXPECT_EQ(echo["remote_address"], "127.0.0.1");
  EXPECT_EQ(echo["remote_is_loopback"], true);

  // The same connection again, with a body this time.
  res = client.request(http::verb::post, "/api/v1/missions", R"({"a":1})",
                       {{"Content-Type", "application/json; charset=utf-8"}});
  ASSERT_EQ(res.result_int(), 200);
  const auto echo2 = json::parse(res.body());
  EXPECT_EQ(echo2["method"], "POST");
  EXPECT_EQ(echo2["body"], R"({"a":1})");
  EXPECT_EQ(echo2["content_type"], "application/json; charset=utf-8");
  EXPECT_EQ(api.calls.load(), 2);
}

TEST_F(HttpServerTest, Http10WithoutKeepAliveIsClosed) {
  start();
  HttpClient client(port);
  const auto res = client.request(http::verb::get, "/api/v1/echo", "", {}, 10);
  EXPECT_EQ(res.result_int(), 200);
  EXPECT_FALSE(res.keep_alive());
  EXPECT_TRUE(client.closed_by_server());
}

TEST_F(HttpServerTest, StatusAndExtraHeadersPassThrough) {
  start();
  const auto res = get(port, "/api/v1/status/201");
  EXPECT_EQ(res.result_int(), 201);
  EXPECT_EQ(res[http::field::location], "/api/v1/things/1");
  EXPECT_EQ(res[http::field::content_length], std::to_string(res.body().size()));
}

TEST_F(HttpServerTest, ExceptionInTheApiIs500ProblemJsonAndTheServerGoesOn) {
  start();
  HttpClient client(port);
  const auto res = client.request(http::verb::get, "/api/v1/throw");
  EXPECT_EQ(res.result_int(), 500);
  EXPECT_EQ(res[http::field::content_type], "application/problem+json");
  const auto problem = json::parse(res.body());
  EXPECT_EQ(problem["type"], "about:blank");
  EXPECT_EQ(problem["title"], "Internal Server Error");
  EXPECT_EQ(problem["status"], 500);
  // The exception's own words stay in the server's log.
  EXPECT_EQ(problem["detail"], "internal error (see the server log)");
  EXPECT_EQ(res.body().find("boom"), std::string::npos);
  // Same connection, and a fresh one.
  EXPECT_EQ(client.request(http::verb::get, "/api/v1/echo").result_int(), 200);
  EXPECT_EQ(get(port, "/api/v1/echo").result_int(), 200);
}

TEST_F(HttpServerTest, StreamPathWithoutUpgradeIs426) {
  start();
  const auto res = get(port, "/api/v1/stream");
  EXPECT_EQ(res.result_int(), 426);
  EXPECT_EQ(api.calls.load(), 0);
}

// --- malformed, oversized, slow and vanishing clients ----------------------------------------

TEST_F(HttpServerTest, BodyOverTheLimitIs413AndClosed) {
  HttpServerOptions o;
  o.body_limit = 1024;
  start(o);
  const std::string body(2000, 'x');
  {
    HttpClient client(port);
    const auto res = client.request(http::verb::post, "/api/v1/missions", body,
                                    {{"Content-Type", "application/json"}});
    EXPECT_EQ(res.result_int(), 413);
    EXPECT_EQ(res[http::field::content_type], "application/problem+json");
    EXPECT_TRUE(client.closed_by_server());
  }
  // The larger limit the API gives a route.
  const auto ok = HttpClient(port).request(http::verb::post, "/api/v1/large", body,
                                           {{"Content-Type", "application/json"}});
  EXPECT_EQ(ok.result_int(), 200);
  EXPECT_EQ(json::parse(ok.body())["body"], body);
  // A chunked body, whose size the header does not give.
  const std::string chunked =
      "POST /api/v1/missions HTTP/1.1\r\nHost: 127.0.0.1\r\nTransfer-Encoding: chunked\r\n\r\n"
      "800\r\n" +
      std::string(0x800, 'y') + "\r\n0\r\n\r\n";
  const auto raw = raw_exchange(port, chunked);
  EXPECT_EQ(status_of(raw.data), 413) << raw.data;
  EXPECT_TRUE(raw.closed());
  EXPECT_EQ(api.calls.load(), 1);
}

TEST_F(HttpServerTest, ExpectContinueGetsContinue) {
  start();
  RawClient c(port);
  c.send(
      "POST /api/v1/missions HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Length: 5\r\n"
      "Expect: 100-continue\r\nConnection: close\r\n\r\n");
  // Nothing but the 100 comes before the body is sent; read it with a short deadline.
  auto first = c.read_until_closed(3000ms);
  EXPECT_TRUE(first.data.starts_with("HTTP/1.1 100 Continue")) << first.data;
}

TEST_F(HttpServerTest, HeaderOverTheLimitIs431) {
  HttpServerOptions o;
  o.header_limit = 1024;
  start(o);
  const auto raw = raw_exchange(port, "GET /api/v1/echo HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Big: " +
                                          std::string(4000, 'b') + "\r\n\r\n");
  EXPECT_EQ(status_of(raw.data), 431) << raw.data;
  EXPECT_TRUE(raw.closed());
  EXPECT_EQ(api.calls.load(), 0);
}

TEST_F(HttpServerTest, GarbageRequestLineIs400AndClosed) {
  start();
  const auto raw = raw_exchange(port, "HELLO\r\n\r\n");
  EXPECT_EQ(status_of(raw.data), 400) << raw.data;
  EXPECT_NE(raw.data.find("application/problem+json"), std::string::npos);
  EXPECT_TRUE(raw.closed());
  const auto bad_header = raw_exchange(port, "GET / HTTP/1.1\r\nNo colon here\r\n\r\n");
  EXPECT_EQ(status_of(bad_header.data), 400) << bad_header.data;
  EXPECT_TRUE(bad_header.closed());
  EXPECT_EQ(get(port, "/api/v1/echo").result_int(), 200);
}

TEST_F(HttpServerTest, ClientThatStallsInTheHeaderIsDisconnected) {
  HttpServerOptions o;
  o.header_timeout = 200ms;
  start(o);
  RawClient slow(port);
  slow.send("GET /api/v1/echo HTTP/1.1\r\nHost: 127.0.0.1\r\n");  // and nothing more
  const auto r = slow.read_until_closed(20000ms);
  EXPECT_TRUE(r.closed()) << r.ec.message();
  EXPECT_TRUE(r.data.empty());
  // A connection that sends nothing at all goes the same way.
  RawClient silent(port);
  EXPECT_TRUE(silent.read_until_closed(20000ms).closed());
  EXPECT_EQ(api.calls.load(), 0);
}

// The other side of the header timeout, without measuring time: a header that arrives in pieces,
// with other requests answered in between, is answered once it is complete.
TEST_F(HttpServerTest, HeaderSentInPiecesWithinTheTimeoutIsAnswered) {
  HttpServerOptions o;
  o.header_timeout = 60000ms;
  start(o);
  RawClient pieces(port);
  pieces.send("GET /api/v1/echo HTTP/1.1\r\nHost: 127.0.0.1\r\n");
  for (int i = 0; i < 3; ++i)
    EXPECT_EQ(get(port, "/api/v1/echo").result_int(), 200);
  pieces.send("Connection: close\r\n\r\n");
  const auto r = pieces.read_until_closed(20000ms);
  EXPECT_EQ(status_of(r.data), 200) << r.data;
  EXPECT_EQ(api.calls.load(), 4);
}

TEST_F(HttpServerTest, IdleKeepAliveConnectionIsClosedAfterIdleTimeout) {
  HttpServerOptions o;
  o.idle_timeout = 200ms;
  start(o);
  HttpClient client(port);
  EXPECT_EQ(client.request(http::verb::get, "/api/v1/echo").result_int(), 200);
  EXPECT_TRUE(client.closed_by_server(20000ms));
}

TEST_F(HttpServerTest, ClientVanishingMidBodyDoesNotDisturbOthers) {
  start();
  std::vector<std::unique_ptr<RawClient>> open;
  for (int i = 0; i < 5; ++i) {
    auto c = std::make_unique<RawClient>(port);
    c->send("POST /api/v1/missions HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Length: 100000\r\n\r\n" +
            std::string(1000, 'z'));
    if (i % 2 == 0)
      c->close();  // gone mid-body
    else
      open.push_back(std::move(c));  // still there, mid-body
  }
  for (int i = 0; i < 3; ++i)
    EXPECT_EQ(get(port, "/api/v1/echo").result_int(), 200);
  EXPECT_EQ(api.calls.load(), 3);
}

// --- static files --------------------------------------------------------------------------

class StaticFilesTest : public HttpServerTest {
 protected:
  void SetUp() override {
    base = fs::temp_directory_path() /
           ("avk_http_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    fs::remove_all(base);
    // The dashboard's layout, and what else lies in web/ in a checkout.
    fs::create_directories(base / "web" / "js" / "sub");
    fs::create_directories(base / "web" / "css");
    fs::create_directories(base / "web" / "tests");
    fs::create_directories(base / "web" / "node_modules" / "plotly.js-dist-min");
    write(base / "web" / "index.html", "<html>dashboard</html>");
    write(base / "web" / "js" / "app.js", "console.log(1);");
    write(base / "web" / "css" / "style.css", "body{}");
    write(base / "web" / "favicon.svg", "<svg/>");
    write(base / "web" / "node_modules" / "plotly.js-dist-min" / "plotly.min.js", "plotly");
    write(base / "web" / "node_modules" / "plotly.js-dist-min" / "package.json", "{}");
    write(base / "web" / "node_modules" / ".package-lock.json", "{}");
    write(base / "web" / "tests" / "e2e.test.mjs", "test");
    write(base / "web" / "package.json", "{}");
    write(base / "web" / "package-lock.json", "{}");
    write(base / "secret", "TOPSECRET");
    fs::create_symlink(base / "secret", base / "web" / "js" / "link.js");
  }
  void TearDown() override {
    server.reset();
    std::error_code ec;
    fs::remove_all(base, ec);
  }
  static void write(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

  fs::path base;
  static inline int counter = 0;
};

TEST_F(StaticFilesTest, ServesFilesWithTheirTypes) {
  HttpServerOptions o;
  o.web_root = (base / "web").string();
  start(o);
  auto res = get(port, "/");
  ASSERT_EQ(res.result_int(), 200);
  EXPECT_TRUE(res[http::field::content_type].starts_with("text/html"));
  EXPECT_EQ(res.body(), "<html>dashboard</html>");
  res = get(port, "/js/app.js?v=3");
  ASSERT_EQ(res.result_int(), 200);
  EXPECT_TRUE(res[http::field::content_type].starts_with("text/javascript"));
  EXPECT_EQ(res.body(), "console.log(1);");
  res = get(port, "/css/style.css");
  EXPECT_TRUE(res[http::field::content_type].starts_with("text/css"));
  EXPECT_EQ(get(port, "/favicon.svg").result_int(), 200);
  EXPECT_EQ(get(port, "/node_modules/plotly.js-dist-min/plotly.min.js").body(), "plotly");
  res = HttpClient(port).request(http::verb::head, "/js/app.js");
  EXPECT_EQ(res.result_int(), 200);
  EXPECT_EQ(res[http::field::content_length], "15");
  EXPECT_TRUE(res.body().empty());
}

TEST_F(StaticFilesTest, NothingOutsideTheRoot) {
  HttpServerOptions o;
  o.web_root = (base / "web").string();
  start(o);
  for (const std::string target :
       {"/../secret", "/%2e%2e/secret", "/%2E%2E%2fsecret", "/a/../../secret", "/js/../../secret",
        "/..%5csecret", "/js/link.js", "/js/app.js%00.html", "/missing.html", "/js/sub",
        "/js/sub/"}) {
    const auto res = get(port, target);
    EXPECT_EQ(res.result_int(), 404) << target;
    EXPECT_EQ(res.body().find("TOPSECRET"), std::string::npos) << target;
    EXPECT_EQ(res[http::field::content_type], "application/problem+json") << target;
  }
}

// Regression: the test suite, package files and node_modules' bookkeeping were served.
TEST_F(StaticFilesTest, OnlyTheDashboardsFilesAreServed) {
  HttpServerOptions o;
  o.web_root = (base / "web").string();
  start(o);
  for (const std::string target :
       {"/tests/e2e.test.mjs", "/package-lock.json", "/package.json",
        "/node_modules/.package-lock.json", "/node_modules/plotly.js-dist-min/package.json",
        "/node_modules/", "/tests/"}) {
    const auto res = get(port, target);
    EXPECT_EQ(res.result_int(), 404) << target;
    EXPECT_EQ(res[http::field::content_type], "application/problem+json") << target;
  }
}

// Regression: responses had no Content-Security-Policy and no framing protection.
TEST_F(StaticFilesTest, EveryResponseCarriesTheSecurityHeaders) {
  HttpServerOptions o;
  o.web_root = (base / "web").string();
  start(o);
  for (const std::string target : {"/", "/js/app.js", "/missing", "/api/v1/echo"}) {
    const auto res = get(port, target);
    const std::string csp(res["Content-Security-Policy"]);
    EXPECT_NE(csp.find("default-src 'self'"), std::string::npos) << target;
    EXPECT_NE(csp.find("frame-ancestors 'none'"), std::string::npos) << target;
    EXPECT_EQ(res["X-Content-Type-Options"], "nosniff") << target;
    EXPECT_EQ(res["X-Frame-Options"], "DENY") << target;
  }
}

TEST_F(StaticFilesTest, OnlyGetAndHead) {
  HttpServerOptions o;
  o.web_root = (base / "web").string();
  start(o);
  const auto res = HttpClient(port).request(http::verb::post, "/index.html", "x");
  EXPECT_EQ(res.result_int(), 405);
  EXPECT_EQ(res[http::field::allow], "GET, HEAD");
}

// Regression: files came without validators, so every page load read and sent them again.
TEST_F(StaticFilesTest, ConditionalRequestsAreAnsweredWith304) {
  HttpServerOptions o;
  o.web_root = (base / "web").string();
  start(o);
  HttpClient c(port);
  const auto full = c.request(http::verb::get, "/js/app.js");
  ASSERT_EQ(full.result_int(), 200);
  const std::string etag(full[http::field::etag]);
  const std::string modified(full[http::field::last_modified]);
  ASSERT_FALSE(etag.empty());
  EXPECT_EQ(etag.front(), '"');
  ASSERT_TRUE(avk::server::StaticFiles::parse_http_date(modified)) << modified;
  EXPECT_EQ(full[http::field::cache_control], "no-cache");

  // The same connection: a 304 has no body, so keep-alive framing must hold.
  for (const std::string& tag : {etag, "W/" + etag, "\"other\", " + etag, std::string("*")}) {
    const auto again = c.request(http::verb::get, "/js/app.js", "", {{"If-None-Match", tag}});
    EXPECT_EQ(again.result_int(), 304) << tag;
    EXPECT_TRUE(again.body().empty());
    EXPECT_EQ(again[http::field::etag], etag);
    EXPECT_EQ(again["X-Content-Type-Options"], "nosniff");
  }
  EXPECT_EQ(
      c.request(http::verb::get, "/js/app.js", "", {{"If-None-Match", "\"other\""}}).result_int(),
      200);
  EXPECT_EQ(c.request(http::verb::head, "/js/app.js", "", {{"If-None-Match", etag}}).result_int(),
            304);
  EXPECT_EQ(
      c.request(http::verb::get, "/js/app.js", "", {{"If-Modified-Since", modified}}).result_int(),
      304);
  EXPECT_EQ(c.request(http::verb::get, "/js/app.js", "",
                      {{"If-Modified-Since", "Sat, 01 Jan 2000 00:00:00 GMT"}})
                .result_int(),
            200);
  // If-None-Match decides alone when both are sent (RFC 9110 13.1.3).
  EXPECT_EQ(c.request(http::verb::get, "/js/app.js", "",
                      {{"If-None-Match", "\"other\""}, {"If-Modified-Since", modified}})
                .result_int(),
            200);
  // An unreadable date is ignored.
  EXPECT_EQ(c.request(http::verb::get, "/js/app.js", "", {{"If-Modified-Since", "yesterday"}})
                .result_int(),
            200);
  // Validators differ between files.
  EXPECT_EQ(
      c.request(http::verb::get, "/css/style.css", "", {{"If-None-Match", etag}}).result_int(),
      200);
}

// The file list is read at the start, each file's bytes when it changes: an edited file is served
// as it is now, with a new ETag; one that became a symlink since is not followed.
TEST_F(StaticFilesTest, AnEditedFileIsServedAnewAndALinkPutInItsPlaceIsNot) {
  HttpServerOptions o;
  o.web_root = (base / "web").string();
  start(o);
  const auto before = get(port, "/js/app.js");
  ASSERT_EQ(before.body(), "console.log(1);");
  write(base / "web" / "js" / "app.js", "console.log('edited');");
  const auto after = get(port, "/js/app.js");
  EXPECT_EQ(after.body(), "console.log('edited');");
  EXPECT_NE(after[http::field::etag], before[http::field::etag]);
  // Added after the start: not in the list.
  write(base / "web" / "js" / "new.js", "new");
  EXPECT_EQ(get(port, "/js/new.js").result_int(), 404);
  fs::remove(base / "web" / "css" / "style.css");
  fs::create_symlink(base / "secret", base / "web" / "css" / "style.css");
  const auto swapped = get(port, "/css/style.css");
  EXPECT_EQ(swapped.result_int(), 404);
  EXPECT_EQ(swapped.body().find("TOPSECRET"), std::string::npos);
}

TEST(HttpDate, FormatsAndParsesImfFixdate) {
  using avk::server::StaticFiles;
  EXPECT_EQ(StaticFiles::http_date(784111777), "Sun, 06 Nov 1994 08:49:37 GMT");
  EXPECT_EQ(StaticFiles::parse_http_date("Sun, 06 Nov 1994 08:49:37 GMT"), 784111777);
  EXPECT_EQ(StaticFiles::parse_http_date(StaticFiles::http_date(1700000000)), 1700000000);
  for (const char* bad : {"", "Sunday, 06-Nov-94 08:49:37 GMT", "Sun Nov  6 08:49:37 1994",
                          "Sun, 31 Feb 1994 08:49:37 GMT", "Sun, 06 Nov 1994 25:49:37 GMT",
                          "Sun, 06 Xyz 1994 08:49:37 GMT", "Sun, 06 Nov 1994 08:49:37 UTC"})
    EXPECT_FALSE(StaticFiles::parse_http_date(bad)) << bad;
}

TEST_F(StaticFilesTest, WithoutAWebRootOnlyTheApi) {
  start();
  EXPECT_EQ(get(port, "/").result_int(), 404);
  EXPECT_EQ(get(port, "/index.html").result_int(), 404);
  EXPECT_EQ(get(port, "/api/v1/echo").result_int(), 200);
}

TEST_F(StaticFilesTest, MissingWebRootIsAnError) {
  HttpServerOptions o;
  o.web_root = (base / "nope").string();
  EXPECT_THROW(HttpServer(o, api, hub), std::runtime_error);
}

// --- the stream ----------------------------------------------------------------------------

TEST_F(HttpServerTest, StreamHelloSubscribeAndPublish) {
  start();
  WsClient ws(port);
  ASSERT_FALSE(ws.handshake_error()) << ws.handshake_error().message();
  const auto hello = ws.read();
  ASSERT_TRUE(hello);
  EXPECT_EQ((*hello)["type"], "hello");
  EXPECT_EQ((*hello)["session_id"], hub.session_id());
  EXPECT_EQ((*hello)["server_version"], "test-1");
  EXPECT_TRUE(wait_for([&] { return server->open_stream_sessions() == 1; }));

  ws.send(R"({"subscribe":["turn"]})");
  auto reply = ws.read();
  ASSERT_TRUE(reply);
  EXPECT_EQ(*reply, json::parse(R"({"type":"subscribed","topics":["turn"]})"));
  EXPECT_EQ(hub.subscriber_count("turn"), 1u);

  hub.publish("turn", 12.5, R"({"event":"finished","id":7})");
  auto message = ws.read();
  ASSERT_TRUE(message);
  EXPECT_EQ((*message)["topic"], "turn");
  EXPECT_EQ((*message)["seq"], 1);
  EXPECT_EQ((*message)["t"], 12.5);
  EXPECT_EQ((*message)["data"]["id"], 7);

  // Errors are answered and the connection stays.
  ws.send(R"({"subscribe":["turn","bogus"]})");
  reply = ws.read();
  ASSERT_TRUE(reply);
  EXPECT_EQ((*reply)["type"], "error");
  EXPECT_NE((*reply)["message"].get<std::string>().find("bogus"), std::string::npos);
  ws.send("not json");
  reply = ws.read();
  ASSERT_TRUE(reply);
  EXPECT_EQ((*reply)["type"], "error");
  ws.send("\x01\x02", true);
  reply = ws.read();
  ASSERT_TRUE(reply);
  EXPECT_EQ((*reply)["type"], "error");

  ws.send(R"({"subscribe":["nav"],"unsubscribe":["turn"]})");
  reply = ws.read();
  ASSERT_TRUE(reply);
  EXPECT_EQ(*reply, json::parse(R"({"type":"subscribed","topics":["nav"]})"));
  EXPECT_EQ(hub.subscriber_count("turn"), 0u);
  hub.publish("turn", 13.0, "{}");  // no longer subscribed
  hub.publish("nav", 13.0, R"({"x":1})");
  message = ws.read();
  ASSERT_TRUE(message);
  EXPECT_EQ((*message)["topic"], "nav");
  EXPECT_EQ(server->open_stream_sessions(), 1u);
}

TEST_F(HttpServerTest, StreamChecksOrigin) {
  start();
  WsClient foreign(port, "http://evil.example");
  EXPECT_EQ(foreign.handshake_error(), websocket::error::upgrade_declined);
  EXPECT_EQ(foreign.handshake_response().result_int(), 403);
  WsClient other_port(port, "http://127.0.0.1:1");
  EXPECT_EQ(other_port.handshake_response().result_int(), 403);

  WsClient same(port, "http://127.0.0.1:" + std::to_string(port));
  ASSERT_FALSE(same.handshake_error()) << same.handshake_error().message();
  EXPECT_TRUE(same.read());
  EXPECT_TRUE(wait_for([&] { return server->open_stream_sessions() == 1; }));
}

// One client stops reading: it is closed with 1008 once its event queue overflows, while a
// reading client gets every message in order and the publisher never waits.
TEST_F(HttpServerTest, StalledEventClientIsClosedAndOthersKeepUp) {
  HttpServerOptions o;
  o.stream_event_queue_limit = 8;
  // The close frame waits behind the write the stalled client blocks; give the test time to
  // come back and read it (the default cuts such a client after 5 s).
  o.close_timeout = 30s;
  start(o);
  WsClient stalled(port, "", 4096);
  ASSERT_TRUE(stalled.read());
  stalled.send(R"({"subscribe":["turn"]})");
  ASSERT_TRUE(stalled.read());

  constexpr int kMessages = 2000;
  constexpr int kWindow = 4;  // below the queue limit: the reader is never the one too slow
  std::mutex mutex;
  std::condition_variable received_cv;
  int received = 0;
  bool reader_ok = true;
  std::string reader_failure;

  WsClient reader(port);
  ASSERT_TRUE(reader.read());
  reader.send(R"({"subscribe":["turn"]})");
  ASSERT_TRUE(reader.read());
  std::thread reader_thread([&] {
    for (int i = 1; i <= kMessages; ++i) {
      const auto m = reader.read(10000ms);
      std::lock_guard lock(mutex);
      if (!m || (*m)["seq"] != i || (*m)["data"]["i"] != i) {
        reader_ok = false;
        reader_failure = m ? "got seq " + (*m)["seq"].dump() + " for " + std::to_string(i)
                           : "read failed: " + reader.error().message();
        received_cv.notify_all();
        return;
      }
      received = i;
      received_cv.notify_all();
    }
  });

  const std::string pad(64 * 1024, 'p');
  for (int i = 1; i <= kMessages; ++i) {
    {
      std::unique_lock lock(mutex);
      const bool ok =
          received_cv.wait_for(lock, 10s, [&] { return !reader_ok || received >= i - kWindow; });
      if (!ok || !reader_ok) break;
    }
    const std::string data = R"({"i":)" + std::to_string(i) + R"(,"pad":")" + pad + R"("})";
    hub.publish("turn", i * 0.1, data);
  }
  reader_thread.join();
  EXPECT_TRUE(reader_ok) << reader_failure;
  EXPECT_EQ(received, kMessages);
  // That the publisher never waited is the loop finishing with a client that never reads; how
  // long a publish takes is bench/stream_load's to measure.

  // The stalled session is gone from the hub and the open count; it still has its close frame
  // to deliver behind what the socket holds.
  EXPECT_TRUE(wait_for([&] { return hub.subscriber_count("turn") == 1; }));
  EXPECT_TRUE(wait_for([&] { return server->open_stream_sessions() == 1; }));
  int stalled_got = 0;
  std::int64_t last_seq = 0;
  while (auto m = stalled.read()) {
    ++stalled_got;
    ASSERT_GT((*m)["seq"].get<std::int64_t>(), last_seq);
    last_seq = (*m)["seq"].get<std::int64_t>();
  }
  EXPECT_EQ(stalled.error(), websocket::error::closed) << stalled.error().message();
  EXPECT_EQ(stalled.close_reason().code, websocket::close_code::policy_error);
  const auto& reason = stalled.close_reason().reason;
  EXPECT_EQ(std::string(reason.data(), reason.size()), "too slow: re-sync over REST");
  EXPECT_LT(stalled_got, kMessages);
}

// Telemetry is latest-value-wins: a client that stops reading nav accumulates nothing and is
// not closed; when it reads again the newest sample reaches it.
TEST_F(HttpServerTest, StalledTelemetryClientStaysOpen) {
  HttpServerOptions o;
  o.stream_event_queue_limit = 8;
  start(o);
  WsClient stalled(port, "", 4096);
  ASSERT_TRUE(stalled.read());
  stalled.send(R"({"subscribe":["nav"]})");
  ASSERT_TRUE(stalled.read());

  constexpr int kMessages = 2000;
  const std::string pad(64 * 1024, 'n');
  // Returns although the client reads nothing: publish never waits for a session.
  for (int i = 1; i <= kMessages; ++i)
    hub.publish("nav", i * 0.1, R"({"i":)" + std::to_string(i) + R"(,"pad":")" + pad + R"("})");

  std::this_thread::sleep_for(200ms);  // let the session work through what was posted
  EXPECT_EQ(server->open_stream_sessions(), 1u);
  EXPECT_EQ(hub.subscriber_count("nav"), 1u);

  int got = 0;
  std::int64_t last_seq = 0;
  while (last_seq < kMessages) {
    const auto m = stalled.read();
    ASSERT_TRUE(m) << stalled.error().message();
    ++got;
    ASSERT_GT((*m)["seq"].get<std::int64_t>(), last_seq);
    last_seq = (*m)["seq"].get<std::int64_t>();
  }
  EXPECT_EQ(last_seq, kMessages);
  EXPECT_LT(got, kMessages);  // older frames were replaced, not queued
  EXPECT_EQ(server->open_stream_sessions(), 1u);
}

// --- the Foxglove connection ---------------------------------------------------------------

// A Foxglove client (foxglove.websocket.v1) on the given path, past server info and advertise.
std::unique_ptr<WsClient> foxglove_client(unsigned short port, const std::string& path,
                                          json* advertise = nullptr, int receive_buffer = 0) {
  auto c = std::make_unique<WsClient>(port, "", receive_buffer, path, "foxglove.websocket.v1");
  if (c->handshake_error()) return c;
  const auto info = c->read();
  EXPECT_TRUE(info && (*info)["op"] == "serverInfo");
  const auto adv = c->read();
  EXPECT_TRUE(adv && (*adv)["op"] == "advertise");
  if (advertise && adv) *advertise = *adv;
  return c;
}

std::uint32_t channel_id(const json& advertise, const std::string& topic) {
  for (const auto& c : advertise["channels"])
    if (c["topic"] == topic) return c["id"].get<std::uint32_t>();
  ADD_FAILURE() << topic;
  return 0;
}

std::uint32_t le32(const std::string& b, std::size_t at) {
  std::uint32_t v = 0;
  for (std::size_t i = 0; i < 4; ++i)
    v |= static_cast<std::uint32_t>(static_cast<unsigned char>(b[at + i])) << (8 * i);
  return v;
}

TEST_F(HttpServerTest, FoxgloveSelectsItsSubprotocolAndSendsBinaryMessageData) {
  start();
  hub.foxglove().advertise("boat", avk::app::foxglove::live_channels("boat"));
  for (const std::string path : {"/api/v1/foxglove", "/api/v1/stream"}) {
    json adv;
    auto c = foxglove_client(port, path, &adv);
    ASSERT_FALSE(c->handshake_error()) << path << ": " << c->handshake_error().message();
    EXPECT_EQ(c->handshake_response()[http::field::sec_websocket_protocol],
              "foxglove.websocket.v1");
    const auto pose = channel_id(adv, "/boat/pose");
    c->send(
        json{{"op", "subscribe"}, {"subscriptions", {{{"id", 41}, {"channelId", pose}}}}}.dump());
    ASSERT_TRUE(wait_for([&] { return hub.foxglove().wanted("/boat/pose"); }));
    hub.foxglove().publish("/boat/pose", 1'500'000'000ULL, R"({"x":1})");
    const auto frame = c->read_text();
    ASSERT_TRUE(frame) << c->error().message();
    EXPECT_TRUE(c->got_binary());
    ASSERT_EQ(frame->size(), 13u + 7u);
    EXPECT_EQ(static_cast<unsigned char>((*frame)[0]), 0x01);
    EXPECT_EQ(le32(*frame, 1), 41u);
    EXPECT_EQ(le32(*frame, 5) | (std::uint64_t{le32(*frame, 9)} << 32), 1'500'000'000ULL);
    EXPECT_EQ(frame->substr(13), R"({"x":1})");
    c->send(json{{"op", "unsubscribe"}, {"subscriptionIds", {41}}}.dump());
    ASSERT_TRUE(wait_for([&] { return !hub.foxglove().wanted("/boat/pose"); }));
  }
  // Without the subprotocol the Foxglove path refuses the upgrade and says why.
  WsClient bare(port, "", 0, "/api/v1/foxglove");
  EXPECT_EQ(bare.handshake_response().result_int(), 400);
}

// The Origin rule with an operator's allow-list: Foxglove's web edition is let in only when
// named, on the Foxglove connection and the stream alike.
TEST_F(HttpServerTest, AllowedOriginsOpenTheLiveConnectionsToANamedSiteOnly) {
  HttpServerOptions o;
  o.allowed_origins = {"https://app.foxglove.dev"};
  start(o);
  WsClient fox(port, "https://App.Foxglove.dev", 0, "/api/v1/foxglove", "foxglove.websocket.v1");
  EXPECT_FALSE(fox.handshake_error()) << fox.handshake_error().message();
  WsClient stream(port, "https://app.foxglove.dev");
  EXPECT_FALSE(stream.handshake_error()) << stream.handshake_error().message();
  WsClient other(port, "https://app.foxglove.dev.evil.example", 0, "/api/v1/foxglove",
                 "foxglove.websocket.v1");
  EXPECT_EQ(other.handshake_response().result_int(), 403);
  WsClient http_scheme(port, "http://app.foxglove.dev", 0, "/api/v1/foxglove",
                       "foxglove.websocket.v1");
  EXPECT_EQ(http_scheme.handshake_response().result_int(), 403);
}

// A client that stops reading a channel of events is closed with 1008; one that stops reading
// telemetry only loses older samples.
TEST_F(HttpServerTest, FoxgloveStalledEventClientIsClosedAndTelemetryClientStaysOpen) {
  HttpServerOptions o;
  o.stream_event_queue_limit = 8;
  o.close_timeout = 30s;
  start(o);
  auto& fox = hub.foxglove();
  fox.advertise("boat", avk::app::foxglove::live_channels("boat"));
  json adv;
  auto events = foxglove_client(port, "/api/v1/foxglove", &adv, 4096);
  auto telemetry = foxglove_client(port, "/api/v1/foxglove", nullptr, 4096);
  events->send(json{{"op", "subscribe"},
                    {"subscriptions", {{{"id", 1}, {"channelId", channel_id(adv, "/boat/log")}}}}}
                   .dump());
  telemetry->send(
      json{{"op", "subscribe"},
           {"subscriptions", {{{"id", 2}, {"channelId", channel_id(adv, "/boat/pose")}}}}}
          .dump());
  ASSERT_TRUE(wait_for([&] { return fox.subscriber_count("/boat/log") == 1; }));
  ASSERT_TRUE(wait_for([&] { return fox.subscriber_count("/boat/pose") == 1; }));
  const std::string pad(64 * 1024, 'p');
  constexpr int kMessages = 2000;
  for (int i = 1; i <= kMessages; ++i) {
    fox.publish("/boat/log", static_cast<std::uint64_t>(i), R"({"pad":")" + pad + R"("})");
    fox.publish("/boat/pose", static_cast<std::uint64_t>(i), R"({"i":)" + std::to_string(i) + "}");
  }
  EXPECT_TRUE(wait_for([&] { return fox.subscriber_count("/boat/log") == 0; }));
  while (events->read_text()) {
  }
  EXPECT_EQ(events->close_reason().code, websocket::close_code::policy_error);
  // The telemetry client reads on and reaches the newest pose.
  int got = 0;
  for (;;) {
    const auto m = telemetry->read_text();
    ASSERT_TRUE(m) << telemetry->error().message();
    if (!telemetry->got_binary()) continue;
    ++got;
    if (m->substr(13) == R"({"i":)" + std::to_string(kMessages) + "}") break;
  }
  EXPECT_LT(got, kMessages);
  EXPECT_EQ(fox.subscriber_count("/boat/pose"), 1u);
}

// --- lifecycle -----------------------------------------------------------------------------

TEST_F(HttpServerTest, StopClosesStreamsWithGoingAway) {
  start();
  WsClient a(port);
  WsClient b(port);
  ASSERT_TRUE(a.read());
  ASSERT_TRUE(b.read());
  HttpClient idle(port);
  EXPECT_EQ(idle.request(http::verb::get, "/api/v1/echo").result_int(), 200);

  // A hang here fails by the test's own time limit; nothing below measures time.
  std::thread stopper([&] { server->stop(); });
  EXPECT_FALSE(a.read());
  EXPECT_EQ(a.error(), websocket::error::closed);
  EXPECT_EQ(a.close_reason().code, websocket::close_code::going_away);
  EXPECT_FALSE(b.read());
  EXPECT_EQ(b.close_reason().code, websocket::close_code::going_away);
  stopper.join();
  EXPECT_TRUE(idle.closed_by_server(20000ms));
  EXPECT_EQ(server->open_stream_sessions(), 0u);
  server->stop();                                      // idempotent
  EXPECT_THROW(RawClient{port}, beast::system_error);  // no longer accepting
}

TEST_F(HttpServerTest, DestructionWithOpenConnectionsNeitherHangsNorCrashes) {
  HttpServerOptions o;
  o.close_timeout = 300ms;
  start(o);
  // A stream client that stopped reading with a write stuck in the socket, a half header,
  // a half body and an idle keep-alive connection.
  WsClient stalled(port, "", 4096);
  ASSERT_TRUE(stalled.read());
  stalled.send(R"({"subscribe":["turn"]})");
  ASSERT_TRUE(stalled.read());
  const std::string pad(64 * 1024, 'q');
  for (int i = 0; i < 100; ++i)
    hub.publish("turn", 0.0, R"({"pad":")" + pad + R"("})");
  RawClient half_header(port);
  half_header.send("GET / HTTP/1.1\r\nHost");
  RawClient half_body(port);
  half_body.send("POST /api/v1/x HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Length: 10\r\n\r\nab");
  HttpClient idle(port);
  EXPECT_EQ(idle.request(http::verb::get, "/api/v1/echo").result_int(), 200);

  std::atomic<bool> publishing{true};
  std::thread publisher([&] {
    // A publisher that keeps going while the server goes away must not touch a dead session.
    while (publishing) {
      hub.publish("turn", 0.0, "{}");
      hub.publish("nav", 0.0, "{}");
      std::this_thread::sleep_for(100us);
    }
  });
  server.reset();  // returns (within close_timeout): a hang fails by the test's time limit
  std::this_thread::sleep_for(20ms);
  publishing = false;
  publisher.join();
  EXPECT_TRUE(half_header.read_until_closed(20000ms).closed());
}

TEST_F(HttpServerTest, StartThenStopWithoutClients) {
  start();
  server->stop();
  server.reset();
  HttpServer never_started(HttpServerOptions{}, api, hub);
  EXPECT_EQ(never_started.port(), 0);
}

TEST_F(HttpServerTest, BindFailureNamesTheAddress) {
  start();
  HttpServerOptions o;
  o.port = port;
  HttpServer second(o, api, hub);
  try {
    second.start();
    FAIL() << "a second server bound the same port";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("127.0.0.1:" + std::to_string(port)), std::string::npos)
        << e.what();
  }
  HttpServerOptions bad;
  bad.bind_address = "not-an-address";
  EXPECT_THROW(HttpServer(bad, api, hub).start(), std::runtime_error);
}

// --- hostile clients ------------------------------------------------------------------------

// The responses in raw bytes, one after the other: {status, Content-Length, body}.
struct RawResponse {
  int status = 0;
  std::string content_length;
  std::string body;
};
std::vector<RawResponse> split_responses(std::string data, bool first_is_head) {
  std::vector<RawResponse> out;
  bool head = first_is_head;
  while (!data.empty()) {
    RawResponse r;
    r.status = status_of(data);
    const auto end = data.find("\r\n\r\n");
    if (r.status == 0 || end == std::string::npos) {
      r.body = data;  // not a response: what a broken framing left over
      out.push_back(r);
      break;
    }
    const std::string header = data.substr(0, end);
    const auto cl = header.find("Content-Length: ");
    if (cl != std::string::npos)
      r.content_length = header.substr(cl + 16, header.find("\r\n", cl) - cl - 16);
    std::size_t length = head || r.content_length.empty() ? 0 : std::stoul(r.content_length);
    r.body = data.substr(end + 4, length);
    data = data.substr(std::min(data.size(), end + 4 + length));
    out.push_back(r);
    head = false;
  }
  return out;
}

// Regression: a HEAD answered with a body (404 static, 426 stream) broke the framing of
// the next response on the same connection.
TEST_F(HttpServerTest, HeadAnswersCarryNoBodyAndKeepAliveFramingHolds) {
  start();
  for (const std::string target : {"/missing.html", "/api/v1/stream", "/api/v1/echo"}) {
    RawClient c(port);
    c.send("HEAD " + target + " HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n" +
           "GET /api/v1/echo HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n");
    const auto raw = c.read_until_closed(5000ms);
    const auto responses = split_responses(raw.data, true);
    ASSERT_EQ(responses.size(), 2u) << target << "\n" << raw.data;
    EXPECT_NE(responses[0].content_length, "0") << target;  // the GET's length
    EXPECT_EQ(responses[1].status, 200) << target << "\n" << raw.data;
    EXPECT_EQ(json::parse(responses[1].body)["method"], "GET") << target;
  }
}

// Regression: with Host: evil.example (DNS rebinding) REST answered and the stream
// upgraded on loopback.
TEST_F(HttpServerTest, OnlyHostsOfThisServerAreAnswered) {
  HttpServerOptions o;
  o.allowed_hosts = {"Boat.Example"};
  start(o);
  const std::string p = std::to_string(port);
  const auto with_host = [&](const std::string& host) {
    return status_of(raw_exchange(port, "GET /api/v1/echo HTTP/1.1\r\nHost: " + host +
                                            "\r\nConnection: close\r\n\r\n")
                         .data);
  };
  EXPECT_EQ(with_host("evil.example:" + p), 421);
  EXPECT_EQ(with_host("evil.example"), 421);
  EXPECT_EQ(with_host("localhost.evil.example:" + p), 421);
  EXPECT_EQ(api.calls.load(), 0);
  for (const std::string& host : std::vector<std::string>{
           "127.0.0.1:" + p, "localhost:" + p, "LOCALHOST", "[::1]:" + p, "192.0.2.7:8080",
           "[2001:db8::1]", "boat.example:" + p, "app.localhost:" + p})
    EXPECT_EQ(with_host(host), 200) << host;
  // The stream: a matching Origin does not help a foreign Host.
  const auto upgrade = raw_exchange(port, "GET /api/v1/stream HTTP/1.1\r\nHost: evil.example:" + p +
                                              "\r\nOrigin: http://evil.example:" + p +
                                              "\r\nConnection: Upgrade\r\nUpgrade: websocket\r\n"
                                              "Sec-WebSocket-Version: 13\r\nSec-WebSocket-Key: "
                                              "dGhlIHNhbXBsZSBub25jZQ==\r\n\r\n");
  EXPECT_EQ(status_of(upgrade.data), 403) << upgrade.data;
  EXPECT_EQ(server->open_stream_sessions(), 0u);
  // HTTP/1.1 without Host is malformed; HTTP/1.0 tools may leave it out.
  EXPECT_EQ(status_of(raw_exchange(port, "GET /api/v1/echo HTTP/1.1\r\n\r\n").data), 400);
  EXPECT_EQ(status_of(raw_exchange(port, "GET /api/v1/echo HTTP/1.0\r\n\r\n").data), 200);
}

// Regression: with two Host headers the first was used, on REST and on the stream upgrade.
TEST_F(HttpServerTest, TwoHostHeadersAre400EvenOnTheStreamUpgrade) {
  start();
  const std::string p = std::to_string(port);
  for (const std::string& hosts : std::vector<std::string>{
           "Host: 127.0.0.1:" + p + "\r\nHost: evil.example", "Host: 127.0.0.1\r\nHost: 127.0.0.1",
           "Host: evil.example\r\nhost: 127.0.0.1:" + p}) {
    const auto rest = raw_exchange(
        port, "GET /api/v1/echo HTTP/1.1\r\n" + hosts + "\r\nConnection: close\r\n\r\n");
    EXPECT_EQ(status_of(rest.data), 400) << hosts << "\n" << rest.data;
    EXPECT_NE(rest.data.find("more than one Host header"), std::string::npos) << rest.data;
    const auto upgrade = raw_exchange(port, "GET /api/v1/stream HTTP/1.1\r\n" + hosts +
                                                "\r\nConnection: Upgrade\r\nUpgrade: websocket\r\n"
                                                "Sec-WebSocket-Version: 13\r\nSec-WebSocket-Key: "
                                                "dGhlIHNhbXBsZSBub25jZQ==\r\n\r\n");
    EXPECT_EQ(status_of(upgrade.data), 400) << hosts << "\n" << upgrade.data;
  }
  EXPECT_EQ(api.calls.load(), 0);
  EXPECT_EQ(server->open_stream_sessions(), 0u);
  // HTTP/1.0 is held to the same rule.
  EXPECT_EQ(status_of(raw_exchange(port,
                                   "GET /api/v1/echo HTTP/1.0\r\nHost: 127.0.0.1\r\n"
                                   "Host: 127.0.0.1\r\n\r\n")
                          .data),
            400);
}

// Regression: invalid UTF-8 in the path or the query answered 500 with nlohmann's
// type_error.316 text.
TEST_F(HttpServerTest, InvalidUtf8InPathIs404AndInQueryIs400NamingIt) {
  start();
  HttpClient client(port);
  auto res = client.request(http::verb::get, "/api/v1/%ff");
  EXPECT_EQ(res.result_int(), 404);
  EXPECT_EQ(res[http::field::content_type], "application/problem+json");
  EXPECT_NE(json::parse(res.body())["detail"].get<std::string>().find("path"), std::string::npos);
  res = client.request(http::verb::get, "/api/v1/turns?limit=%ff");
  EXPECT_EQ(res.result_int(), 400);
  EXPECT_NE(json::parse(res.body())["detail"].get<std::string>().find("'limit'"), std::string::npos)
      << res.body();
  for (const std::string target :
       {"/api/v1/x?speed=%c3%28", "/api/v1/x?a=%ed%a0%80", "/api/v1/x?%fe=1",
        "/api/v1/x?a=%f4%90%80%80", "/api/v1/x?a=%c0%af"}) {
    res = client.request(http::verb::get, target);
    EXPECT_EQ(res.result_int(), 400) << target;
    EXPECT_EQ(res.body().find("json.exception"), std::string::npos) << target;
  }
  EXPECT_EQ(api.calls.load(), 0);
  // Well-formed UTF-8 passes.
  res = client.request(http::verb::get, "/api/v1/%c3%a9?v=%e2%82%ac");
  ASSERT_EQ(res.result_int(), 200);
  EXPECT_EQ(json::parse(res.body())["query"]["v"], "\xe2\x82\xac");
}

// Regression: a 500 carried the library's exception text to the client.
TEST_F(HttpServerTest, A500FromTheApiCarriesNoInternals) {
  start();
  const auto res = get(port, "/api/v1/status/500");
  EXPECT_EQ(res.result_int(), 500);
  EXPECT_EQ(res[http::field::content_type], "application/problem+json");
  EXPECT_EQ(json::parse(res.body())["detail"], "internal error (see the server log)");
  EXPECT_EQ(res.body().find("/api/v1/status/500"), std::string::npos);
}

// Regression: a JSON body nested 100,000 deep overflowed the stack of a handler.
TEST_F(HttpServerTest, JsonBodiesNestedTooDeepAre400BeforeAnyHandler) {
  start();
  HttpClient client(port);
  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  auto res = client.request(http::verb::post, "/api/v1/models", "{\"missions\":" + deep + "}",
                            {{"Content-Type", "application/json"}});
  EXPECT_EQ(res.result_int(), 400);
  EXPECT_NE(json::parse(res.body())["detail"].get<std::string>().find("deeper than 64"),
            std::string::npos);
  // Recognised by its first character whatever the type says; brackets inside strings are text.
  res = client.request(http::verb::post, "/api/v1/models", deep, {{"Content-Type", "text/plain"}});
  EXPECT_EQ(res.result_int(), 400);
  EXPECT_EQ(api.calls.load(), 0);
  const std::string ok = "{\"a\":\"" + std::string(1000, '[') + "\",\"b\":" + std::string(63, '[') +
                         std::string(63, ']') + "}";
  res = client.request(http::verb::post, "/api/v1/models", ok,
                       {{"Content-Type", "application/json"}});
  EXPECT_EQ(res.result_int(), 200);
}

// Regression: a body was read (up to 64 MB) before the token was checked. The header
// alone decides: the 401 arrives although the 60 MB announced are never sent.
TEST_F(HttpServerTest, RefusedBeforeTheBodyIsRead) {
  start();
  RawClient c(port);
  c.send(
      "POST /api/v1/guarded HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\n"
      "Content-Length: 60000000\r\n\r\n{");
  const auto raw = c.read_until_closed(10000ms);
  EXPECT_EQ(status_of(raw.data), 401) << raw.data;
  EXPECT_TRUE(raw.closed());
  EXPECT_EQ(api.calls.load(), 0);
  // The route's own limit, from the header too.
  const auto small = raw_exchange(
      port, "POST /api/v1/small HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Length: 11\r\n\r\n");
  EXPECT_EQ(status_of(small.data), 413) << small.data;
  // With the token the body is read and handled.
  const auto ok = HttpClient(port).request(http::verb::post, "/api/v1/guarded", "{}",
                                           {{"Authorization", "Bearer ok"}});
  EXPECT_EQ(ok.result_int(), 200);
  EXPECT_EQ(api.calls.load(), 1);
}

// A plain POSIX socket: trickles bytes while watching for the server's close.
class TrickleClient {
 public:
  explicit TrickleClient(unsigned short port) : fd_(::socket(AF_INET, SOCK_STREAM, 0)) {
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(port);
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (::connect(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0)
      throw std::runtime_error("connect");
  }
  ~TrickleClient() { ::close(fd_); }
  bool send(std::string_view bytes) {
    return ::send(fd_, bytes.data(), bytes.size(), MSG_NOSIGNAL) ==
           static_cast<ssize_t>(bytes.size());
  }
  // Whether the server closed within wait (reset, or EOF after whatever it answered).
  bool closed_within(std::chrono::milliseconds wait) {
    pollfd p{fd_, POLLIN, 0};
    if (::poll(&p, 1, static_cast<int>(wait.count())) <= 0) return false;
    char b[512];
    for (;;) {
      const auto n = ::recv(fd_, b, sizeof b, MSG_DONTWAIT);
      if (n == 0) return true;
      if (n < 0) return errno != EAGAIN && errno != EWOULDBLOCK;
    }
  }

 private:
  int fd_;
};

// Regression: a body sent one byte per pause shorter than the idle timeout was never
// cut. Now the whole request has a deadline.
TEST_F(HttpServerTest, ABodyTrickledInIsCutAtTheRequestDeadline) {
  HttpServerOptions o;
  o.request_timeout = 300ms;
  o.idle_timeout = 30s;
  start(o);
  TrickleClient c(port);
  ASSERT_TRUE(
      c.send("POST /api/v1/x HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Length: 100000\r\n\r\n"));
  bool closed = false;
  // 100 ms between bytes, far under the idle timeout; at most 60 s in all.
  for (int i = 0; i < 600 && !closed; ++i) {
    if (!c.send("z")) break;
    closed = c.closed_within(100ms);
  }
  EXPECT_TRUE(closed);
  EXPECT_EQ(api.calls.load(), 0);
  EXPECT_EQ(get(port, "/api/v1/echo").result_int(), 200);
}

// Connections from one address that have sent a request are bounded: at the cap the oldest one
// idle between requests makes room for the new one's request.
TEST_F(HttpServerTest, AtThePerAddressCapTheOldestIdleConnectionMakesRoom) {
  HttpServerOptions o;
  o.max_connections_per_address = 4;
  start(o);
  std::vector<std::unique_ptr<HttpClient>> idle;
  for (int i = 0; i < 4; ++i) {
    idle.push_back(std::make_unique<HttpClient>(port));
    ASSERT_EQ(idle.back()->request(http::verb::get, "/api/v1/echo").result_int(), 200);
  }
  EXPECT_EQ(get(port, "/api/v1/echo").result_int(), 200);
  EXPECT_TRUE(idle[0]->closed_by_server());
  EXPECT_EQ(idle[3]->request(http::verb::get, "/api/v1/echo").result_int(), 200);
}

// Regression: the per-address cap counted connections that had not sent their request yet, so a
// burst of connections from one address (dashboards behind a proxy) closed its own members
// before they asked. Those are bounded by the header timeout instead.
TEST_F(HttpServerTest, ConnectionsThatHaveNotAskedYetAreNotCutByThePerAddressCap) {
  HttpServerOptions o;
  o.max_connections_per_address = 4;
  start(o);
  std::vector<std::unique_ptr<RawClient>> waiting;
  for (int i = 0; i < 12; ++i)
    waiting.push_back(std::make_unique<RawClient>(port));
  for (auto& c : waiting) {
    c->send("GET /api/v1/echo HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n");
    EXPECT_EQ(status_of(c->read_until_closed().data), 200);
  }
}

// Regression: with every slot taken, the oldest waiting connection of any address made room, so
// one address's flood of slow connections closed another client's. The address holding the
// most connections makes room now.
TEST_F(HttpServerTest, AtTheTotalCapTheAddressHoldingTheMostMakesRoom) {
  HttpServerOptions o;
  o.max_connections = 6;
  start(o);
  HttpClient other(port, "127.0.0.2");
  ASSERT_EQ(other.request(http::verb::get, "/api/v1/echo").result_int(), 200);
  std::vector<std::unique_ptr<TrickleClient>> slow;
  for (int i = 0; i < 5; ++i) {
    slow.push_back(std::make_unique<TrickleClient>(port));
    slow.back()->send("GET /api/v1/echo HTTP/1.1\r\n");  // and never the rest
  }
  // Full (6): this connection makes the oldest of 127.0.0.1's slow ones close, not 127.0.0.2's
  // older idle one.
  EXPECT_EQ(get(port, "/api/v1/echo").result_int(), 200);
  EXPECT_TRUE(slow[0]->closed_within(20000ms));
  EXPECT_EQ(other.request(http::verb::get, "/api/v1/echo").result_int(), 200);
}

// When no connection can make room (open streams), a new one gets a 503, not a silent hang.
TEST_F(HttpServerTest, OverTheTotalCapWithNothingToCloseIs503) {
  HttpServerOptions o;
  o.max_connections = 2;
  start(o);
  WsClient a(port);
  ASSERT_FALSE(a.handshake_error());
  ASSERT_TRUE(wait_for([&] { return server->open_stream_sessions() == 1; }));
  WsClient b(port);
  ASSERT_FALSE(b.handshake_error());
  ASSERT_TRUE(wait_for([&] { return server->open_stream_sessions() == 2; }));
  const auto refused = raw_exchange(port, "GET /api/v1/echo HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n");
  EXPECT_EQ(status_of(refused.data), 503) << refused.data;
  EXPECT_NE(refused.data.find("application/problem+json"), std::string::npos);
  EXPECT_TRUE(refused.closed());
  EXPECT_EQ(api.calls.load(), 0);
}

// Regression: a burst of 100 WebSocket clients from one address lost 36: the per-address cap of
// 64 counted the connections whose upgrade had not been read yet and closed them to make room.
TEST_F(HttpServerTest, ABurstOfUpgradesFromOneAddressAllGetSessions) {
  start();
  constexpr int kClients = 100;
  net::io_context ioc;
  std::vector<std::unique_ptr<websocket::stream<beast::tcp_stream>>> clients;
  std::atomic<int> opened{0};
  std::atomic<int> failed{0};
  for (int i = 0; i < kClients; ++i) {
    clients.push_back(std::make_unique<websocket::stream<beast::tcp_stream>>(ioc));
    auto& ws = *clients.back();
    beast::get_lowest_layer(ws).async_connect(loopback(port), [&ws, &opened, &failed,
                                                               this](beast::error_code ec) {
      if (ec) return void(++failed);
      ws.async_handshake("127.0.0.1:" + std::to_string(port), "/api/v1/stream",
                         [&opened, &failed](beast::error_code hec) { ++(hec ? failed : opened); });
    });
  }
  ioc.run_for(30s);
  EXPECT_EQ(opened.load(), kClients);
  EXPECT_EQ(failed.load(), 0);
  EXPECT_TRUE(wait_for([&] { return server->open_stream_sessions() == kClients; }, 20000ms))
      << server->open_stream_sessions();
}

// Live sessions from one address have a cap of their own: one over it is a 503 with
// Retry-After, and a place that frees up is taken again.
TEST_F(HttpServerTest, LiveSessionsPerAddressAreCappedWith503AndRetryAfter) {
  HttpServerOptions o;
  o.max_streams_per_address = 2;
  start(o);
  auto a = std::make_unique<WsClient>(port);
  ASSERT_FALSE(a->handshake_error());
  WsClient b(port, "", 0, "/api/v1/foxglove", "foxglove.websocket.v1");
  ASSERT_FALSE(b.handshake_error());
  WsClient over(port);
  EXPECT_TRUE(over.handshake_error());
  EXPECT_EQ(over.handshake_response().result_int(), 503);
  EXPECT_FALSE(over.handshake_response()[http::field::retry_after].empty());
  // The server counts a session once its handshake's answer is written, which the client may
  // see first: wait for the count, do not race it.
  for (const auto deadline = Clock::now() + 20s;
       server->open_stream_sessions() != 2u && Clock::now() < deadline;)
    std::this_thread::sleep_for(5ms);
  EXPECT_EQ(server->open_stream_sessions(), 2u);
  a.reset();
  bool reopened = false;
  for (const auto deadline = Clock::now() + 20s; !reopened && Clock::now() < deadline;) {
    WsClient again(port);
    reopened = !again.handshake_error();
    if (!reopened) std::this_thread::sleep_for(20ms);
  }
  EXPECT_TRUE(reopened);
}

// --- request work on the request workers ---------------------------------------------------

std::string raw_get(const std::string& target) {
  return "GET " + target + " HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n";
}

bool has_header(const std::string& raw, const std::string& line) {
  return raw.find("\r\n" + line + "\r\n") != std::string::npos;
}

// Regression: request work ran on the two I/O threads, so two slow requests stalled /health and
// the live stream. It runs on the request workers; with the only worker busy and the queue full,
// the next request is a 503 with Retry-After while /health and the stream still answer.
TEST_F(HttpServerTest, ABusyPoolAnswers503WhileHealthAndTheStreamAnswer) {
  HttpServerOptions o;
  o.request_workers = 1;
  o.request_queue = 1;
  start(o);
  const auto [first, second] = the_worker_busy_and_one_waiting(port);
  ASSERT_TRUE(first && second);

  const auto refused = raw_exchange(port, raw_get("/api/v1/echo"));
  EXPECT_EQ(status_of(refused.data), 503) << refused.data;
  EXPECT_TRUE(has_header(refused.data, "Retry-After: 1")) << refused.data;
  EXPECT_NE(refused.data.find("application/problem+json"), std::string::npos);

  EXPECT_EQ(get(port, "/api/v1/health").result_int(), 200);
  WsClient ws(port);
  ASSERT_FALSE(ws.handshake_error());
  ASSERT_TRUE(ws.read());  // hello
  ws.send(R"({"subscribe":["turn"]})");
  ASSERT_TRUE(ws.read());  // subscribed
  hub.publish("turn", 1.0, R"({"id":1})");
  const auto message = ws.read();
  ASSERT_TRUE(message);
  EXPECT_EQ((*message)["data"]["id"], 1);

  api.open_gate();
  EXPECT_EQ(status_of(first->read_until_closed().data), 200);
  EXPECT_EQ(status_of(second->read_until_closed().data), 200);
}

// Expensive requests run on at most expensive_requests workers, the others stay for cheap ones,
// and one client address may have expensive_requests_per_address of them running or waiting.
TEST_F(HttpServerTest, ExpensiveRequestsAreLimitedInAllAndPerAddress) {
  HttpServerOptions o;
  o.request_workers = 2;
  o.expensive_requests = 1;
  o.expensive_requests_per_address = 1;
  start(o);
  RawClient heavy(port);
  heavy.send(raw_get("/api/v1/block?cost=expensive"));
  ASSERT_TRUE(wait_for([&] { return api.blocked.load() == 1; }));

  const auto same_address = raw_exchange(port, raw_get("/api/v1/echo?cost=expensive"));
  EXPECT_EQ(status_of(same_address.data), 429) << same_address.data;
  EXPECT_TRUE(has_header(same_address.data, "Retry-After: 1")) << same_address.data;

  // Another address is let in, and waits for the expensive worker.
  HttpClient other(port, "127.0.0.2");
  std::optional<http::response<http::string_body>> other_answer;
  std::thread asking(
      [&] { other_answer = other.request(http::verb::get, "/api/v1/echo?cost=expensive"); });
  EXPECT_TRUE(wait_for([&] { return server->waiting_requests() == 1; }));
  // Cheap work takes the other worker meanwhile.
  EXPECT_EQ(get(port, "/api/v1/echo").result_int(), 200);
  api.open_gate();
  asking.join();
  ASSERT_TRUE(other_answer);
  EXPECT_EQ(other_answer->result_int(), 200);
  EXPECT_EQ(status_of(heavy.read_until_closed().data), 200);
  // Answered: the address has its share back.
  EXPECT_EQ(get(port, "/api/v1/echo?cost=expensive").result_int(), 200);
}

// A request still waiting for a worker when the server stops is answered 503 at once, not left
// to the stop's deadline.
TEST_F(HttpServerTest, StopAnswersTheRequestsStillWaiting) {
  HttpServerOptions o;
  o.request_workers = 1;
  start(o);
  const auto [first, waiting] = the_worker_busy_and_one_waiting(port);
  ASSERT_TRUE(first && waiting);
  std::thread stopping([&] { server->stop(); });
  const auto answer = waiting->read_until_closed();
  EXPECT_EQ(status_of(answer.data), 503) << answer.data;
  EXPECT_NE(answer.data.find("shutting down"), std::string::npos);
  api.open_gate();
  stopping.join();
}

}  // namespace
