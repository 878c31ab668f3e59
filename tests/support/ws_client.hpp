#pragma once
// The tests' WebSocket client on loopback: every operation has a deadline, so a broken server
// fails a test instead of hanging it. An Origin, a small receive window (a client that stops
// reading stalls the server sooner), another path and a subprotocol can be asked for.

#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <chrono>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace avk::testing {

namespace ws_client_detail {
namespace beast = boost::beast;
namespace http = boost::beast::http;
namespace websocket = boost::beast::websocket;
namespace net = boost::asio;
using tcp = boost::asio::ip::tcp;
using json = nlohmann::json;
using namespace std::chrono_literals;

class WsClient {
 public:
  WsClient(unsigned short port, const std::string& origin = "", int receive_buffer = 0,
           const std::string& path = "/api/v1/stream", const std::string& subprotocol = "")
      : ws_(ioc_) {
    auto& socket = ws_.next_layer();
    socket.open(tcp::v4());
    // A small receive window makes a client that stops reading stall the server sooner.
    if (receive_buffer > 0)
      socket.set_option(net::socket_base::receive_buffer_size(receive_buffer));
    socket.connect(tcp::endpoint(net::ip::make_address("127.0.0.1"), port));
    ws_.set_option(
        websocket::stream_base::decorator([origin, subprotocol](websocket::request_type& req) {
          if (!origin.empty()) req.set(http::field::origin, origin);
          if (!subprotocol.empty()) req.set(http::field::sec_websocket_protocol, subprotocol);
        }));
    const auto ec = run([&](auto handler) {
      ws_.async_handshake(response_, "127.0.0.1:" + std::to_string(port), path, handler);
    });
    handshake_error_ = ec;
  }

  beast::error_code handshake_error() const { return handshake_error_; }
  const websocket::response_type& handshake_response() const { return response_; }

  // The next message as JSON; nullopt when the connection ended (error() says how).
  std::optional<json> read(std::chrono::milliseconds limit = 5000ms) {
    const auto text = read_text(limit);
    if (!text) return std::nullopt;
    return json::parse(*text);
  }

  std::optional<std::string> read_text(std::chrono::milliseconds limit = 5000ms) {
    buffer_.consume(buffer_.size());
    last_error_ = run([&](auto handler) { ws_.async_read(buffer_, handler); }, limit);
    if (last_error_) return std::nullopt;
    return beast::buffers_to_string(buffer_.data());
  }

  void send(const std::string& text, bool binary = false) {
    ws_.binary(binary);
    const auto ec = run([&](auto handler) { ws_.async_write(net::buffer(text), handler); });
    if (ec) throw beast::system_error(ec);
  }

  beast::error_code error() const { return last_error_; }
  websocket::close_reason close_reason() const { return ws_.reason(); }
  bool got_binary() const { return ws_.got_binary(); }

 private:
  // Runs one asynchronous operation to completion or cancels it at the limit.
  template <class Start>
  beast::error_code run(Start start, std::chrono::milliseconds limit = 5000ms) {
    bool done = false;
    beast::error_code result;
    start([&](beast::error_code ec, auto&&...) {
      done = true;
      result = ec;
    });
    ioc_.restart();
    ioc_.run_for(limit);
    if (!done) {
      beast::error_code ignored;
      ws_.next_layer().close(ignored);
      ioc_.restart();
      ioc_.run();
      return beast::error::timeout;
    }
    return result;
  }

  net::io_context ioc_;
  websocket::stream<tcp::socket> ws_;
  websocket::response_type response_;
  beast::flat_buffer buffer_;
  beast::error_code handshake_error_;
  beast::error_code last_error_;
};

}  // namespace ws_client_detail

using ws_client_detail::WsClient;

}  // namespace avk::testing
