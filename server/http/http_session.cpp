#include "server/http/http_session.hpp"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <exception>
#include <limits>
#include <map>
#include <utility>

#include "server/http/responses.hpp"
#include "server/http/server_state.hpp"
#include "server/http/url.hpp"
#include "server/http/websocket_session.hpp"

namespace avk::server {

namespace {

constexpr std::string_view kApiPrefix = "/api/v1/";
constexpr std::string_view kStreamPath = "/api/v1/stream";
// How long a closing connection may keep sending what we will not read (the rest of an
// oversized body): closing with unread data sends a reset that can destroy our error response
// in the client's buffer before it reads it.
constexpr std::chrono::milliseconds kMaxLinger{1000};

const beast::error_category& http_errors() {
  static const auto& category = http::make_error_code(http::error::bad_method).category();
  return category;
}

bool has_line_break(std::string_view s) {
  return s.find_first_of("\r\n") != std::string_view::npos;
}

}  // namespace

HttpSession::HttpSession(tcp::socket&& socket, std::shared_ptr<ServerState> state)
    : stream_(std::move(socket)), state_(std::move(state)) {}

HttpSession::~HttpSession() {
  state_->remove(this);
}

void HttpSession::run() {
  state_->add(shared_from_this());
  beast::error_code ec;
  const auto remote = stream_.socket().remote_endpoint(ec);
  if (!ec) {
    const auto address = remote.address();
    remote_address_ = address.to_string();
    remote_is_loopback_ =
        address.is_loopback() ||
        (address.is_v6() && address.to_v6().is_v4_mapped() &&
         net::ip::make_address_v4(net::ip::v4_mapped, address.to_v6()).is_loopback());
  }
  net::dispatch(stream_.get_executor(),
                beast::bind_front_handler(&HttpSession::start_request, shared_from_this()));
}

void HttpSession::shutdown() {
  net::post(stream_.get_executor(), [self = shared_from_this()] {
    if (self->phase_ == Phase::reading || self->phase_ == Phase::lingering) self->close_now();
  });
}

std::size_t HttpSession::body_limit_for(const std::string& path) const {
  const auto& options = state_->options();
  const auto it = options.body_limit_by_path.find(path);
  return it == options.body_limit_by_path.end() ? options.body_limit : it->second;
}

void HttpSession::start_request() {
  if (state_->stopping()) return close_now();
  phase_ = Phase::reading;
  const auto& options = state_->options();
  parser_.emplace();
  parser_->header_limit(static_cast<std::uint32_t>(
      std::min<std::size_t>(options.header_limit, std::numeric_limits<std::uint32_t>::max())));
  // The path, and with it the real limit, is known only after the header; until then the
  // largest limit, so that the parser does not refuse a Content-Length we would accept.
  std::size_t largest = options.body_limit;
  for (const auto& [path, limit] : options.body_limit_by_path)
    largest = std::max(largest, limit);
  parser_->body_limit(largest);

  if (first_request_ || buffer_.size() > 0) return read_header();
  // Between keep-alive requests the idle timeout applies; the header timeout starts with the
  // first byte of the next request.
  stream_.expires_after(options.idle_timeout);
  stream_.async_read_some(
      buffer_.prepare(4096),
      beast::bind_front_handler(&HttpSession::on_first_byte, shared_from_this()));
}

void HttpSession::on_first_byte(beast::error_code ec, std::size_t bytes) {
  if (ec) return close_now();
  buffer_.commit(bytes);
  read_header();
}

void HttpSession::read_header() {
  first_request_ = false;
  stream_.expires_after(state_->options().header_timeout);
  http::async_read_header(stream_, buffer_, *parser_,
                          beast::bind_front_handler(&HttpSession::on_header, shared_from_this()));
}

void HttpSession::on_header(beast::error_code ec, std::size_t) {
  if (ec) return on_read_error(ec);
  const auto& req = parser_->get();
  const std::string path = percent_decode(split_target(req.target()).path, false);
  const std::size_t limit = body_limit_for(path);
  if (const auto length = parser_->content_length(); length && *length > limit)
    return reject(http::status::payload_too_large,
                  "request body larger than " + std::to_string(limit) + " bytes");
  parser_->body_limit(limit);

  // curl and others wait for this before they send a large body.
  if (!parser_->is_done() && beast::iequals(req[http::field::expect], "100-continue")) {
    auto res =
        std::make_shared<http::response<http::empty_body>>(http::status::continue_, req.version());
    stream_.expires_after(state_->options().idle_timeout);
    http::async_write(stream_, *res,
                      [self = shared_from_this(), res](beast::error_code write_ec, std::size_t n) {
                        self->on_continue_sent(write_ec, n);
                      });
    return;
  }
  read_body();
}

void HttpSession::on_continue_sent(beast::error_code ec, std::size_t) {
  if (ec) return close_now();
  read_body();
}

void HttpSession::read_body() {
  if (parser_->is_done()) return handle_request();
  // Read piecewise so that the deadline is per pause, not for the whole body.
  stream_.expires_after(state_->options().idle_timeout);
  http::async_read_some(stream_, buffer_, *parser_,
                        beast::bind_front_handler(&HttpSession::on_body, shared_from_this()));
}

void HttpSession::on_body(beast::error_code ec, std::size_t) {
  if (ec) return on_read_error(ec);
  read_body();
}

void HttpSession::on_read_error(beast::error_code ec) {
  if (ec == http::error::header_limit)
    return reject(
        http::status::request_header_fields_too_large,
        "request header larger than " + std::to_string(state_->options().header_limit) + " bytes");
  if (ec == http::error::body_limit)
    return reject(http::status::payload_too_large, "request body too large");
  // A client that went away (or never finished) gets no answer; a malformed request does.
  if (ec == http::error::end_of_stream || ec == http::error::partial_message ||
      &ec.category() != &http_errors())
    return close_now();
  reject(http::status::bad_request, "malformed request: " + ec.message());
}

void HttpSession::handle_request() {
  phase_ = Phase::handling;
  Request req = parser_->release();
  const bool keep_alive = req.keep_alive() && !state_->stopping();
  const auto target = split_target(req.target());
  std::string path = percent_decode(target.path, false);

  if (path == kStreamPath) {
    if (!websocket::is_upgrade(req)) {
      auto res = problem_response(http::status::upgrade_required,
                                  "the stream is a WebSocket: connect with Upgrade: websocket",
                                  req.version(), keep_alive);
      res.set(http::field::upgrade, "websocket");
      return send(std::move(res));
    }
    // Browsers send Origin; a page from elsewhere must not read the station's stream with the
    // user's network position. Tools without a browser send none and are let in.
    const auto origin = req[http::field::origin];
    if (!origin.empty() && !same_origin(origin, req[http::field::host]))
      return send(problem_response(http::status::forbidden,
                                   "Origin " + std::string(origin) + " does not match Host " +
                                       std::string(req[http::field::host]),
                                   req.version(), keep_alive));
    if (!may_open_stream(req, target.query)) {
      auto res =
          problem_response(http::status::unauthorized,
                           "the stream needs the station's bearer token from this address "
                           "(Authorization: Bearer, or ?token= where a browser cannot set it)",
                           req.version(), keep_alive);
      res.set(http::field::www_authenticate, "Bearer");
      return send(std::move(res));
    }
    if (state_->stopping())
      return send(problem_response(http::status::service_unavailable, "server shutting down",
                                   req.version(), false));
    phase_ = Phase::done;
    std::make_shared<WebSocketSession>(stream_.release_socket(), state_)->run(std::move(req));
    return;
  }
  if (path + "/" == kApiPrefix || path.starts_with(kApiPrefix))
    return send(call_api(req, std::move(path), target.query, keep_alive));
  send(state_->static_files().respond(req, path, keep_alive));
}

bool HttpSession::may_open_stream(const Request& req, std::string_view raw_query) const {
  ApiRequest who;
  who.method = "GET";
  who.path = std::string(kStreamPath);
  who.authorization = std::string(req[http::field::authorization]);
  if (who.authorization.empty()) {
    std::map<std::string, std::string> query;
    std::multimap<std::string, std::string> multi;
    parse_query(raw_query, query, multi);
    if (const auto it = query.find("token"); it != query.end())
      who.authorization = "Bearer " + it->second;
  }
  who.origin = std::string(req[http::field::origin]);
  who.host = std::string(req[http::field::host]);
  who.remote_address = remote_address_;
  who.remote_is_loopback = remote_is_loopback_;
  return state_->api().may_open_stream(who);
}

http::message_generator HttpSession::call_api(Request& req, std::string path,
                                              std::string_view raw_query, bool keep_alive) {
  const unsigned version = req.version();
  const bool head = req.method() == http::verb::head;
  ApiResponse response;
  try {
    ApiRequest api_request;
    api_request.method = std::string(req.method_string());
    api_request.path = std::move(path);
    parse_query(raw_query, api_request.query, api_request.multi_query);
    api_request.content_type = std::string(req[http::field::content_type]);
    api_request.accept = std::string(req[http::field::accept]);
    api_request.authorization = std::string(req[http::field::authorization]);
    api_request.origin = std::string(req[http::field::origin]);
    api_request.host = std::string(req[http::field::host]);
    api_request.remote_address = remote_address_;
    api_request.remote_is_loopback = remote_is_loopback_;
    api_request.body = std::move(req.body());
    response = state_->api().handle(api_request);
  } catch (const std::exception& e) {
    return problem_response(http::status::internal_server_error, e.what(), version, keep_alive);
  } catch (...) {
    return problem_response(http::status::internal_server_error, "unknown error", version,
                            keep_alive);
  }

  // What a handler returns must not be able to break the framing of the response.
  if (response.status < 200 || response.status > 599)
    return problem_response(http::status::internal_server_error,
                            "handler returned status " + std::to_string(response.status), version,
                            keep_alive);
  if (has_line_break(response.content_type) ||
      std::any_of(response.headers.begin(), response.headers.end(), [](const auto& h) {
        return h.first.empty() || has_line_break(h.first) || has_line_break(h.second) ||
               h.first.find(':') != std::string::npos;
      }))
    return problem_response(http::status::internal_server_error,
                            "handler returned an invalid header", version, keep_alive);

  http::response<http::string_body> res;
  res.version(version);
  res.result(static_cast<unsigned>(response.status));
  set_common_headers(res);
  if (!response.content_type.empty()) res.set(http::field::content_type, response.content_type);
  for (const auto& [name, value] : response.headers)
    res.insert(name, value);
  res.keep_alive(keep_alive);
  const auto status = response.status;
  if (status == 204 || status == 304) {
    res.body().clear();
  } else if (head) {
    res.content_length(response.body.size());
    return res;
  } else {
    res.body() = std::move(response.body);
  }
  res.prepare_payload();
  return res;
}

void HttpSession::reject(http::status status, std::string_view detail) {
  const unsigned version = parser_ ? parser_->get().version() : 11;
  send(problem_response(status, detail, version == 10 ? 10 : 11, false));
}

void HttpSession::send(http::message_generator message) {
  phase_ = Phase::writing;
  const bool keep_alive = message.keep_alive();
  stream_.expires_after(state_->options().idle_timeout);
  beast::async_write(
      stream_, std::move(message),
      beast::bind_front_handler(&HttpSession::on_write, shared_from_this(), keep_alive));
}

void HttpSession::on_write(bool keep_alive, beast::error_code ec, std::size_t) {
  if (ec) return close_now();
  if (!keep_alive || state_->stopping()) return linger();
  start_request();
}

void HttpSession::linger() {
  phase_ = Phase::lingering;
  beast::error_code ec;
  stream_.socket().shutdown(tcp::socket::shutdown_send, ec);
  if (ec) return close_now();
  stream_.expires_after(
      std::min<std::chrono::milliseconds>(kMaxLinger, state_->options().close_timeout));
  stream_.async_read_some(net::buffer(discard_),
                          beast::bind_front_handler(&HttpSession::on_linger, shared_from_this()));
}

void HttpSession::on_linger(beast::error_code ec, std::size_t) {
  if (ec) return close_now();
  // Same deadline: a client that keeps sending does not keep the connection.
  stream_.async_read_some(net::buffer(discard_),
                          beast::bind_front_handler(&HttpSession::on_linger, shared_from_this()));
}

void HttpSession::close_now() {
  phase_ = Phase::done;
  beast::error_code ec;
  stream_.socket().shutdown(tcp::socket::shutdown_both, ec);
  stream_.close();
}

}  // namespace avk::server
