#pragma once
// What the hub holds for one WebSocket session. A separate object, not the session itself: the
// hub's publisher may hold a sink after the server is gone, and a session (socket, strand) must
// never be destroyed after its io_context. detach() cuts the link, and waits out a delivery in
// progress, before the io_context goes.

#include <memory>
#include <mutex>

#include "server/api_types.hpp"
#include "server/http/live_session.hpp"

namespace avk::server {

class WebSocketSession;

class WebSocketStreamSink final : public StreamSink, public DetachableSink {
 public:
  explicit WebSocketStreamSink(std::weak_ptr<WebSocketSession> session);

  void deliver(std::shared_ptr<const StreamMessage> message) override;
  void detach() override;

 private:
  std::mutex mutex_;
  std::weak_ptr<WebSocketSession> session_;
};

}  // namespace avk::server
