#pragma once
// One client of the live stream at /api/v1/stream. The hub's publisher must never wait for a
// client, and Beast queues nothing itself, so the session keeps its own write queue on its
// strand: telemetry (nav, helm) is latest-value-wins — an unsent older frame of the topic is
// replaced in place, keeping its position — events are queued, and a client that lets more than
// stream_event_queue_limit of them pile up is closed with 1008 to re-sync over REST.

#include <cstddef>
#include <memory>
#include <set>
#include <string>

#include "server/api_types.hpp"
#include "server/http/beast.hpp"
#include "server/http/live_session.hpp"
#include "server/send_queue.hpp"

namespace avk::server {

class ServerState;
class WebSocketStreamSink;

class WebSocketSession : public LiveSession, public std::enable_shared_from_this<WebSocketSession> {
 public:
  WebSocketSession(tcp::socket&& socket, std::shared_ptr<ServerState> state);
  ~WebSocketSession() override;

  // Completes the upgrade the HTTP session has read.
  void run(Request request);
  // Any thread; returns at once.
  void deliver(std::shared_ptr<const StreamMessage> message);
  // Any thread: close with 1001 (going away).
  void shutdown() override;

 private:
  void on_accept(beast::error_code ec);
  void do_read();
  void on_read(beast::error_code ec, std::size_t bytes);
  void handle_text(const std::string& text);
  void send_control(std::string text);
  void enqueue(std::shared_ptr<const StreamMessage> message);
  void do_write();
  void on_write(beast::error_code ec, std::size_t bytes);
  void close(websocket::close_code code, const char* reason);
  void finish();

  websocket::stream<beast::tcp_stream> ws_;
  std::shared_ptr<ServerState> state_;
  std::shared_ptr<WebSocketStreamSink> sink_;
  beast::flat_buffer read_buffer_;
  net::steady_timer close_timer_;

  SendQueue<std::shared_ptr<const StreamMessage>> queue_;
  std::shared_ptr<const StreamMessage> in_flight_;  // keeps the payload alive while written
  std::set<std::string> topics_;
  bool open_ = false;     // counted in the server's open sessions
  bool closing_ = false;  // no more writes; a close is on its way
  bool finished_ = false;
};

}  // namespace avk::server
