#include "server/http/websocket_stream_sink.hpp"

#include <utility>

#include "server/http/websocket_session.hpp"

namespace avk::server {

WebSocketStreamSink::WebSocketStreamSink(std::weak_ptr<WebSocketSession> session)
    : session_(std::move(session)) {}

void WebSocketStreamSink::deliver(std::shared_ptr<const StreamMessage> message) {
  std::lock_guard lock(mutex_);
  if (auto session = session_.lock()) session->deliver(std::move(message));
}

void WebSocketStreamSink::detach() {
  std::lock_guard lock(mutex_);
  session_.reset();
}

}  // namespace avk::server
