#include "server/http/http_session.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdint>
#include <exception>
#include <iostream>
#include <limits>
#include <map>
#include <utility>

#include "server/http/descriptor_body.hpp"
#include "server/http/foxglove_session.hpp"
#include "server/http/responses.hpp"
#include "server/http/server_state.hpp"
#include "server/http/url.hpp"
#include "server/http/websocket_session.hpp"

namespace avk::server {

namespace {

constexpr std::string_view kApiPrefix = "/api/v1/";
constexpr std::string_view kStreamPath = "/api/v1/stream";
constexpr std::string_view kFoxglovePath = "/api/v1/foxglove";

// Sec-WebSocket-Protocol lists the client's subprotocols as a comma-separated token list.
bool offers_subprotocol(std::string_view header, std::string_view wanted) {
  for (const auto& item : http::token_list{header})
    if (item == wanted) return true;
  return false;
}

// How long a closing connection may keep sending what we will not read (the rest of an
// oversized body): closing with unread data sends a reset that can destroy our error response
// in the client's buffer before it reads it.
constexpr std::chrono::milliseconds kMaxLinger{1000};

// A live session lasts minutes to hours: a client over its address's cap waits a few seconds for
// one to close rather than retrying at once.
constexpr const char* kStreamRetryAfterS = "5";

const beast::error_category& http_errors() {
  static const auto& category = http::make_error_code(http::error::bad_method).category();
  return category;
}

bool has_line_break(std::string_view s) {
  return s.find_first_of("\r\n") != std::string_view::npos;
}

bool looks_like_json(std::string_view content_type, std::string_view body) {
  const auto semicolon = content_type.find(';');
  std::string type(content_type.substr(0, semicolon));
  std::transform(type.begin(), type.end(), type.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  while (!type.empty() && type.back() == ' ')
    type.pop_back();
  if (type == "application/json" || type.ends_with("+json")) return true;
  const auto first = body.find_first_not_of(" \t\r\n");
  return first != std::string_view::npos && (body[first] == '{' || body[first] == '[');
}

// A value a client sent, for an error message: short, so that no message grows with the input.
std::string quoted_excerpt(std::string_view text) {
  constexpr std::size_t kMax = 40;
  if (text.size() <= kMax) return "'" + std::string(text) + "'";
  return "'" + std::string(text.substr(0, kMax)) + "...'";
}

}  // namespace

HttpSession::HttpSession(tcp::socket&& socket, std::shared_ptr<ServerState> state)
    : stream_(std::move(socket)), state_(std::move(state)) {}

HttpSession::~HttpSession() {
  state_->remove(this);
}

void HttpSession::run() {
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
  state_->add(shared_from_this());
  net::dispatch(stream_.get_executor(),
                beast::bind_front_handler(&HttpSession::start_request, shared_from_this()));
}

void HttpSession::shutdown() {
  net::post(stream_.get_executor(), [self = shared_from_this()] {
    if (self->phase_ == Phase::reading || self->phase_ == Phase::lingering) self->close_now();
  });
}

void HttpSession::evict() {
  shutdown();
}

void HttpSession::expires_within(std::chrono::milliseconds limit) {
  const auto now = std::chrono::steady_clock::now();
  stream_.expires_at(std::min(now + limit, request_deadline_));
}

void HttpSession::start_request() {
  if (state_->stopping()) return close_now();
  phase_ = Phase::reading;
  awaiting_request_ = true;
  head_ = false;
  workload_ = Workload::cheap;
  const auto& options = state_->options();
  parser_.emplace();
  parser_->header_limit(static_cast<std::uint32_t>(
      std::min<std::size_t>(options.header_limit, std::numeric_limits<std::uint32_t>::max())));
  // The real limit is known only after the header (the route and the token decide it): until
  // then none, so that the parser does not answer a large Content-Length before the header has
  // been checked. check_header() sets the limit before any body byte is read.
  parser_->body_limit(std::numeric_limits<std::uint64_t>::max());

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
  request_deadline_ = std::chrono::steady_clock::now() + state_->options().request_timeout;
  expires_within(state_->options().header_timeout);
  http::async_read_header(stream_, buffer_, *parser_,
                          beast::bind_front_handler(&HttpSession::on_header, shared_from_this()));
}

void HttpSession::on_header(beast::error_code ec, std::size_t) {
  if (ec) return on_read_error(ec);
  head_ = parser_->get().method() == http::verb::head;
  // An upgrade is counted as a live session instead (max_streams_per_address).
  if (!established_ && !websocket::is_upgrade(parser_->get())) {
    established_ = state_->establish(this);
    if (!established_)
      return reject(http::status::service_unavailable,
                    "too many connections from this address (at most " +
                        std::to_string(state_->options().max_connections_per_address) +
                        " that have sent a request); try again shortly");
  }
  if (auto refusal = check_header()) return send(std::move(*refusal));

  const auto& req = parser_->get();
  // curl and others wait for this before they send a large body.
  if (!parser_->is_done() && beast::iequals(req[http::field::expect], "100-continue")) {
    auto res =
        std::make_shared<http::response<http::empty_body>>(http::status::continue_, req.version());
    expires_within(state_->options().idle_timeout);
    http::async_write(stream_, *res,
                      [self = shared_from_this(), res](beast::error_code write_ec, std::size_t n) {
                        self->on_continue_sent(write_ec, n);
                      });
    return;
  }
  read_body();
}

std::optional<ResponseGenerator> HttpSession::check_header() {
  const auto& req = parser_->get();
  const unsigned version = req.version() == 10 ? 10 : 11;
  // A refused request whose body is still coming cannot keep its connection: the body would be
  // read as the next request.
  const bool keep_alive = req.keep_alive() && parser_->is_done() && !state_->stopping();
  const auto refuse = [&](http::status status, std::string_view detail,
                          bool keep = false) -> ResponseGenerator {
    return body_unless_head(head_, problem_response(status, detail, version, keep && keep_alive));
  };
  const auto target = split_target(req.target());
  std::string path = percent_decode(target.path, false);

  // Two Host fields leave the target ambiguous (a proxy may route by one while this server checks
  // the other): RFC 9112 §3.2 requires a 400, on every path including the stream's upgrade.
  if (req.count(http::field::host) > 1)
    return refuse(http::status::bad_request, "more than one Host header");
  // DNS rebinding: a page of evil.example re-pointed at 127.0.0.1 sends Host: evil.example.
  const auto host = req[http::field::host];
  if (host.empty()) {
    if (version == 11) return refuse(http::status::bad_request, "HTTP/1.1 needs a Host header");
  } else if (!host_is_allowed(host, state_->options().allowed_hosts)) {
    const bool upgrade = path == kStreamPath;
    return refuse(upgrade ? http::status::forbidden : http::status::misdirected_request,
                  "this server does not answer to Host " + quoted_excerpt(host) +
                      " (start it with --allow-host NAME, or with NAME in " + kAllowHostsVariable +
                      ", to add a name)");
  }
  // No route has such a path; quoting it in the answer could not be done in JSON either.
  if (!is_valid_utf8(path))
    return refuse(http::status::not_found,
                  "no resource at this path (not valid UTF-8 once decoded)", true);

  std::size_t limit = state_->options().body_limit;
  if (path.starts_with(kApiPrefix) && path != kStreamPath) {
    std::map<std::string, std::string> query;
    std::multimap<std::string, std::string> multi;
    parse_query(target.query, query, multi);
    for (const auto& [key, value] : multi) {
      if (!is_valid_utf8(key))
        return refuse(http::status::bad_request, "a query parameter name is not valid UTF-8", true);
      if (!is_valid_utf8(value))
        return refuse(http::status::bad_request, "query parameter '" + key + "' is not valid UTF-8",
                      true);
    }
    Admission admission;
    try {
      admission = state_->api().admit(api_request_of(req, path, target.query));
    } catch (const std::exception& e) {
      std::cerr << "avk http: admit failed: " << e.what() << "\n";
      return refuse(http::status::internal_server_error, "internal error (see the server log)");
    }
    if (admission.refusal) return to_http(std::move(*admission.refusal), version, keep_alive);
    if (admission.body_limit_bytes) limit = *admission.body_limit_bytes;
    workload_ = admission.workload;
  }
  if (const auto length = parser_->content_length(); length && *length > limit)
    return refuse(http::status::payload_too_large,
                  "request body larger than " + std::to_string(limit) + " bytes");
  parser_->body_limit(limit);
  return std::nullopt;
}

void HttpSession::on_continue_sent(beast::error_code ec, std::size_t) {
  if (ec) return close_now();
  read_body();
}

void HttpSession::read_body() {
  if (parser_->is_done()) return handle_request();
  // Read piecewise so that the deadline is per pause, and within the whole request's.
  expires_within(state_->options().idle_timeout);
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
  awaiting_request_ = false;
  Request req = parser_->release();
  const bool keep_alive = req.keep_alive() && !state_->stopping();
  const auto target = split_target(req.target());
  std::string path = percent_decode(target.path, false);

  if (path == kStreamPath || path == kFoxglovePath) {
    if (!websocket::is_upgrade(req)) {
      auto res = problem_response(http::status::upgrade_required,
                                  path == kStreamPath
                                      ? "the stream is a WebSocket: connect with Upgrade: websocket"
                                      : "the Foxglove connection is a WebSocket: connect with "
                                        "Upgrade: websocket and Sec-WebSocket-Protocol: " +
                                            std::string(kFoxgloveSubprotocol),
                                  req.version(), keep_alive);
      res.set(http::field::upgrade, "websocket");
      return send(body_unless_head(head_, std::move(res)));
    }
    // Foxglove's clients ask for their protocol by name, on its own path or on the stream's.
    const bool foxglove =
        offers_subprotocol(req[http::field::sec_websocket_protocol], kFoxgloveSubprotocol);
    if (path == kFoxglovePath && !foxglove)
      return send(problem_response(http::status::bad_request,
                                   "this path speaks the Foxglove WebSocket protocol: offer "
                                   "Sec-WebSocket-Protocol: " +
                                       std::string(kFoxgloveSubprotocol),
                                   req.version(), keep_alive));
    // Browsers send Origin; a page from elsewhere must not read the station's stream with the
    // user's network position. Tools without a browser send none and are let in.
    const auto origin = req[http::field::origin];
    if (!origin.empty() &&
        !origin_allowed(origin, req[http::field::host], state_->options().allowed_origins))
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
    if (!state_->reserve_stream(remote_address_)) {
      auto res = problem_response(
          http::status::service_unavailable,
          "too many live connections from this address (at most " +
              std::to_string(state_->options().max_streams_per_address) +
              ": avk serve --max-streams-per-address); try again when one has closed",
          req.version(), keep_alive);
      res.set(http::field::retry_after, kStreamRetryAfterS);
      return send(std::move(res));
    }
    phase_ = Phase::done;
    awaiting_request_ = false;
    if (foxglove)
      std::make_shared<FoxgloveSession>(stream_.release_socket(), state_, remote_address_)
          ->run(std::move(req));
    else
      std::make_shared<WebSocketSession>(stream_.release_socket(), state_, remote_address_)
          ->run(std::move(req));
    // The connection is the WebSocket's now: counted once, as a stream.
    state_->remove(this);
    return;
  }
  if (path + "/" == kApiPrefix || path.starts_with(kApiPrefix))
    return dispatch_api(std::move(req), std::move(path), std::string(target.query), keep_alive);
  send(state_->static_files().respond(req, path, keep_alive));
}

void HttpSession::dispatch_api(Request req, std::string path, std::string raw_query,
                               bool keep_alive) {
  if (workload_ == Workload::immediate)
    return send(call_api(req, std::move(path), raw_query, keep_alive));
  const unsigned version = req.version();
  // Shared, so that the work is copyable (std::function); only the worker touches it.
  auto request = std::make_shared<Request>(std::move(req));
  auto work = [self = shared_from_this(), request, path = std::move(path),
               raw_query = std::move(raw_query), keep_alive, version](bool run) {
    if (!run)
      return self->send_from_worker(
          body_unless_head(self->head_, problem_response(http::status::service_unavailable,
                                                         "server shutting down", version, false)));
    self->send_from_worker(self->call_api(*request, path, raw_query, keep_alive));
  };
  const auto refuse = [&](http::status status, const std::string& detail, bool keep) {
    auto res = problem_response(status, detail, version, keep);
    res.set(http::field::retry_after, "1");
    send(body_unless_head(head_, std::move(res)));
  };
  switch (
      state_->pool().submit(workload_ == Workload::expensive, remote_address_, std::move(work))) {
    case RequestPool::Submitted::queued:
      return;
    case RequestPool::Submitted::queue_full:
      return refuse(http::status::service_unavailable,
                    "the server is busy: " + std::to_string(state_->pool().limits().queue) +
                        " requests are waiting; try again shortly",
                    keep_alive);
    case RequestPool::Submitted::address_busy:
      return refuse(http::status::too_many_requests,
                    "this address has " +
                        std::to_string(state_->pool().limits().expensive_per_address) +
                        " expensive requests running or waiting already (analyses, "
                        "held-out predictions, exports); try again when one has answered",
                    keep_alive);
    case RequestPool::Submitted::closed:
      return refuse(http::status::service_unavailable, "server shutting down", false);
  }
}

void HttpSession::send_from_worker(ResponseGenerator message) {
  net::post(stream_.get_executor(), [self = shared_from_this(), m = std::move(message)]() mutable {
    self->send(std::move(m));
  });
}

bool HttpSession::may_open_stream(const Request& req, std::string_view raw_query) const {
  ApiRequest who = api_request_of(req, std::string(kStreamPath), raw_query);
  who.method = "GET";
  if (who.authorization.empty()) {
    if (const auto it = who.query.find("token"); it != who.query.end())
      who.authorization = "Bearer " + it->second;
  }
  return state_->api().may_open_stream(who);
}

ApiRequest HttpSession::api_request_of(const Request& req, std::string path,
                                       std::string_view raw_query) const {
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
  return api_request;
}

ResponseGenerator HttpSession::call_api(Request& req, std::string path, std::string_view raw_query,
                                        bool keep_alive) {
  const unsigned version = req.version();
  const auto limit = state_->options().json_depth_limit;
  if (looks_like_json(req[http::field::content_type], req.body()) &&
      json_deeper_than(req.body(), limit))
    return body_unless_head(head_,
                            problem_response(http::status::bad_request,
                                             "the JSON body nests arrays and objects deeper than " +
                                                 std::to_string(limit) + " levels",
                                             version, keep_alive));
  ApiResponse response;
  try {
    ApiRequest api_request = api_request_of(req, std::move(path), raw_query);
    api_request.body = std::move(req.body());
    response = state_->api().handle(api_request);
  } catch (const std::exception& e) {
    // The log has the library's words; the client only learns that it was not its fault.
    std::cerr << "avk http: " << req.method_string() << " " << req.target() << ": " << e.what()
              << "\n";
    response = ApiResponse{500, "", "", {}};
  } catch (...) {
    response = ApiResponse{500, "", "", {}};
  }
  return to_http(std::move(response), version, keep_alive);
}

ResponseGenerator HttpSession::to_http(ApiResponse response, unsigned version, bool keep_alive) {
  const auto internal = [&](std::string_view log) {
    std::cerr << "avk http: " << log << "\n";
    return body_unless_head(
        head_, problem_response(http::status::internal_server_error,
                                "internal error (see the server log)", version, keep_alive));
  };
  // What a handler returns must not be able to break the framing of the response.
  if (response.status < 200 || response.status > 599)
    return internal("handler returned status " + std::to_string(response.status));
  if (has_line_break(response.content_type) ||
      std::any_of(response.headers.begin(), response.headers.end(), [](const auto& h) {
        return h.first.empty() || has_line_break(h.first) || has_line_break(h.second) ||
               h.first.find(':') != std::string::npos;
      }))
    return internal("handler returned an invalid header");
  // Last resort: a 500 says what failed in words meant for the log (a library's exception
  // text, a path on disk); the client gets a fixed sentence.
  if (response.status == 500) {
    if (!response.body.empty()) std::cerr << "avk http: 500: " << response.body << "\n";
    return internal("(the handler's answer above)");
  }

  http::response<http::string_body> res;
  res.version(version);
  res.result(static_cast<unsigned>(response.status));
  set_common_headers(res);
  if (!response.content_type.empty()) res.set(http::field::content_type, response.content_type);
  for (const auto& [name, value] : response.headers)
    res.insert(name, value);
  res.keep_alive(keep_alive);
  if (response.status == 204 || response.status == 304) {
    res.body().clear();
    res.prepare_payload();
    return res;
  }
  if (response.body_file) {
    std::uint64_t size = 0;
    try {
      size = response.body_file->size();
    } catch (const std::exception& e) {
      return internal(e.what());
    }
    res.content_length(size);
    if (head_) return http::response<http::empty_body>(std::move(res.base()));
    http::response<DescriptorBody> from_file(std::move(res.base()));
    from_file.body() = std::move(response.body_file);
    return from_file;
  }
  res.body() = std::move(response.body);
  res.prepare_payload();
  return body_unless_head(head_, std::move(res));
}

void HttpSession::reject(http::status status, std::string_view detail) {
  const unsigned version = parser_ ? parser_->get().version() : 11;
  auto res = problem_response(status, detail, version == 10 ? 10 : 11, false);
  if (status == http::status::service_unavailable) res.set(http::field::retry_after, "1");
  send(body_unless_head(head_, std::move(res)));
}

void HttpSession::send(ResponseGenerator message) {
  phase_ = Phase::writing;
  awaiting_request_ = false;
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
  // Answered already: under connection pressure it is the first to make room.
  awaiting_request_ = true;
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
