#include "server/http/websocket_session.hpp"

#include <functional>
#include <nlohmann/json.hpp>
#include <utility>
#include <vector>

#include "server/http/server_state.hpp"
#include "server/http/websocket_stream_sink.hpp"
#include "server/stream_hub.hpp"

namespace avk::server {

namespace {

// Client messages are small commands; anything larger is a broken or hostile client.
constexpr std::size_t kMaxClientMessage = 64 * 1024;

std::string error_message(const std::string& message) {
  return nlohmann::json{{"type", "error"}, {"message", message}}.dump(
      -1, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace

WebSocketSession::WebSocketSession(tcp::socket&& socket, std::shared_ptr<ServerState> state)
    : ws_(std::move(socket)),
      state_(std::move(state)),
      close_timer_(ws_.get_executor()),
      queue_(state_->options().stream_event_queue_limit) {}

WebSocketSession::~WebSocketSession() {
  if (sink_) state_->hub().unsubscribe_all(sink_.get());
  if (open_) state_->stream_closed();
  state_->remove(this);
}

void WebSocketSession::run(Request request) {
  sink_ = std::make_shared<WebSocketStreamSink>(weak_from_this());
  state_->add(shared_from_this(), sink_);

  const auto& options = state_->options();
  // The websocket stream keeps its own timers; the HTTP deadline must not cut a long stream.
  beast::get_lowest_layer(ws_).expires_never();
  auto timeouts = websocket::stream_base::timeout::suggested(beast::role_type::server);
  timeouts.handshake_timeout = options.close_timeout;
  // Pings at half the idle time find peers that vanished without a FIN (Wi-Fi out of range).
  timeouts.idle_timeout = options.idle_timeout;
  timeouts.keep_alive_pings = true;
  ws_.set_option(timeouts);
  ws_.set_option(websocket::stream_base::decorator(
      [](websocket::response_type& res) { res.set(http::field::server, "avk-station"); }));
  ws_.read_message_max(kMaxClientMessage);
  ws_.async_accept(request,
                   beast::bind_front_handler(&WebSocketSession::on_accept, shared_from_this()));
}

void WebSocketSession::on_accept(beast::error_code ec) {
  if (ec) return finish();
  open_ = true;
  state_->stream_opened();
  // A stop that came while the handshake ran did not reach this session yet.
  if (state_->stopping()) return close(websocket::close_code::going_away, "server shutting down");
  send_control(state_->hub().hello(state_->options().server_version));
  do_read();
}

void WebSocketSession::deliver(std::shared_ptr<const StreamMessage> message) {
  net::post(ws_.get_executor(), [self = shared_from_this(), m = std::move(message)]() mutable {
    self->enqueue(std::move(m));
  });
}

void WebSocketSession::shutdown() {
  net::post(ws_.get_executor(), [self = shared_from_this()] {
    // Before the handshake completes on_accept sees the stop flag instead.
    if (self->open_) self->close(websocket::close_code::going_away, "server shutting down");
  });
}

void WebSocketSession::do_read() {
  ws_.async_read(read_buffer_,
                 beast::bind_front_handler(&WebSocketSession::on_read, shared_from_this()));
}

void WebSocketSession::on_read(beast::error_code ec, std::size_t) {
  // Closed by the peer, by our close, by a timeout or a reset: either way the session is over.
  if (ec) return finish();
  // Our close is on its way: a late command must not subscribe the session again.
  if (closing_) return;
  if (ws_.got_text())
    handle_text(beast::buffers_to_string(read_buffer_.data()));
  else
    send_control(error_message("binary frames are not supported: send JSON text"));
  read_buffer_.consume(read_buffer_.size());
  if (!closing_) do_read();
}

void WebSocketSession::handle_text(const std::string& text) {
  const auto command = nlohmann::json::parse(text, nullptr, false);
  if (command.is_discarded() || !command.is_object())
    return send_control(error_message(
        R"(expected a JSON object such as {"subscribe":["nav"]} or {"unsubscribe":["nav"]})"));

  struct Change {
    bool subscribe;
    std::vector<std::string> topics;
  };
  std::vector<Change> changes;
  std::vector<std::string> unknown;
  for (const char* key : {"subscribe", "unsubscribe"}) {
    const auto it = command.find(key);
    if (it == command.end()) continue;
    if (!it->is_array())
      return send_control(error_message(std::string(key) + " takes an array of topic names"));
    Change change{std::string_view(key) == "subscribe", {}};
    for (const auto& t : *it) {
      if (!t.is_string())
        return send_control(error_message(std::string(key) + " takes an array of topic names"));
      const auto& topic = t.get_ref<const std::string&>();
      if (!StreamHub::is_topic(topic))
        unknown.push_back(topic);
      else
        change.topics.push_back(topic);
    }
    changes.push_back(std::move(change));
  }
  if (changes.empty())
    return send_control(error_message(R"(expected "subscribe" or "unsubscribe")"));
  // All or nothing, so a client never has to work out which half of a request took effect.
  if (!unknown.empty()) {
    std::string list;
    for (const auto& t : unknown)
      list += (list.empty() ? "" : ", ") + t;
    std::string offered;
    for (const auto& t : StreamHub::topics())
      offered += (offered.empty() ? "" : ", ") + t;
    return send_control(error_message("unknown topic: " + list + " (topics: " + offered + ")"));
  }
  auto& hub = state_->hub();
  for (const auto& change : changes) {
    for (const auto& topic : change.topics) {
      if (change.subscribe) {
        hub.subscribe(sink_, topic);
        topics_.insert(topic);
      } else {
        hub.unsubscribe(sink_.get(), topic);
        topics_.erase(topic);
      }
    }
  }
  send_control(nlohmann::json{{"type", "subscribed"}, {"topics", topics_}}.dump());
}

void WebSocketSession::send_control(std::string text) {
  auto message = std::make_shared<StreamMessage>();
  message->payload = std::make_shared<const std::string>(std::move(text));
  enqueue(std::move(message));
}

void WebSocketSession::enqueue(std::shared_ptr<const StreamMessage> message) {
  if (!open_ || closing_ || finished_) return;
  std::optional<std::uint64_t> key;
  if (message->latest_value_wins) key = std::hash<std::string>{}(message->topic);
  if (!queue_.push(std::move(message), key))
    return close(websocket::close_code::policy_error, "too slow: re-sync over REST");
  if (!in_flight_) do_write();
}

void WebSocketSession::do_write() {
  in_flight_ = queue_.pop();
  ws_.text(true);
  ws_.async_write(net::buffer(*in_flight_->payload),
                  beast::bind_front_handler(&WebSocketSession::on_write, shared_from_this()));
}

void WebSocketSession::on_write(beast::error_code ec, std::size_t) {
  in_flight_.reset();
  if (ec) {
    // The pending read may never learn of it (a half-open peer): make sure it does.
    beast::get_lowest_layer(ws_).close();
    return finish();
  }
  if (closing_ || finished_) return;
  if (!queue_.empty()) do_write();
}

void WebSocketSession::close(websocket::close_code code, const char* reason) {
  if (closing_ || finished_) return;
  closing_ = true;
  queue_.clear();
  if (open_) {
    open_ = false;
    state_->stream_closed();
  }
  state_->hub().unsubscribe_all(sink_.get());
  // Beast sends the close frame after a write in progress, which a client that stopped reading
  // never lets finish: the timer cuts the socket then.
  close_timer_.expires_after(state_->options().close_timeout);
  close_timer_.async_wait([self = shared_from_this()](beast::error_code ec) {
    if (!ec) beast::get_lowest_layer(self->ws_).close();
  });
  ws_.async_close(websocket::close_reason(code, reason),
                  [self = shared_from_this()](beast::error_code) { self->close_timer_.cancel(); });
}

void WebSocketSession::finish() {
  if (finished_) return;
  finished_ = true;
  queue_.clear();
  if (open_) {
    open_ = false;
    state_->stream_closed();
  }
  if (sink_) state_->hub().unsubscribe_all(sink_.get());
  close_timer_.cancel();
  // Whatever is still pending (a write to a peer that vanished) completes now, and the session
  // is released instead of waiting for the kernel to give up on the connection.
  beast::get_lowest_layer(ws_).close();
}

}  // namespace avk::server
