// The only file in vehicle/ that includes Asio: the M200's TCP link.
#include "vehicle/m200.hpp"

#include <array>
#include <atomic>
#include <boost/asio/connect.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/asio/write.hpp>
#include <charconv>
#include <condition_variable>
#include <mutex>
#include <stdexcept>
#include <string_view>
#include <thread>

namespace avk::vehicle {

namespace asio = boost::asio;
using tcp = asio::ip::tcp;

M200Endpoint parse_m200_endpoint(const std::string& text) {
  M200Endpoint e;
  const auto colon = text.rfind(':');
  e.host = colon == std::string::npos ? text : text.substr(0, colon);
  if (e.host.empty()) throw std::invalid_argument("'" + text + "': no host (HOST:PORT)");
  if (colon != std::string::npos) {
    const std::string p = text.substr(colon + 1);
    unsigned port = 0;
    const auto r = std::from_chars(p.data(), p.data() + p.size(), port);
    if (r.ec != std::errc() || r.ptr != p.data() + p.size() || port == 0 || port > 65535)
      throw std::invalid_argument("'" + text + "': the port must be a number from 1 to 65535");
    e.port = static_cast<unsigned short>(port);
  }
  return e;
}

struct M200::Impl {
  M200Options options;
  const ScaledClock& clock;

  mutable std::mutex mutex;  // session and last_link_error
  mutable std::condition_variable nav_arrived;
  M200Session session;
  std::string last_link_error;

  // Network thread only.
  asio::io_context io;
  tcp::resolver resolver{io};
  tcp::socket socket{io};
  asio::steady_timer control_timer{io};
  asio::steady_timer reconnect_timer{io};
  std::array<char, 4096> read_buffer{};
  bool link_up = false;
  bool writing = false;
  std::string in_flight;
  std::optional<std::string> queued;  // only the newest command matters
  std::uint64_t generation = 0;       // callbacks of a closed connection are ignored
  double backoff_s;
  asio::steady_timer::time_point next_control;
  std::thread thread;

  Impl(M200Options o, const ScaledClock& c)
      : options(std::move(o)),
        clock(c),
        session(options.config),
        backoff_s(options.reconnect_min_s) {
    if (!(options.reconnect_min_s > 0.0) || options.reconnect_max_s < options.reconnect_min_s)
      throw std::invalid_argument("M200 reconnect backoff must be positive, min <= max");
  }

  void connect() {
    const std::uint64_t gen = ++generation;
    resolver.async_resolve(
        options.endpoint.host, std::to_string(options.endpoint.port),
        [this, gen](const boost::system::error_code& ec, tcp::resolver::results_type results) {
          if (gen != generation) return;
          if (ec) return fail("cannot resolve " + options.endpoint.host + ": " + ec.message());
          asio::async_connect(
              socket, results,
              [this, gen](const boost::system::error_code& ec2, const tcp::endpoint&) {
                if (gen != generation) return;
                if (ec2) return fail("cannot connect: " + ec2.message());
                connected();
              });
        });
  }

  void connected() {
    boost::system::error_code ignored;
    socket.set_option(tcp::no_delay(true), ignored);
    link_up = true;
    {
      std::lock_guard lock(mutex);
      session.on_connected(clock.now_s());
      last_link_error.clear();
    }
    read();
  }

  void read() {
    const std::uint64_t gen = generation;
    socket.async_read_some(asio::buffer(read_buffer),
                           [this, gen](const boost::system::error_code& ec, std::size_t n) {
                             if (gen != generation) return;
                             if (ec) {
                               return fail(ec == asio::error::eof ? "the frontseat closed the link"
                                                                  : "read: " + ec.message());
                             }
                             received(n);
                             read();
                           });
  }

  void received(std::size_t n) {
    const double now = clock.now_s();
    std::lock_guard lock(mutex);
    const std::uint64_t before = session.counters().nav_samples;
    session.on_received(std::string_view(read_buffer.data(), n), now);
    if (session.counters().nav_samples != before) {
      // Only navigation proves the link healthy: a frontseat that accepts and drops us at once
      // (rebooting, or refusing while its radio is down) keeps the backoff growing.
      backoff_s = options.reconnect_min_s;
      nav_arrived.notify_all();
    }
  }

  void fail(const std::string& why) {
    ++generation;
    boost::system::error_code ignored;
    socket.close(ignored);
    link_up = false;
    writing = false;
    queued.reset();
    {
      std::lock_guard lock(mutex);
      session.on_disconnected(clock.now_s());
      last_link_error = why;
    }
    reconnect_timer.expires_after(clock.wall_duration(backoff_s));
    backoff_s = std::min(backoff_s * 2.0, options.reconnect_max_s);
    reconnect_timer.async_wait([this](const boost::system::error_code& ec) {
      if (!ec) connect();
    });
  }

  void schedule_control() {
    const auto period = clock.wall_duration(1.0 / options.config.controller_hz);
    next_control += period;
    const auto now = asio::steady_timer::clock_type::now();
    if (next_control < now - period) next_control = now + period;  // starved: do not burst
    control_timer.expires_at(next_control);
    control_timer.async_wait([this](const boost::system::error_code& ec) {
      if (ec) return;
      std::string line;
      {
        std::lock_guard lock(mutex);
        line = session.control_tick(clock.now_s());
      }
      if (link_up && !line.empty()) send(std::move(line));
      schedule_control();
    });
  }

  void send(std::string line) {
    if (writing) {
      queued = std::move(line);
      return;
    }
    writing = true;
    in_flight = std::move(line);
    const std::uint64_t gen = generation;
    asio::async_write(socket, asio::buffer(in_flight),
                      [this, gen](const boost::system::error_code& ec, std::size_t) {
                        if (gen != generation) return;
                        writing = false;
                        if (ec) return fail("write: " + ec.message());
                        if (queued) {
                          std::string next = std::move(*queued);
                          queued.reset();
                          send(std::move(next));
                        }
                      });
  }
};

M200::M200(M200Options options, const ScaledClock& clock)
    : impl_(std::make_unique<Impl>(std::move(options), clock)), info_(impl_->session.info()) {
  Impl& i = *impl_;
  i.next_control = asio::steady_timer::clock_type::now();
  asio::post(i.io, [&i] {
    i.connect();
    i.schedule_control();
  });
  i.thread = std::thread([&i] { i.io.run(); });
}

M200::~M200() {
  stop();
}

void M200::stop() {
  if (!impl_->thread.joinable()) return;
  Impl& i = *impl_;
  asio::post(i.io, [&i] {
    ++i.generation;
    boost::system::error_code ignored;
    i.socket.close(ignored);
    i.resolver.cancel();
    i.control_timer.cancel();
    i.reconnect_timer.cancel();
    i.io.stop();
  });
  i.thread.join();
  std::lock_guard lock(i.mutex);
  i.session.on_disconnected(i.clock.now_s());
}

std::vector<NavSample> M200::take_nav() {
  std::lock_guard lock(impl_->mutex);
  return impl_->session.take_nav();
}

std::optional<NavSample> M200::last_nav() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->session.last_nav();
}

LinkState M200::link_state(double now_s) const {
  std::lock_guard lock(impl_->mutex);
  return impl_->session.link_state(now_s);
}

void M200::command(const DesiredCommand& desired) {
  std::lock_guard lock(impl_->mutex);
  impl_->session.command(desired);
}

void M200::all_stop(double now_s) {
  std::lock_guard lock(impl_->mutex);
  impl_->session.all_stop(now_s);
}

std::optional<DesiredCommand> M200::last_command() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->session.last_command();
}

std::optional<ActuatorCommand> M200::last_actuators() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->session.last_actuators();
}

M200Status M200::status() const {
  std::lock_guard lock(impl_->mutex);
  M200Status s;
  s.connected = impl_->session.connected();
  s.link = impl_->session.link_state(impl_->clock.now_s());
  s.failsafe = impl_->session.failsafe();
  s.battery = impl_->session.battery();
  s.counters = impl_->session.counters();
  s.last_link_error = impl_->last_link_error;
  return s;
}

bool M200::wait_for_nav(std::chrono::milliseconds timeout) const {
  std::unique_lock lock(impl_->mutex);
  return impl_->nav_arrived.wait_for(lock, timeout,
                                     [&] { return impl_->session.last_nav().has_value(); });
}

}  // namespace avk::vehicle
