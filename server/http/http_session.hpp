#pragma once
// One HTTP connection: reads requests one at a time (keep-alive), routes them — the stream
// upgrade, the Api under /api/v1 (its work on the server's request workers), static files
// otherwise — and writes each response before it reads the next request. Every read and write has a
// deadline; malformed or oversized requests get their 4xx and the connection is closed.

#include <array>
#include <atomic>
#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "server/api_types.hpp"
#include "server/http/beast.hpp"
#include "server/http/response_generator.hpp"

namespace avk::server {

class ServerState;

class HttpSession : public std::enable_shared_from_this<HttpSession> {
 public:
  HttpSession(tcp::socket&& socket, std::shared_ptr<ServerState> state);
  ~HttpSession();

  void run();
  // Any thread: a session waiting for a request closes; one answering finishes first.
  void shutdown();
  // Any thread: closes the connection if it is still waiting for or reading a request (to make
  // room for a new connection); one being answered is left alone.
  void evict();
  // Whether evict() would close it now: waiting for or reading a request, or lingering after
  // its last answer.
  bool evictable() const { return awaiting_request_.load(); }
  const std::string& remote_address() const { return remote_address_; }

 private:
  enum class Phase { reading, handling, writing, lingering, done };

  void start_request();
  void on_first_byte(beast::error_code ec, std::size_t bytes);
  void read_header();
  void on_header(beast::error_code ec, std::size_t bytes);
  void on_continue_sent(beast::error_code ec, std::size_t bytes);
  void read_body();
  void on_body(beast::error_code ec, std::size_t bytes);
  void on_read_error(beast::error_code ec);

  // What the header alone decides (Host, encoding, the token, the body limit): an answer when
  // the request is refused before its body is read.
  std::optional<ResponseGenerator> check_header();
  void handle_request();
  // The Api's rule for the stream, with a `?token=` taken as the bearer token.
  bool may_open_stream(const Request& req, std::string_view raw_query) const;
  // On the I/O thread for immediate work, else queued for a request worker (or refused: 503
  // with a full queue, 429 when the address has its expensive requests already).
  void dispatch_api(Request req, std::string path, std::string raw_query, bool keep_alive);
  ResponseGenerator call_api(Request& req, std::string path, std::string_view raw_query,
                             bool keep_alive);
  // From a request worker: the answer is sent on the session's strand.
  void send_from_worker(ResponseGenerator message);
  ApiRequest api_request_of(const Request& req, std::string path, std::string_view raw_query) const;
  ResponseGenerator to_http(ApiResponse response, unsigned version, bool keep_alive);
  void reject(http::status status, std::string_view detail);
  void expires_within(std::chrono::milliseconds limit);
  void send(ResponseGenerator message);
  void on_write(bool keep_alive, beast::error_code ec, std::size_t bytes);
  void linger();
  void on_linger(beast::error_code ec, std::size_t bytes);
  void close_now();

  beast::tcp_stream stream_;
  beast::flat_buffer buffer_;
  std::optional<http::request_parser<http::string_body>> parser_;
  std::shared_ptr<ServerState> state_;
  std::string remote_address_;
  bool remote_is_loopback_ = false;
  Phase phase_ = Phase::reading;
  bool first_request_ = true;
  bool established_ = false;             // counted as a connection that has sent a request
  bool head_ = false;                    // the request being answered is a HEAD
  Workload workload_ = Workload::cheap;  // the request being answered, as the Api admitted it
  std::chrono::steady_clock::time_point request_deadline_{};
  std::atomic<bool> awaiting_request_{true};
  std::array<char, 4096> discard_{};
};

}  // namespace avk::server
