#pragma once
// Fan-out of the live Foxglove connection (foxglove.websocket.v1, docs/foxglove.md): the
// station's FoxgloveLive feed advertises each vehicle's channels and publishes on them; each
// connected client gets the channel list, subscribes by channel id, and receives only what it
// subscribed to. A message is serialised once and shared by every client that sends it; a channel
// nobody subscribed to costs nothing beyond the question wanted(). Latched channels (the region,
// the turn) keep their last message for a client that subscribes later.

#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "app/foxglove_live.hpp"

namespace avk::server {

inline constexpr const char* kFoxgloveSubprotocol = "foxglove.websocket.v1";

// One message of a channel, as every client sends it (each with its own subscription id).
struct FoxgloveFrame {
  std::uint32_t channel_id = 0;
  std::uint64_t t_ns = 0;
  bool latest_value_wins = true;
  std::shared_ptr<const std::string> payload;
};

// A connected client as the hub sees it. Calls come from the publisher's thread: they must hand
// the work to the client's own strand and return at once.
class FoxgloveClient {
 public:
  virtual ~FoxgloveClient() = default;
  virtual void send_text(std::shared_ptr<const std::string> json) = 0;
  virtual void deliver(std::shared_ptr<const FoxgloveFrame> frame) = 0;
  virtual void send_time(std::uint64_t t_ns) = 0;
  // The channels went away (their vehicle did): forget the subscriptions, then tell the client.
  virtual void channels_removed(std::vector<std::uint32_t> ids,
                                std::shared_ptr<const std::string> unadvertise_json) = 0;
};

class FoxgloveHub final : public app::foxglove::FoxgloveSink {
 public:
  explicit FoxgloveHub(std::string session_id);

  std::string server_info(const std::string& server_version) const;
  // Registers a client and returns the advertise message of every channel now offered (sent
  // even when empty: the protocol promises one at connection).
  std::string join(const std::shared_ptr<FoxgloveClient>& client);
  void leave(const FoxgloveClient* client);

  enum class SubscribeOutcome { ok, unknown_channel };
  // On success the channel's latched message (if any) is given back to send at once.
  SubscribeOutcome subscribe(const FoxgloveClient* client, std::uint32_t channel_id,
                             std::shared_ptr<const FoxgloveFrame>* latched);
  void unsubscribe(const FoxgloveClient* client, std::uint32_t channel_id);

  // app::foxglove::FoxgloveSink
  void advertise(const std::string& vehicle_id,
                 const std::vector<app::foxglove::ChannelSpec>& channels) override;
  void unadvertise(const std::string& vehicle_id) override;
  bool wanted(const std::string& topic) const override;
  void publish(const std::string& topic, std::uint64_t t_ns, std::string payload) override;
  void status(app::foxglove::LogLevel level, const std::string& message) override;
  void time(std::uint64_t t_ns) override;

  std::size_t client_count() const;
  std::size_t subscriber_count(const std::string& topic) const;
  std::uint64_t published() const;

 private:
  struct Channel {
    app::foxglove::ChannelSpec spec;
    std::string vehicle_id;
    bool advertised = false;
    std::set<const FoxgloveClient*> subscribers;
    std::shared_ptr<const FoxgloveFrame> last;  // latched channels
  };
  std::vector<std::shared_ptr<FoxgloveClient>> clients_locked() const;
  std::vector<std::shared_ptr<FoxgloveClient>> subscribers_locked(const Channel& c) const;

  std::string session_id_;
  mutable std::mutex mutex_;
  std::map<std::uint32_t, Channel> channels_;
  std::map<std::string, std::uint32_t> ids_by_topic_;
  std::uint32_t next_id_ = 1;
  std::map<const FoxgloveClient*, std::weak_ptr<FoxgloveClient>> clients_;
  std::uint64_t published_ = 0;
};

}  // namespace avk::server
