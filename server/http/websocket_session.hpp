#pragma once
// One client of the live stream at /api/v1/stream (server/http/live_websocket.hpp for the queue,
// the timeouts and how a session ends): telemetry (nav, helm, current) is latest-value-wins per
// topic and vehicle, events are queued, and a client that lets more than stream_event_queue_limit
// of them pile up is closed with 1008 to re-sync over REST. A client may ask for at most max_hz
// nav and helm messages a second per vehicle (a dashboard of a fleet at x10 needs far fewer than
// the 100 a second each vehicle sends).

#include <chrono>
#include <map>
#include <memory>
#include <set>
#include <string>

#include "server/api_types.hpp"
#include "server/http/live_websocket.hpp"

namespace avk::server {

class WebSocketStreamSink;

class WebSocketSession
    : public LiveWebSocket<WebSocketSession, std::shared_ptr<const StreamMessage>> {
 public:
  // address: the client's, reserved with ServerState::reserve_stream.
  WebSocketSession(tcp::socket&& socket, std::shared_ptr<ServerState> state, std::string address);
  ~WebSocketSession() override;

  // Completes the upgrade the HTTP session has read.
  void run(Request request);
  // Any thread; returns at once.
  void deliver(std::shared_ptr<const StreamMessage> message);

 private:
  friend class LiveWebSocket<WebSocketSession, std::shared_ptr<const StreamMessage>>;
  void on_open();
  void on_text(const std::string& text);
  void on_binary();
  const char* too_slow_reason() const { return "too slow: re-sync over REST"; }
  template <class Handler>
  bool start_write(const std::shared_ptr<const StreamMessage>& m, Handler&& done) {
    ws_.text(true);
    ws_.async_write(net::buffer(*m->payload), std::forward<Handler>(done));
    return true;
  }
  void leave_hub();
  void send_control(std::string text);

  std::shared_ptr<WebSocketStreamSink> sink_;
  std::set<std::string> topics_;
  // On the strand: the client's telemetry rate (0: all) and when each key's last frame was taken.
  double max_hz_ = 0.0;
  std::map<std::string, std::chrono::steady_clock::time_point> taken_;
};

}  // namespace avk::server
