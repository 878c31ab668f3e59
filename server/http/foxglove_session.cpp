#include "server/http/foxglove_session.hpp"

#include <nlohmann/json.hpp>
#include <utility>
#include <vector>

#include "server/http/live_sources.hpp"
#include "server/http/server_state.hpp"

namespace avk::server {

using nlohmann::json;

namespace {

constexpr std::uint8_t kOpMessageData = 0x01;
constexpr std::uint8_t kOpTime = 0x02;
// Queue keys: a channel id for its latest-value-wins messages, this one for the time.
constexpr std::uint64_t kTimeKey = std::uint64_t{1} << 32;
enum StatusLevel { info = 0, warning = 1, error = 2 };

template <class T>
void put_le(unsigned char* out, T v) {
  for (std::size_t i = 0; i < sizeof(T); ++i)
    out[i] = static_cast<unsigned char>((v >> (8 * i)) & 0xFF);
}

// The ids of a client's command: unsigned 32-bit numbers, or none (the message says why).
std::optional<std::uint32_t> id_of(const json& j, const char* key) {
  const auto it = j.find(key);
  if (it == j.end() || !it->is_number_unsigned() || it->get<std::uint64_t>() > 0xFFFFFFFFULL)
    return std::nullopt;
  return static_cast<std::uint32_t>(it->get<std::uint64_t>());
}

// What the hub holds for the session: cut by detach() before the io_context goes, as the
// stream's sink is (websocket_stream_sink.hpp).
class FoxgloveSessionSink final : public FoxgloveClient, public DetachableSink {
 public:
  explicit FoxgloveSessionSink(std::weak_ptr<FoxgloveSession> s) : session_(std::move(s)) {}
  void send_text(std::shared_ptr<const std::string> text) override {
    with_session([&](FoxgloveSession& s) { s.post_text(std::move(text)); });
  }
  void deliver(std::shared_ptr<const FoxgloveFrame> frame) override {
    with_session([&](FoxgloveSession& s) { s.post_frame(std::move(frame)); });
  }
  void send_time(std::uint64_t t_ns) override {
    with_session([&](FoxgloveSession& s) { s.post_time(t_ns); });
  }
  void channels_removed(std::vector<std::uint32_t> ids,
                        std::shared_ptr<const std::string> text) override {
    with_session(
        [&](FoxgloveSession& s) { s.post_channels_removed(std::move(ids), std::move(text)); });
  }
  void detach() override {
    std::lock_guard lock(mutex_);
    session_.reset();
  }

 private:
  template <class F>
  void with_session(F&& f) {
    std::lock_guard lock(mutex_);
    if (auto s = session_.lock()) f(*s);
  }
  std::mutex mutex_;
  std::weak_ptr<FoxgloveSession> session_;
};

}  // namespace

FoxgloveSession::FoxgloveSession(tcp::socket&& socket, std::shared_ptr<ServerState> state,
                                 std::string address)
    : LiveWebSocket(std::move(socket), std::move(state), std::move(address)) {}

FoxgloveSession::~FoxgloveSession() {
  if (client_) state_->foxglove().leave(client_.get());
  if (open_) state_->stream_closed();
  state_->remove(this);
}

void FoxgloveSession::run(Request request) {
  auto sink = std::make_shared<FoxgloveSessionSink>(weak_from_this());
  client_ = sink;
  state_->add(shared_from_this(), sink, address_);
  // The client offered the subprotocol (the HTTP session checked): the server must select it.
  accept(std::move(request), kFoxgloveSubprotocol);
}

void FoxgloveSession::on_open() {
  auto& hub = state_->foxglove();
  enqueue(std::make_shared<const std::string>(hub.server_info(state_->options().server_version)),
          std::nullopt);
  enqueue(std::make_shared<const std::string>(hub.join(client_)), std::nullopt);
}

void FoxgloveSession::on_binary() {
  send_status(error,
              "client publishing and service calls are not supported by this server "
              "(capabilities: time)");
}

void FoxgloveSession::leave_hub() {
  if (client_) state_->foxglove().leave(client_.get());
}

void FoxgloveSession::post_text(std::shared_ptr<const std::string> text) {
  on_strand([self = shared_from_this(), t = std::move(text)]() mutable {
    self->enqueue(std::move(t), std::nullopt);
  });
}

void FoxgloveSession::post_frame(std::shared_ptr<const FoxgloveFrame> frame) {
  on_strand([self = shared_from_this(), f = std::move(frame)]() mutable {
    // Unsubscribed while the frame was on its way.
    if (!self->subscription_of_channel_.contains(f->channel_id)) return;
    std::optional<std::uint64_t> key;
    if (f->latest_value_wins) key = f->channel_id;
    self->enqueue(std::move(f), key);
  });
}

void FoxgloveSession::post_time(std::uint64_t t_ns) {
  net::post(ws_.get_executor(), [self = shared_from_this(), t_ns] {
    self->enqueue(foxglove_wire::Time{t_ns}, kTimeKey);
  });
}

void FoxgloveSession::post_channels_removed(std::vector<std::uint32_t> ids,
                                            std::shared_ptr<const std::string> text) {
  net::post(ws_.get_executor(),
            [self = shared_from_this(), ids = std::move(ids), t = std::move(text)]() mutable {
              for (const auto id : ids) {
                const auto it = self->subscription_of_channel_.find(id);
                if (it == self->subscription_of_channel_.end()) continue;
                self->channel_of_subscription_.erase(it->second);
                self->subscription_of_channel_.erase(it);
              }
              self->enqueue(std::move(t), std::nullopt);
            });
}

void FoxgloveSession::on_text(const std::string& text) {
  const auto command = json::parse(text, nullptr, false);
  if (command.is_discarded() || !command.is_object() || !command.contains("op") ||
      !command["op"].is_string())
    return send_status(error, R"(expected a JSON object with an "op", such as {"op":"subscribe",)"
                              R"("subscriptions":[{"id":0,"channelId":1}]})");
  const auto& op = command["op"].get_ref<const std::string&>();
  if (op == "subscribe") return subscribe(command);
  if (op == "unsubscribe") return unsubscribe(command);
  send_status(error, "unsupported operation '" + op +
                         "': this server offers subscribe and unsubscribe (capabilities: time)");
}

void FoxgloveSession::subscribe(const json& command) {
  const auto list = command.find("subscriptions");
  if (list == command.end() || !list->is_array())
    return send_status(error, "subscribe needs \"subscriptions\": [{\"id\", \"channelId\"}]");
  auto& hub = state_->foxglove();
  for (const auto& s : *list) {
    const auto id = s.is_object() ? id_of(s, "id") : std::nullopt;
    const auto channel = s.is_object() ? id_of(s, "channelId") : std::nullopt;
    if (!id || !channel) {
      send_status(error,
                  "subscribe: each subscription needs an unsigned \"id\" and "
                  "\"channelId\", got " +
                      s.dump());
      continue;
    }
    if (channel_of_subscription_.contains(*id)) {
      send_status(error, "subscribe: subscription id " + std::to_string(*id) + " is in use");
      continue;
    }
    if (subscription_of_channel_.contains(*channel)) {
      send_status(error, "subscribe: channel " + std::to_string(*channel) +
                             " is already subscribed (one subscription per channel)");
      continue;
    }
    std::shared_ptr<const FoxgloveFrame> latched;
    if (hub.subscribe(client_.get(), *channel, &latched) ==
        FoxgloveSource::SubscribeOutcome::unknown_channel) {
      send_status(error, "subscribe: unknown channel id " + std::to_string(*channel) +
                             " (not advertised, or its vehicle went away)");
      continue;
    }
    subscription_of_channel_[*channel] = *id;
    channel_of_subscription_[*id] = *channel;
    if (latched) enqueue(std::move(latched), std::nullopt);
  }
}

void FoxgloveSession::unsubscribe(const json& command) {
  const auto list = command.find("subscriptionIds");
  if (list == command.end() || !list->is_array())
    return send_status(error, "unsubscribe needs \"subscriptionIds\": [ids]");
  for (const auto& v : *list) {
    const auto id = v.is_number_unsigned() && v.get<std::uint64_t>() <= 0xFFFFFFFFULL
                        ? std::optional<std::uint32_t>(v.get<std::uint32_t>())
                        : std::nullopt;
    const auto it = id ? channel_of_subscription_.find(*id) : channel_of_subscription_.end();
    if (it == channel_of_subscription_.end()) {
      send_status(warning, "unsubscribe: no subscription " + v.dump());
      continue;
    }
    state_->foxglove().unsubscribe(client_.get(), it->second);
    subscription_of_channel_.erase(it->second);
    channel_of_subscription_.erase(it);
  }
}

void FoxgloveSession::send_status(int level, const std::string& message) {
  enqueue(std::make_shared<const std::string>(
              json{{"op", "status"}, {"level", level}, {"message", message}}.dump(
                  -1, ' ', false, json::error_handler_t::replace)),
          std::nullopt);
}

template <class Handler>
bool FoxgloveSession::start_write(foxglove_wire::Outgoing& item, Handler&& done) {
  if (const auto* text = std::get_if<std::shared_ptr<const std::string>>(&item)) {
    ws_.text(true);
    ws_.async_write(net::buffer(**text), std::forward<Handler>(done));
    return true;
  }
  ws_.binary(true);
  if (const auto* t = std::get_if<foxglove_wire::Time>(&item)) {
    header_[0] = kOpTime;
    put_le(&header_[1], t->t_ns);
    ws_.async_write(net::buffer(header_.data(), 9), std::forward<Handler>(done));
    return true;
  }
  const auto& frame = *std::get<std::shared_ptr<const FoxgloveFrame>>(item);
  const auto sub = subscription_of_channel_.find(frame.channel_id);
  // Unsubscribed while queued: the frame is dropped (its own write would name a dead id).
  if (sub == subscription_of_channel_.end()) return false;
  header_[0] = kOpMessageData;
  put_le(&header_[1], sub->second);
  put_le(&header_[5], frame.t_ns);
  const std::array<net::const_buffer, 2> buffers{net::buffer(header_.data(), header_.size()),
                                                 net::buffer(*frame.payload)};
  ws_.async_write(buffers, std::forward<Handler>(done));
  return true;
}

}  // namespace avk::server
