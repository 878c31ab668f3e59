#pragma once
// What every connection of one server shares: the options, the Api and the hub, the static
// files, and a registry of live sessions so that stop() can reach them.

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "server/api_types.hpp"
#include "server/http/http_server.hpp"
#include "server/http/live_sources.hpp"
#include "server/http/request_pool.hpp"
#include "server/http/static_files.hpp"

namespace avk::server {

class HttpSession;
class LiveSession;
class DetachableSink;

class ServerState {
 public:
  ServerState(HttpServerOptions options, Api& api, StreamSource& hub);

  const HttpServerOptions& options() const { return options_; }
  Api& api() { return api_; }
  StreamSource& hub() { return hub_; }
  FoxgloveSource& foxglove() { return hub_.foxglove_source(); }
  const StaticFiles& static_files() const { return static_files_; }
  RequestPool& pool() { return pool_; }
  bool stopping() const { return stopping_.load(); }

  // Whether a new connection may be served: true while the server holds fewer than
  // max_connections, or when a connection still waiting for (or reading) a request has been told
  // to close to make room — the oldest of the address that holds the most HTTP connections, so
  // that one address's flood closes its own connections, not another's. False: refuse it.
  bool make_room();
  // At a connection's first complete request header: whether its address may have one more
  // connection that has sent a request (max_connections_per_address). At the cap, the address's
  // oldest such connection now idle between requests is told to close to make room; false when
  // none can be. Connections that have not sent a request yet (a burst of WebSocket handshakes
  // behind one proxy) are not counted here: the header timeout bounds them.
  bool establish(const HttpSession* session);

  // Sessions add themselves when they start and remove themselves in their destructors.
  void add(const std::shared_ptr<HttpSession>& session);
  void remove(const HttpSession* session);
  // Before a live WebSocket session (the stream or the Foxglove connection) is made for an
  // upgrade: whether its address may have one more (max_streams_per_address). The reservation
  // is the session's from add() on and ends with its remove().
  bool reserve_stream(const std::string& address);
  // A live session and what its publisher holds; address: the one reserve_stream() was given.
  void add(const std::shared_ptr<LiveSession>& session, const std::shared_ptr<DetachableSink>& sink,
           const std::string& address);
  void remove(const LiveSession* session);

  // A session counts as open from its accepted handshake until it starts to close.
  void stream_opened() { ++open_streams_; }
  void stream_closed() { --open_streams_; }
  std::size_t open_stream_sessions() const { return open_streams_.load(); }

  // Sets stopping, cancels the API requests still waiting for a worker (each answers 503) and
  // asks every registered session to wind down (each on its own strand).
  void begin_stop();
  // Whether every session is gone by the deadline.
  bool wait_until_idle(std::chrono::steady_clock::time_point deadline);
  // After the io threads are joined: the hub may still hold the sinks, and a publisher must not
  // reach a session whose io_context is about to be destroyed.
  void detach_sinks();

 private:
  HttpServerOptions options_;
  Api& api_;
  StreamSource& hub_;
  StaticFiles static_files_;
  RequestPool pool_;
  std::atomic<bool> stopping_{false};
  std::atomic<std::size_t> open_streams_{0};

  std::mutex mutex_;
  std::condition_variable idle_;
  struct HttpEntry {
    std::weak_ptr<HttpSession> session;
    std::string address;
    std::uint64_t order = 0;   // accept order: the lowest is the oldest
    bool evicted = false;      // told to close; no longer counted
    bool established = false;  // has sent a request
  };
  std::map<const HttpSession*, HttpEntry> http_sessions_;
  std::uint64_t accepted_ = 0;
  struct StreamEntry {
    std::weak_ptr<LiveSession> session;
    std::shared_ptr<DetachableSink> sink;
    std::string address;
  };
  std::map<const LiveSession*, StreamEntry> stream_sessions_;
  std::map<std::string, std::size_t> streams_by_address_;  // reserved or open
};

}  // namespace avk::server
