#pragma once
// Accepts connections and hands each to its own HttpSession on its own strand.

#include <memory>

#include "server/http/beast.hpp"

namespace avk::server {

class ServerState;

class Listener : public std::enable_shared_from_this<Listener> {
 public:
  // Binds and listens; throws std::runtime_error naming address:port when that fails.
  Listener(net::io_context& ioc, const tcp::endpoint& endpoint, std::shared_ptr<ServerState> state);

  unsigned short port() const { return port_; }
  void run();
  // Any thread: stop accepting.
  void stop();

 private:
  void do_accept();
  void on_accept(beast::error_code ec, tcp::socket socket);
  void refuse(tcp::socket& socket);

  net::io_context& ioc_;
  tcp::acceptor acceptor_;
  net::steady_timer retry_timer_;
  std::shared_ptr<ServerState> state_;
  unsigned short port_ = 0;
  bool stopped_ = false;
};

}  // namespace avk::server
