#include "server/http/websocket_session.hpp"

#include <chrono>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <utility>
#include <vector>

#include "server/http/live_sources.hpp"
#include "server/http/server_state.hpp"
#include "server/http/websocket_stream_sink.hpp"

namespace avk::server {

namespace {

std::string error_message(const std::string& message) {
  return nlohmann::json{{"type", "error"}, {"message", message}}.dump(
      -1, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace

WebSocketSession::WebSocketSession(tcp::socket&& socket, std::shared_ptr<ServerState> state,
                                   std::string address)
    : LiveWebSocket(std::move(socket), std::move(state), std::move(address)) {}

WebSocketSession::~WebSocketSession() {
  if (sink_) state_->hub().unsubscribe_all(sink_.get());
  if (open_) state_->stream_closed();
  state_->remove(this);
}

void WebSocketSession::run(Request request) {
  sink_ = std::make_shared<WebSocketStreamSink>(weak_from_this());
  state_->add(shared_from_this(), sink_, address_);
  accept(std::move(request), std::nullopt);
}

void WebSocketSession::on_open() {
  send_control(state_->hub().hello(state_->options().server_version));
}

void WebSocketSession::on_binary() {
  send_control(error_message("binary frames are not supported: send JSON text"));
}

void WebSocketSession::deliver(std::shared_ptr<const StreamMessage> message) {
  on_strand([self = shared_from_this(), m = std::move(message)]() mutable {
    if (m->rate_limitable && self->max_hz_ > 0.0) {
      // A frame within 1/max_hz of the key's last one is not taken: telemetry is sent
      // continuously, so the next one after the interval carries the newest state.
      const auto now = std::chrono::steady_clock::now();
      auto& last = self->taken_[m->latest_key];
      if (last.time_since_epoch().count() != 0 &&
          now - last < std::chrono::duration<double>(1.0 / self->max_hz_))
        return;
      last = now;
    }
    std::optional<std::uint64_t> key;
    if (m->latest_value_wins) key = std::hash<std::string>{}(m->latest_key);
    self->enqueue(std::move(m), key);
  });
}

void WebSocketSession::on_text(const std::string& text) {
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
      if (!state_->hub().has_topic(topic))
        unknown.push_back(topic);
      else
        change.topics.push_back(topic);
    }
    changes.push_back(std::move(change));
  }
  std::optional<double> max_hz;
  if (const auto it = command.find("max_hz"); it != command.end()) {
    if (!it->is_number() || !(it->get<double>() >= 0.0 && it->get<double>() <= 1000.0))
      return send_control(
          error_message("max_hz takes the most nav and helm messages a second per vehicle, "
                        "from 0 (all of them) to 1000"));
    max_hz = it->get<double>();
  }
  if (changes.empty() && !max_hz)
    return send_control(error_message(R"(expected "subscribe", "unsubscribe" or "max_hz")"));
  // All or nothing, so a client never has to work out which half of a request took effect.
  if (!unknown.empty()) {
    std::string list;
    for (const auto& t : unknown)
      list += (list.empty() ? "" : ", ") + t;
    std::string offered;
    for (const auto& t : state_->hub().topic_names())
      offered += (offered.empty() ? "" : ", ") + t;
    return send_control(error_message("unknown topic: " + list + " (topics: " + offered + ")"));
  }
  if (max_hz) {
    max_hz_ = *max_hz;
    taken_.clear();
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
  send_control(
      nlohmann::json{{"type", "subscribed"}, {"topics", topics_}, {"max_hz", max_hz_}}.dump());
}

void WebSocketSession::send_control(std::string text) {
  auto message = std::make_shared<StreamMessage>();
  message->payload = std::make_shared<const std::string>(std::move(text));
  enqueue(std::move(message), std::nullopt);
}

void WebSocketSession::leave_hub() {
  if (sink_) state_->hub().unsubscribe_all(sink_.get());
}

}  // namespace avk::server
