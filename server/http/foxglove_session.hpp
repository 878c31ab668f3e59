#pragma once
// One client of the Foxglove WebSocket protocol (foxglove.websocket.v1, docs/foxglove.md): server
// info and the channel list on connection, subscribe/unsubscribe by channel id, binary message
// data with the client's subscription id and the station-clock timestamp, time messages, status
// for mission events and for the client's mistakes (an unknown channel is an error status, not a
// dropped connection). The stream's limits (server/http/live_websocket.hpp): latest-value-wins
// telemetry per channel, a bounded queue of events, a slow client closed with 1008.

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <variant>
#include <vector>

#include "server/http/live_sources.hpp"
#include "server/http/live_websocket.hpp"

namespace avk::server {

namespace foxglove_wire {
struct Time {
  std::uint64_t t_ns = 0;
};
// What a Foxglove session sends: a JSON text, a channel's message, or the time.
using Outgoing =
    std::variant<std::shared_ptr<const std::string>, std::shared_ptr<const FoxgloveFrame>, Time>;
}  // namespace foxglove_wire

class FoxgloveSession : public LiveWebSocket<FoxgloveSession, foxglove_wire::Outgoing> {
 public:
  // address: the client's, reserved with ServerState::reserve_stream.
  FoxgloveSession(tcp::socket&& socket, std::shared_ptr<ServerState> state, std::string address);
  ~FoxgloveSession() override;

  // Completes the upgrade the HTTP session has read; the request offered kFoxgloveSubprotocol.
  void run(Request request);

  // From the hub (any thread): posted to the session's strand.
  void post_text(std::shared_ptr<const std::string> json);
  void post_frame(std::shared_ptr<const FoxgloveFrame> frame);
  void post_time(std::uint64_t t_ns);
  void post_channels_removed(std::vector<std::uint32_t> ids,
                             std::shared_ptr<const std::string> json);

 private:
  friend class LiveWebSocket<FoxgloveSession, foxglove_wire::Outgoing>;
  void on_open();
  void on_text(const std::string& text);
  void on_binary();
  const char* too_slow_reason() const { return "too slow: reconnect"; }
  template <class Handler>
  bool start_write(foxglove_wire::Outgoing& item, Handler&& done);
  void leave_hub();

  void subscribe(const nlohmann::json& request);
  void unsubscribe(const nlohmann::json& request);
  void send_status(int level, const std::string& message);

  std::shared_ptr<FoxgloveClient> client_;  // what the hub holds (detachable)
  std::array<unsigned char, 13> header_{};
  std::map<std::uint32_t, std::uint32_t> subscription_of_channel_;
  std::map<std::uint32_t, std::uint32_t> channel_of_subscription_;
};

}  // namespace avk::server
