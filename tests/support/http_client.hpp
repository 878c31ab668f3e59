#pragma once
// Small synchronous loopback clients for end-to-end tests: one HTTP request per call and a
// WebSocket that reads with a deadline, so a broken server fails a test instead of hanging it.

#include <boost/asio/connect.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <chrono>
#include <map>
#include <optional>
#include <string>

namespace avk::testing {

struct HttpReply {
  int status = 0;
  std::string body;
  std::map<std::string, std::string> headers;
};

inline HttpReply http_call(unsigned short port, const std::string& method,
                           const std::string& target, const std::string& body = "",
                           const std::map<std::string, std::string>& headers = {}) {
  namespace beast = boost::beast;
  namespace http = beast::http;
  boost::asio::io_context io;
  beast::tcp_stream stream(io);
  stream.expires_after(std::chrono::seconds(30));
  stream.connect(boost::asio::ip::tcp::endpoint(boost::asio::ip::make_address("127.0.0.1"), port));
  http::request<http::string_body> req(http::string_to_verb(method), target, 11);
  req.set(http::field::host, "127.0.0.1:" + std::to_string(port));
  for (const auto& [k, v] : headers)
    req.set(k, v);
  req.body() = body;
  req.prepare_payload();
  http::write(stream, req);
  beast::flat_buffer buffer;
  http::response<http::string_body> res;
  http::read(stream, buffer, res);
  HttpReply r;
  r.status = static_cast<int>(res.result_int());
  r.body = res.body();
  for (const auto& f : res)
    r.headers[std::string(f.name_string())] = std::string(f.value());
  beast::error_code ec;
  stream.socket().shutdown(boost::asio::ip::tcp::socket::shutdown_both, ec);
  return r;
}

class WsClient {
 public:
  explicit WsClient(unsigned short port) : ws_(io_) {
    namespace beast = boost::beast;
    beast::get_lowest_layer(ws_).expires_after(std::chrono::seconds(10));
    beast::get_lowest_layer(ws_).connect(
        boost::asio::ip::tcp::endpoint(boost::asio::ip::make_address("127.0.0.1"), port));
    beast::get_lowest_layer(ws_).expires_never();
    ws_.set_option(
        boost::beast::websocket::stream_base::timeout::suggested(beast::role_type::client));
    ws_.handshake("127.0.0.1:" + std::to_string(port), "/api/v1/stream");
  }
  void send(const std::string& text) { ws_.write(boost::asio::buffer(text)); }
  // The next text message, or empty when none arrives within the timeout.
  std::optional<std::string> read(std::chrono::milliseconds timeout) {
    namespace beast = boost::beast;
    std::optional<std::string> out;
    beast::flat_buffer buffer;
    ws_.async_read(buffer, [&](beast::error_code ec, std::size_t) {
      if (!ec) out = beast::buffers_to_string(buffer.data());
    });
    io_.restart();
    io_.run_for(timeout);
    if (!io_.stopped()) {
      // Timed out: cancel the read so the stream is usable again.
      beast::get_lowest_layer(ws_).socket().cancel();
      io_.restart();
      io_.run();
    }
    return out;
  }

 private:
  boost::asio::io_context io_;
  boost::beast::websocket::stream<boost::beast::tcp_stream> ws_;
};

}  // namespace avk::testing
