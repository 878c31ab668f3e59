#include "server/http/http_server.hpp"

#include <algorithm>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <thread>
#include <utility>
#include <vector>

#include "server/http/beast.hpp"
#include "server/http/listener.hpp"
#include "server/http/server_state.hpp"

namespace avk::server {

class HttpServer::Impl {
 public:
  Impl(HttpServerOptions options, Api& api, StreamSource& hub)
      : threads_count_(std::max(1, options.threads)),
        state_(std::make_shared<ServerState>(std::move(options), api, hub)),
        ioc_(threads_count_) {}

  ~Impl() { stop(); }

  void start() {
    if (started_) throw std::logic_error("HttpServer::start: already started");
    const auto& options = state_->options();
    beast::error_code ec;
    const auto address = net::ip::make_address(options.bind_address, ec);
    if (ec)
      throw std::runtime_error("cannot listen on " + options.bind_address + ":" +
                               std::to_string(options.port) + ": not an IP address");
    listener_ = std::make_shared<Listener>(ioc_, tcp::endpoint{address, options.port}, state_);
    started_ = true;
    // Without work (every client gone, the acceptor closed by stop) the io threads would return,
    // and what stop() posts to the sessions after that would never run.
    work_.emplace(ioc_.get_executor());
    state_->pool().start();
    listener_->run();
    threads_.reserve(static_cast<std::size_t>(threads_count_));
    for (int i = 0; i < threads_count_; ++i)
      threads_.emplace_back([this] { run_io(); });
  }

  unsigned short port() const { return listener_ ? listener_->port() : 0; }

  void stop() {
    if (!started_ || stopped_) return;
    stopped_ = true;
    listener_->stop();
    state_->begin_stop();
    // WebSockets get close_timeout for their close handshake before they cut the socket
    // themselves; the margin lets that happen before the io_context is stopped under them.
    const auto deadline = std::chrono::steady_clock::now() + state_->options().close_timeout +
                          std::chrono::milliseconds(250);
    state_->wait_until_idle(deadline);
    work_.reset();
    ioc_.stop();
    for (auto& t : threads_)
      t.join();
    threads_.clear();
    // A request running still runs to its end (its answer, posted to the stopped io_context, is
    // never sent); nothing may reach a session after the io_context goes.
    state_->pool().stop();
    state_->detach_sinks();
  }

  std::size_t open_stream_sessions() const { return state_->open_stream_sessions(); }
  std::size_t waiting_requests() const { return state_->pool().waiting(); }

 private:
  void run_io() {
    // Handlers catch their own exceptions; this only keeps one that slipped through from
    // taking the thread (and with it the whole process) down.
    for (;;) {
      try {
        ioc_.run();
        return;
      } catch (const std::exception& e) {
        std::cerr << "avk http: unexpected exception in an io thread: " << e.what() << "\n";
      } catch (...) {
        std::cerr << "avk http: unexpected exception in an io thread\n";
      }
    }
  }

  int threads_count_;
  bool started_ = false;
  bool stopped_ = false;
  std::shared_ptr<ServerState> state_;
  // Destroyed before state_ and after listener_: the sessions and the listener its unrun
  // handlers still hold go with it, and no socket outlives its io_context.
  net::io_context ioc_;
  std::optional<net::executor_work_guard<net::io_context::executor_type>> work_;
  std::shared_ptr<Listener> listener_;
  std::vector<std::thread> threads_;
};

HttpServer::HttpServer(HttpServerOptions options, Api& api, StreamSource& hub)
    : impl_(std::make_unique<Impl>(std::move(options), api, hub)) {}

HttpServer::~HttpServer() = default;

void HttpServer::start() {
  impl_->start();
}

unsigned short HttpServer::port() const {
  return impl_->port();
}

void HttpServer::stop() {
  impl_->stop();
}

std::size_t HttpServer::open_stream_sessions() const {
  return impl_->open_stream_sessions();
}

std::size_t HttpServer::waiting_requests() const {
  return impl_->waiting_requests();
}

}  // namespace avk::server
