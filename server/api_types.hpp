#pragma once
// What the HTTP transport and the station's handlers exchange, without Beast: the transport
// parses a request into ApiRequest and writes ApiResponse back, so every handler is testable
// without a socket and Beast's headers stay in the transport files.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "server/body_file.hpp"

namespace avk::server {

struct ApiRequest {
  std::string method;                        // "GET", "POST", ...
  std::string path;                          // decoded path, without the query
  std::map<std::string, std::string> query;  // decoded; a repeated key keeps every value in multi
  std::multimap<std::string, std::string> multi_query;
  std::string body;
  std::string content_type;  // as sent, e.g. "application/json; charset=utf-8"
  std::string accept;
  std::string authorization;
  std::string origin;
  std::string host;
  std::string remote_address;
  bool remote_is_loopback = true;
};

struct ApiResponse {
  ApiResponse() = default;
  ApiResponse(int status_code, std::string type, std::string text,
              std::vector<std::pair<std::string, std::string>> extra_headers = {})
      : status(status_code),
        content_type(std::move(type)),
        body(std::move(text)),
        headers(std::move(extra_headers)) {}

  int status = 200;
  std::string content_type = "application/json";
  std::string body;
  std::vector<std::pair<std::string, std::string>> headers;  // extra (Location, ...)
  std::shared_ptr<BodyFile> body_file;                       // sent instead of body when set
};

// Where the transport runs a request's work.
enum class Workload {
  immediate,  // on the I/O thread: constant work with no I/O (/health), never queued
  cheap,      // on a request worker
  expensive,  // on a request worker, limited in number at once and per client address
};

// What the API decides from a request's header alone, before the transport reads its body: a
// client without the token must not make the server hold 64 MB for it, and the route (not the
// transport) knows how large its body may be and how much work its answer takes.
struct Admission {
  std::optional<ApiResponse> refusal;           // sent as is; the body is never read
  std::optional<std::size_t> body_limit_bytes;  // none: the transport's default
  Workload workload = Workload::cheap;
};

// The REST API behind /api/v1. handle() is called concurrently from the transport's request
// workers (and, for immediate work, its I/O threads); admit() and may_open_stream() from its I/O
// threads.
class Api {
 public:
  virtual ~Api() = default;
  virtual ApiResponse handle(const ApiRequest& request) = 0;
  // Whether this client may open the live stream; asked by the transport before the upgrade.
  // Browsers cannot set headers on a WebSocket, so a `?token=` of the upgrade request arrives
  // here as `authorization` ("Bearer <token>"). The default lets everyone in (test doubles).
  virtual bool may_open_stream(const ApiRequest& request) {
    (void)request;
    return true;
  }

  // head: the request with an empty body. Default: admitted with the transport's limit.
  virtual Admission admit(const ApiRequest& head) {
    (void)head;
    return {};
  }
};

// --- the live stream --------------------------------------------------------------------

// One message of the stream, serialised once and shared by every session that sends it.
struct StreamMessage {
  std::string topic;
  std::uint64_t seq = 0;
  // Telemetry (nav, helm) is latest-value-wins: an unsent older frame of the same topic is
  // replaced. Events (mission, turn, status) are queued and never dropped silently.
  bool latest_value_wins = false;
  // What a latest-value-wins frame replaces: an unsent frame of the same topic about the same
  // vehicle (one vehicle's telemetry never replaces another's).
  std::string latest_key;
  // Telemetry sent continuously (nav, helm): a client may ask for fewer per second (max_hz).
  bool rate_limitable = false;
  std::shared_ptr<const std::string> payload;  // {"topic","seq","t","data"} as text
};

// A stream client as the hub sees it. deliver() must not block: it hands the message to the
// session's own queue (on its strand) and returns.
class StreamSink {
 public:
  virtual ~StreamSink() = default;
  virtual void deliver(std::shared_ptr<const StreamMessage> message) = 0;
};

}  // namespace avk::server
