#pragma once
// What the transport's live connections are fed by, as the transport sees them: the station's
// own stream (/api/v1/stream) and the Foxglove WebSocket protocol. The transport knows these
// interfaces, never the hubs behind them or the domain they carry: a session subscribes its sink
// and receives payloads already serialised.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "server/api_types.hpp"

namespace avk::server {

inline constexpr const char* kFoxgloveSubprotocol = "foxglove.websocket.v1";

// One message of a channel, as every client sends it (each with its own subscription id).
struct FoxgloveFrame {
  std::uint32_t channel_id = 0;
  std::uint64_t t_ns = 0;
  bool latest_value_wins = true;
  std::shared_ptr<const std::string> payload;
};

// A connected client as the source sees it. Calls come from the publisher's thread: they must
// hand the work to the client's own strand and return at once.
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

class FoxgloveSource {
 public:
  virtual ~FoxgloveSource() = default;
  virtual std::string server_info(const std::string& server_version) const = 0;
  // Registers a client and returns the advertise message of every channel now offered (sent
  // even when empty: the protocol promises one at connection).
  virtual std::string join(const std::shared_ptr<FoxgloveClient>& client) = 0;
  virtual void leave(const FoxgloveClient* client) = 0;
  enum class SubscribeOutcome { ok, unknown_channel };
  // On success the channel's latched message (if any) is given back to send at once.
  virtual SubscribeOutcome subscribe(const FoxgloveClient* client, std::uint32_t channel_id,
                                     std::shared_ptr<const FoxgloveFrame>* latched) = 0;
  virtual void unsubscribe(const FoxgloveClient* client, std::uint32_t channel_id) = 0;
};

class StreamSource {
 public:
  virtual ~StreamSource() = default;
  virtual const std::vector<std::string>& topic_names() const = 0;
  virtual bool has_topic(const std::string& topic) const = 0;
  // The hello a new connection receives.
  virtual std::string hello(const std::string& server_version) const = 0;
  // The source keeps weak references: a closed session simply stops receiving.
  virtual void subscribe(const std::shared_ptr<StreamSink>& sink, const std::string& topic) = 0;
  virtual void unsubscribe(const StreamSink* sink, const std::string& topic) = 0;
  virtual void unsubscribe_all(const StreamSink* sink) = 0;
  // The same live data for clients of the Foxglove WebSocket protocol.
  virtual FoxgloveSource& foxglove_source() = 0;
};

}  // namespace avk::server
