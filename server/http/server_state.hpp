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
#include "server/foxglove_hub.hpp"
#include "server/http/http_server.hpp"
#include "server/http/static_files.hpp"
#include "server/stream_hub.hpp"

namespace avk::server {

class HttpSession;
class LiveSession;
class DetachableSink;

class ServerState {
 public:
  ServerState(HttpServerOptions options, Api& api, StreamHub& hub);

  const HttpServerOptions& options() const { return options_; }
  Api& api() { return api_; }
  StreamHub& hub() { return hub_; }
  FoxgloveHub& foxglove() { return hub_.foxglove(); }
  const StaticFiles& static_files() const { return static_files_; }
  bool stopping() const { return stopping_.load(); }

  // Whether a connection from this address may be served: true when there is room, or when the
  // oldest connection still waiting for its request (from that address when the address is
  // over its share, else from any) has been told to close to make room; false: refuse it.
  bool make_room(const std::string& address);

  // Sessions add themselves when they start and remove themselves in their destructors.
  void add(const std::shared_ptr<HttpSession>& session);
  void remove(const HttpSession* session);
  // A live WebSocket session (the stream or the Foxglove connection) and what its publisher
  // holds.
  void add(const std::shared_ptr<LiveSession>& session,
           const std::shared_ptr<DetachableSink>& sink);
  void remove(const LiveSession* session);

  // A session counts as open from its accepted handshake until it starts to close.
  void stream_opened() { ++open_streams_; }
  void stream_closed() { --open_streams_; }
  std::size_t open_stream_sessions() const { return open_streams_.load(); }

  // Sets stopping and asks every registered session to wind down (each on its own strand).
  void begin_stop();
  // Whether every session is gone by the deadline.
  bool wait_until_idle(std::chrono::steady_clock::time_point deadline);
  // After the io threads are joined: the hub may still hold the sinks, and a publisher must not
  // reach a session whose io_context is about to be destroyed.
  void detach_sinks();

 private:
  HttpServerOptions options_;
  Api& api_;
  StreamHub& hub_;
  StaticFiles static_files_;
  std::atomic<bool> stopping_{false};
  std::atomic<std::size_t> open_streams_{0};

  std::mutex mutex_;
  std::condition_variable idle_;
  struct HttpEntry {
    std::weak_ptr<HttpSession> session;
    std::string address;
    std::uint64_t order = 0;  // accept order: the lowest is the oldest
    bool evicted = false;     // told to close; no longer counted
  };
  std::map<const HttpSession*, HttpEntry> http_sessions_;
  std::uint64_t accepted_ = 0;
  struct StreamEntry {
    std::weak_ptr<LiveSession> session;
    std::shared_ptr<DetachableSink> sink;
  };
  std::map<const LiveSession*, StreamEntry> stream_sessions_;
};

}  // namespace avk::server
