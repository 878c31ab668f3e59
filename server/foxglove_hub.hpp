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
#include "server/http/live_sources.hpp"

namespace avk::server {

class FoxgloveHub final : public app::foxglove::FoxgloveSink, public FoxgloveSource {
 public:
  explicit FoxgloveHub(std::string session_id);

  // FoxgloveSource
  std::string server_info(const std::string& server_version) const override;
  std::string join(const std::shared_ptr<FoxgloveClient>& client) override;
  void leave(const FoxgloveClient* client) override;
  SubscribeOutcome subscribe(const FoxgloveClient* client, std::uint32_t channel_id,
                             std::shared_ptr<const FoxgloveFrame>* latched) override;
  void unsubscribe(const FoxgloveClient* client, std::uint32_t channel_id) override;

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
