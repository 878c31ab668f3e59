#pragma once
// The stream's clients in bench_stream_load: well-behaved dashboards that read every nav message
// and time the probes, and one client that subscribes and then never reads. Used by one program
// only, so defined here whole.

#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/socket.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <chrono>
#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "support/ws_client.hpp"

namespace avk::bench {

namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
namespace net = boost::asio;
using tcp = net::ip::tcp;
using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;
using json = nlohmann::json;

inline tcp::endpoint loopback(unsigned short port) {
  return {net::ip::make_address("127.0.0.1"), port};
}

inline std::int64_t now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now().time_since_epoch())
      .count();
}

// The phase a message arrived in: set by the main thread, read by the io thread.
inline std::atomic<int> g_phase{-1};
inline constexpr int kPhases = 3;  // 0: baseline, 1: with the stalled client, 2: and heavy reads
inline constexpr const char* kPhaseNames[kPhases] = {"baseline (no stall)", "with stalled client",
                                                     "and heavy reads"};

struct PhaseStats {
  std::uint64_t messages = 0;  // every message that arrived in the phase
  std::uint64_t nav = 0;       // nav messages (vehicle and probe)
  std::vector<std::int64_t> latency_ns;
};

// A well-behaved dashboard: subscribes to nav and reads everything as fast as it comes.
class Client : public std::enable_shared_from_this<Client> {
 public:
  Client(net::io_context& ioc, unsigned short port, std::size_t probes_total,
         std::atomic<int>& subscribed_count, bool quickack)
      : ws_(ioc), port_(port), quickack_(quickack), subscribed_count_(subscribed_count) {
    got_probe.assign(probes_total, 0);
    probe_latency_ns.assign(probes_total, -1);
  }

  void start() {
    beast::get_lowest_layer(ws_).expires_after(10s);
    beast::get_lowest_layer(ws_).async_connect(
        loopback(port_), beast::bind_front_handler(&Client::on_connect, shared_from_this()));
  }

  // On the io thread.
  void close() {
    if (ended_ || closing_) return;
    closing_ = true;
    ws_.async_close(websocket::close_code::normal, [self = shared_from_this()](beast::error_code) {
      beast::error_code ignored;
      beast::get_lowest_layer(self->ws_).socket().close(ignored);
    });
  }

  std::array<PhaseStats, kPhases> phase{};
  std::uint64_t nav_seq_gaps = 0;  // nav messages skipped (latest-value-wins may drop some)
  std::vector<std::uint8_t> got_probe;
  std::vector<std::int64_t> probe_latency_ns;  // by probe id; -1: not received
  bool subscribed = false;
  beast::error_code end_error;  // how the read loop ended
  std::string failure;

 private:
  void on_connect(beast::error_code ec) {
    if (ec) return fail("connect", ec);
    beast::get_lowest_layer(ws_).socket().set_option(tcp::no_delay(true));
    // From here the websocket keeps its own deadlines; the tcp_stream's would cut a long read.
    beast::get_lowest_layer(ws_).expires_never();
    auto timeouts = websocket::stream_base::timeout::suggested(beast::role_type::client);
    timeouts.handshake_timeout = 5s;
    ws_.set_option(timeouts);
    ws_.async_handshake("127.0.0.1:" + std::to_string(port_), "/api/v1/stream",
                        beast::bind_front_handler(&Client::on_handshake, shared_from_this()));
  }

  void on_handshake(beast::error_code ec) {
    if (ec) return fail("handshake", ec);
    do_read();
  }

  void do_read() {
    ws_.async_read(buffer_, beast::bind_front_handler(&Client::on_read, shared_from_this()));
  }

  void on_read(beast::error_code ec, std::size_t) {
    const std::int64_t received_ns = now_ns();
    if (ec) {
      ended_ = true;
      end_error = ec;
      return;
    }
    const auto text = beast::buffers_to_string(buffer_.data());
    buffer_.consume(buffer_.size());
    handle(text, received_ns);
    do_read();
  }

  void handle(const std::string& text, std::int64_t received_ns) {
    const int p = g_phase.load(std::memory_order_relaxed);
    if (p >= 0 && p < kPhases) ++phase[static_cast<std::size_t>(p)].messages;
    const json m = json::parse(text, nullptr, false);
    if (m.is_discarded()) return;
    if (const auto type = m.find("type"); type != m.end()) {
      if (*type == "hello") {
        subscribe_text_ = R"({"subscribe":["nav"]})";
        ws_.async_write(net::buffer(subscribe_text_),
                        [self = shared_from_this()](beast::error_code e, std::size_t) {
                          if (e) return self->fail("subscribe", e);
                          if (self->quickack_) self->ack_at_once();
                        });
      } else if (*type == "subscribed" && !subscribed) {
        subscribed = true;
        ++subscribed_count_;
      }
      return;
    }
    if (m.value("topic", "") != "nav") return;
    if (p >= 0 && p < kPhases) ++phase[static_cast<std::size_t>(p)].nav;
    const auto seq = m.value("seq", std::uint64_t{0});
    if (last_nav_seq_ != 0 && seq > last_nav_seq_ + 1) nav_seq_gaps += seq - last_nav_seq_ - 1;
    last_nav_seq_ = std::max(last_nav_seq_, seq);
    const auto data_it = m.find("data");
    if (data_it == m.end() || !data_it->is_object() || !data_it->contains("probe_ns")) return;
    const json& data = *data_it;
    const auto id = data.value("probe", std::size_t{0});
    const auto probe_phase = data.value("phase", -1);
    const std::int64_t latency = received_ns - data["probe_ns"].get<std::int64_t>();
    if (id < got_probe.size()) {
      got_probe[id] = 1;
      probe_latency_ns[id] = latency;
    }
    if (probe_phase >= 0 && probe_phase < kPhases)
      phase[static_cast<std::size_t>(probe_phase)].latency_ns.push_back(latency);
  }

  void ack_at_once() {
    int one = 1;
    ::setsockopt(beast::get_lowest_layer(ws_).socket().native_handle(), IPPROTO_TCP, TCP_QUICKACK,
                 &one, sizeof one);
  }

  void fail(const char* what, beast::error_code ec) {
    if (failure.empty()) failure = std::string(what) + ": " + ec.message();
    ended_ = true;
    end_error = ec;
  }

  websocket::stream<beast::tcp_stream> ws_;
  unsigned short port_;
  bool quickack_;
  bool ended_ = false;
  bool closing_ = false;
  beast::flat_buffer buffer_;
  std::string subscribe_text_;
  std::uint64_t last_nav_seq_ = 0;
  std::atomic<int>& subscribed_count_;
};

// Connects and subscribes to nav and turn, then stops reading: its small receive window fills
// and the server's writes to it stay pending. Every operation has a deadline.
class StalledClient {
 public:
  // A 4 KiB receive window: a client that stops reading stalls the server's writes soon.
  explicit StalledClient(unsigned short port) : ws_(port, "", 4096) {
    check(ws_.handshake_error(), "handshake");
    ws_.send(R"({"subscribe":["nav","turn"]})");
  }

  struct Drain {
    std::uint64_t messages = 0;
    std::uint64_t first_nav_seq = 0, last_nav_seq = 0;
    std::uint64_t nav_gaps = 0;  // frames the server replaced while its write was stuck
    std::uint64_t turn_messages = 0;
    bool caught_up = false;                        // reached a nav frame published after the run
    std::optional<websocket::close_reason> close;  // a close frame the server sent
    beast::error_code end;
  };

  // Reads what has piled up, until a nav frame at or past live_seq (it has caught up with the
  // live stream), the server's close, an error or the limit.
  Drain drain(std::uint64_t live_seq, std::chrono::milliseconds limit) {
    Drain d;
    const auto deadline = Clock::now() + limit;
    while (Clock::now() < deadline) {
      const auto left =
          std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
      const auto text = ws_.read_text(std::max(left, 1ms));
      if (!text) {
        d.end = ws_.error();
        if (d.end == websocket::error::closed) d.close = ws_.close_reason();
        break;
      }
      ++d.messages;
      const json m = json::parse(*text, nullptr, false);
      if (m.is_discarded() || !m.contains("topic")) continue;
      if (m["topic"] == "turn") ++d.turn_messages;
      if (m["topic"] == "nav") {
        const auto seq = m.value("seq", std::uint64_t{0});
        if (d.first_nav_seq == 0) d.first_nav_seq = seq;
        if (d.last_nav_seq != 0 && seq > d.last_nav_seq + 1) d.nav_gaps += seq - d.last_nav_seq - 1;
        d.last_nav_seq = seq;
        if (seq >= live_seq) {
          d.caught_up = true;
          break;
        }
      }
    }
    return d;
  }

 private:
  static void check(beast::error_code ec, const char* what) {
    if (ec) throw std::runtime_error(std::string("stalled client: ") + what + ": " + ec.message());
  }

  avk::testing::WsClient ws_;
};

}  // namespace avk::bench
