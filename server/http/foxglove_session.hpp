#pragma once
// One client of the Foxglove WebSocket protocol (foxglove.websocket.v1, docs/foxglove.md): server
// info and the channel list on connection, subscribe/unsubscribe by channel id, binary message
// data with the client's subscription id and the station-clock timestamp, time messages, status
// for mission events and for the client's mistakes (an unknown channel is an error status, not a
// dropped connection). The same limits as the stream (server/send_queue.hpp): latest-value-wins
// telemetry per channel, a bounded queue of events, a slow client closed with 1008.

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "server/foxglove_hub.hpp"
#include "server/http/beast.hpp"
#include "server/http/live_session.hpp"
#include "server/send_queue.hpp"

namespace avk::server {

class ServerState;

class FoxgloveSession : public LiveSession, public std::enable_shared_from_this<FoxgloveSession> {
 public:
  FoxgloveSession(tcp::socket&& socket, std::shared_ptr<ServerState> state);
  ~FoxgloveSession() override;

  // Completes the upgrade the HTTP session has read; the request offered kFoxgloveSubprotocol.
  void run(Request request);
  void shutdown() override;

  // From the hub (any thread): posted to the session's strand.
  void post_text(std::shared_ptr<const std::string> json);
  void post_frame(std::shared_ptr<const FoxgloveFrame> frame);
  void post_time(std::uint64_t t_ns);
  void post_channels_removed(std::vector<std::uint32_t> ids,
                             std::shared_ptr<const std::string> json);

 private:
  struct Time {
    std::uint64_t t_ns = 0;
  };
  using Outgoing =
      std::variant<std::shared_ptr<const std::string>, std::shared_ptr<const FoxgloveFrame>, Time>;

  void on_accept(beast::error_code ec);
  void do_read();
  void on_read(beast::error_code ec, std::size_t bytes);
  void handle_text(const std::string& text);
  void subscribe(const nlohmann::json& request);
  void unsubscribe(const nlohmann::json& request);
  void send_status(int level, const std::string& message);
  void enqueue(Outgoing item, std::optional<std::uint64_t> key);
  void do_write();
  void on_write(beast::error_code ec, std::size_t bytes);
  void close(websocket::close_code code, const char* reason);
  void finish();

  websocket::stream<beast::tcp_stream> ws_;
  std::shared_ptr<ServerState> state_;
  std::shared_ptr<FoxgloveClient> client_;  // what the hub holds (detachable)
  beast::flat_buffer read_buffer_;
  net::steady_timer close_timer_;

  SendQueue<Outgoing> queue_;
  std::optional<Outgoing> in_flight_;  // keeps the payload alive while written
  std::array<unsigned char, 13> header_{};
  std::map<std::uint32_t, std::uint32_t> subscription_of_channel_;
  std::map<std::uint32_t, std::uint32_t> channel_of_subscription_;
  bool open_ = false;
  bool closing_ = false;
  bool finished_ = false;
};

}  // namespace avk::server
