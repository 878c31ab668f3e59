#pragma once
// The station's HTTP/WebSocket transport: REST under /api/v1 (handed to an Api), the live stream
// at /api/v1/stream (fed by a StreamSource) and static files for the dashboard. Beast stays behind
// the pimpl so that whoever starts a server does not compile it.

#include <chrono>
#include <cstddef>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "server/api_types.hpp"
#include "server/http/live_sources.hpp"

namespace avk::server {

// The environment variable `avk serve` takes more allowed host names from (comma separated),
// beside --allow-host: the Docker image's command line is fixed.
inline constexpr const char* kAllowHostsVariable = "AVK_ALLOW_HOSTS";

struct HttpServerOptions {
  std::string bind_address = "127.0.0.1";
  unsigned short port = 0;  // 0: an ephemeral port (tests)
  int threads = 2;
  std::optional<std::string> web_root;  // static files; none: only the API
  std::size_t header_limit = 8 * 1024;  // larger -> 431 and close
  // Larger -> 413 and close. The Api may give a route another limit (Api::admit).
  std::size_t body_limit = 1 << 20;
  // A client that has not sent a complete header by then is disconnected (slowloris).
  std::chrono::milliseconds header_timeout{10000};
  // Header and body together, from the request's first byte: a body trickled in at one byte
  // per pause shorter than idle_timeout is still cut here.
  std::chrono::milliseconds request_timeout{30000};
  // Open connections (HTTP and WebSocket) in all. When full, a connection still waiting for (or
  // reading) a request is closed to make room — the oldest of the address holding the most — so
  // a flood of slow connections cannot keep /health out; when none can be closed the new one gets
  // a 503 and is closed.
  std::size_t max_connections = 512;
  // HTTP connections from one address that have sent a request. At the cap the address's oldest
  // one idle between requests is closed to make room, else the request gets a 503. A connection
  // that has sent nothing yet is not counted (header_timeout bounds it), so a burst of upgrades
  // from one address (a dashboard behind a proxy) is not cut before it asks.
  std::size_t max_connections_per_address = 64;
  // Live WebSocket sessions (the stream and the Foxglove connection) from one address, counted
  // from the accepted upgrade request until the session ends; one more is a 503 with
  // Retry-After instead of a 101.
  std::size_t max_streams_per_address = 256;
  // Request bodies that are JSON (by type or by their first character) nested deeper are a 400
  // before any handler parses them: nothing recursive ever sees an attacker's depth.
  std::size_t json_depth_limit = 64;
  // Host names (besides loopback names and IP literals) the server answers to; anything else is
  // 421 (403 for the stream upgrade), which defeats DNS rebinding.
  std::vector<std::string> allowed_hosts;
  // Origins (scheme://host[:port], lower case) whose pages may open the live stream and the
  // Foxglove connection besides the server's own, e.g. https://app.foxglove.dev for Foxglove's
  // web edition. Empty: only same-origin pages (and tools that send no Origin).
  std::vector<std::string> allowed_origins;
  // Keep-alive: how long a connection may wait for its next request; also the longest pause
  // inside a body or a response write, and the WebSocket's dead-peer detection (pings at half).
  std::chrono::milliseconds idle_timeout{30000};
  // How long a WebSocket close handshake (and a write stuck in front of it) may take before the
  // socket is cut, and how long stop() waits for in-flight responses before it cuts the rest.
  std::chrono::milliseconds close_timeout{5000};
  // The API's request work runs on these workers, never on the I/O threads (but for immediate
  // routes such as /health): `threads` only read, write and route. A request that finds
  // request_queue requests waiting is a 503 with Retry-After. Expensive requests (Route::workload)
  // run on at most expensive_requests workers at once, so the others stay free for cheap ones;
  // a client address with expensive_requests_per_address of them running or waiting gets a 429
  // with Retry-After for the next.
  std::size_t request_workers = 4;
  std::size_t request_queue = 64;
  std::size_t expensive_requests = 2;
  std::size_t expensive_requests_per_address = 4;
  std::size_t stream_event_queue_limit = 256;  // per WebSocket session
  std::string server_version;                  // for the hello
};

class HttpServer {
 public:
  // api and hub must outlive the server.
  HttpServer(HttpServerOptions options, Api& api, StreamSource& hub);
  ~HttpServer();  // stops
  HttpServer(const HttpServer&) = delete;
  HttpServer& operator=(const HttpServer&) = delete;

  // Binds (throws std::runtime_error naming address:port on failure) and runs the io threads.
  // Once only: a stopped server is not restarted.
  void start();
  unsigned short port() const;  // the bound port (0 before start)
  // Graceful: stops accepting, closes WebSockets with 1001 (going away), lets in-flight
  // responses finish (at most close_timeout), joins the threads. Idempotent. Not from a handler.
  void stop();
  std::size_t open_stream_sessions() const;
  // API requests waiting for a request worker.
  std::size_t waiting_requests() const;

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace avk::server
