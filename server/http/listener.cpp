#include "server/http/listener.hpp"

#include <chrono>
#include <stdexcept>
#include <utility>

#include "server/http/http_session.hpp"
#include "server/http/problem.hpp"
#include "server/http/responses.hpp"
#include "server/http/server_state.hpp"

namespace avk::server {

namespace {

std::string endpoint_text(const tcp::endpoint& endpoint) {
  const auto address = endpoint.address().to_string();
  return (endpoint.address().is_v6() ? "[" + address + "]" : address) + ":" +
         std::to_string(endpoint.port());
}

}  // namespace

Listener::Listener(net::io_context& ioc, const tcp::endpoint& endpoint,
                   std::shared_ptr<ServerState> state)
    : ioc_(ioc),
      acceptor_(net::make_strand(ioc)),
      retry_timer_(acceptor_.get_executor()),
      state_(std::move(state)) {
  beast::error_code ec;
  const auto fail = [&](const char* what) {
    throw std::runtime_error("cannot listen on " + endpoint_text(endpoint) + ": " + what + ": " +
                             ec.message());
  };
  acceptor_.open(endpoint.protocol(), ec);
  if (ec) fail("open");
  acceptor_.set_option(net::socket_base::reuse_address(true), ec);
  if (ec) fail("set_option");
  acceptor_.bind(endpoint, ec);
  if (ec) fail("bind");
  acceptor_.listen(net::socket_base::max_listen_connections, ec);
  if (ec) fail("listen");
  port_ = acceptor_.local_endpoint(ec).port();
  if (ec) fail("local_endpoint");
}

void Listener::run() {
  net::dispatch(acceptor_.get_executor(),
                beast::bind_front_handler(&Listener::do_accept, shared_from_this()));
}

void Listener::stop() {
  net::post(acceptor_.get_executor(), [self = shared_from_this()] {
    self->stopped_ = true;
    beast::error_code ec;
    self->acceptor_.close(ec);
    self->retry_timer_.cancel();
  });
}

void Listener::do_accept() {
  if (stopped_) return;
  // Each connection gets its own strand: its handlers never run concurrently.
  acceptor_.async_accept(net::make_strand(ioc_),
                         beast::bind_front_handler(&Listener::on_accept, shared_from_this()));
}

void Listener::on_accept(beast::error_code ec, tcp::socket socket) {
  if (stopped_ || ec == net::error::operation_aborted) return;
  if (ec) {
    // Out of file descriptors, typically: retrying at once would spin a core.
    retry_timer_.expires_after(std::chrono::milliseconds(50));
    retry_timer_.async_wait([self = shared_from_this()](beast::error_code wait_ec) {
      if (!wait_ec) self->do_accept();
    });
    return;
  }
  // Small frames (a stream message after a client's subscribe, an API answer) must not wait for
  // the peer's delayed ACK: Nagle would hold them up to 40 ms.
  beast::error_code nodelay_ec;
  socket.set_option(tcp::no_delay(true), nodelay_ec);
  beast::error_code remote_ec;
  socket.remote_endpoint(remote_ec);
  if (remote_ec || !state_->make_room()) {
    refuse(socket);
  } else {
    std::make_shared<HttpSession>(std::move(socket), state_)->run();
  }
  do_accept();
}

void Listener::refuse(tcp::socket& socket) {
  // Written without waiting: a fresh socket's send buffer takes it whole, and a client that does
  // not read it loses nothing it was promised.
  static const std::string response = [] {
    const std::string body = problem_json(503, "too many connections; try again shortly");
    return "HTTP/1.1 503 Service Unavailable\r\nServer: avk-station\r\n"
           "Content-Type: application/problem+json\r\nRetry-After: 1\r\n"
           "Connection: close\r\nContent-Length: " +
           std::to_string(body.size()) + "\r\n\r\n" + body;
  }();
  beast::error_code ec;
  socket.non_blocking(true, ec);
  socket.write_some(net::buffer(response), ec);
  socket.shutdown(tcp::socket::shutdown_both, ec);
  socket.close(ec);
}

}  // namespace avk::server
