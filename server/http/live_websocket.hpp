#pragma once
// What the live WebSocket sessions share, whatever protocol they speak (the stream, the Foxglove
// connection): the upgrade with the server's timeouts, reading client commands, a write queue on
// the session's strand (server/send_queue.hpp: the publisher never waits for a client), and the
// ways a session ends — our close with a code (1001 at stop, 1008 for a client too slow), the
// peer going away, or a write that fails. Derived (CRTP) supplies the protocol:
//   void on_open();                          the first messages after the handshake
//   void on_text(const std::string& text);   a client command
//   void on_binary();                         a binary frame from the client
//   const char* too_slow_reason() const;      the 1008 close reason
//   template <class H> bool start_write(Item& item, H&& done);  false: nothing to send (dropped)
//   void leave_hub();                          stop receiving from the publisher

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include "server/http/beast.hpp"
#include "server/http/live_session.hpp"
#include "server/http/server_state.hpp"
#include "server/send_queue.hpp"

namespace avk::server {

template <class Derived, class Item>
class LiveWebSocket : public LiveSession, public std::enable_shared_from_this<Derived> {
 public:
  // Any thread: close with 1001 (going away).
  void shutdown() override {
    net::post(ws_.get_executor(), [self = this->shared_from_this()] {
      // Before the handshake completes on_accept sees the stop flag instead.
      if (self->open_) self->close(websocket::close_code::going_away, "server shutting down");
    });
  }

 protected:
  // Client messages are small commands; anything larger is a broken or hostile client.
  static constexpr std::size_t kMaxClientMessage = 64 * 1024;

  // address: the client's, as reserved with ServerState::reserve_stream.
  LiveWebSocket(tcp::socket&& socket, std::shared_ptr<ServerState> state, std::string address)
      : ws_(std::move(socket)),
        state_(std::move(state)),
        address_(std::move(address)),
        close_timer_(ws_.get_executor()),
        queue_(state_->options().stream_event_queue_limit) {}

  // Completes the upgrade the HTTP session has read; selects the subprotocol when given.
  void accept(Request request, std::optional<std::string_view> subprotocol) {
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
        [protocol = std::string(subprotocol.value_or(""))](websocket::response_type& res) {
          res.set(http::field::server, "avk-station");
          if (!protocol.empty()) res.set(http::field::sec_websocket_protocol, protocol);
        }));
    ws_.read_message_max(kMaxClientMessage);
    ws_.async_accept(
        request, [self = this->shared_from_this()](beast::error_code ec) { self->on_accept(ec); });
  }

  // From any thread, onto the session's strand.
  template <class F>
  void on_strand(F&& f) {
    net::post(ws_.get_executor(), std::forward<F>(f));
  }

  // On the strand. key: latest-value-wins under it; none: an event (bounded).
  void enqueue(Item item, std::optional<std::uint64_t> key) {
    if (!open_ || closing_ || finished_) return;
    if (!queue_.push(std::move(item), key))
      return close(websocket::close_code::policy_error, derived().too_slow_reason());
    if (!in_flight_) do_write();
  }

  bool closing() const { return closing_ || finished_; }

  websocket::stream<beast::tcp_stream> ws_;
  std::shared_ptr<ServerState> state_;
  std::string address_;
  bool open_ = false;  // counted in the server's open sessions

 private:
  Derived& derived() { return static_cast<Derived&>(*this); }

  void on_accept(beast::error_code ec) {
    if (ec) return finish();
    open_ = true;
    state_->stream_opened();
    // A stop that came while the handshake ran did not reach this session yet.
    if (state_->stopping()) return close(websocket::close_code::going_away, "server shutting down");
    derived().on_open();
    do_read();
  }

  void do_read() {
    ws_.async_read(read_buffer_, [self = this->shared_from_this()](
                                     beast::error_code ec, std::size_t) { self->on_read(ec); });
  }

  void on_read(beast::error_code ec) {
    // Closed by the peer, by our close, by a timeout or a reset: either way the session is over.
    if (ec) return finish();
    // Our close is on its way: a late command must not subscribe the session again.
    if (closing_) return;
    if (ws_.got_text())
      derived().on_text(beast::buffers_to_string(read_buffer_.data()));
    else
      derived().on_binary();
    read_buffer_.consume(read_buffer_.size());
    if (!closing_) do_read();
  }

  void do_write() {
    while (!queue_.empty()) {
      in_flight_ = queue_.pop();
      auto done = [self = this->shared_from_this()](beast::error_code ec, std::size_t) {
        self->on_write(ec);
      };
      if (derived().start_write(*in_flight_, std::move(done))) return;
      in_flight_.reset();
    }
  }

  void on_write(beast::error_code ec) {
    in_flight_.reset();
    if (ec) {
      // The pending read may never learn of it (a half-open peer): make sure it does.
      beast::get_lowest_layer(ws_).close();
      return finish();
    }
    if (closing_ || finished_) return;
    do_write();
  }

  void close(websocket::close_code code, const char* reason) {
    if (closing_ || finished_) return;
    closing_ = true;
    queue_.clear();
    if (open_) {
      open_ = false;
      state_->stream_closed();
    }
    derived().leave_hub();
    // Beast sends the close frame after a write in progress, which a client that stopped
    // reading never lets finish: the timer cuts the socket then.
    close_timer_.expires_after(state_->options().close_timeout);
    close_timer_.async_wait([self = this->shared_from_this()](beast::error_code ec) {
      if (!ec) beast::get_lowest_layer(self->ws_).close();
    });
    ws_.async_close(
        websocket::close_reason(code, reason),
        [self = this->shared_from_this()](beast::error_code) { self->close_timer_.cancel(); });
  }

  void finish() {
    if (finished_) return;
    finished_ = true;
    queue_.clear();
    if (open_) {
      open_ = false;
      state_->stream_closed();
    }
    derived().leave_hub();
    close_timer_.cancel();
    // Whatever is still pending (a write to a peer that vanished) completes now, and the session
    // is released instead of waiting for the kernel to give up on the connection.
    beast::get_lowest_layer(ws_).close();
  }

  net::steady_timer close_timer_;
  beast::flat_buffer read_buffer_;
  SendQueue<Item> queue_;
  std::optional<Item> in_flight_;  // keeps the payload alive while written
  bool closing_ = false;           // no more writes; a close is on its way
  bool finished_ = false;
};

}  // namespace avk::server
