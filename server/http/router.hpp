#pragma once
// The API's route table: method + path pattern -> handler, each route declaring who may call it,
// how large its body may be and how much work its answer takes. Answers what no handler should: 404
// for no route, 405 with Allow, 401 without the token, HEAD as the route's GET (the transport drops
// the body and keeps its Content-Length), a request error thrown by a handler as problem+json.

#include <cstddef>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "server/api_types.hpp"

namespace avk::server {

// read: open on this machine (loopback), the token from anywhere else. control: the token
// always, for anything that changes the station or commands the boat. image: a read that a page
// makes with an <img> (map tiles), which cannot carry a header: the token may also come as
// `?token=`, as on the stream's upgrade.
enum class Access { read, control, image };

using PathParams = std::map<std::string, std::string>;
using RouteHandler = std::function<ApiResponse(const ApiRequest&, const PathParams&)>;

// A form a route answers in: the name `?format=` gives it and its media type.
struct Representation {
  std::string format;      // "json", "csv", "mcap"
  std::string media_type;  // "application/json", "text/csv", ...
};
inline const Representation kJsonRepresentation{"json", "application/json"};
inline const Representation kCsvRepresentation{"csv", "text/csv"};

struct Route {
  std::string method;   // "GET" (answers HEAD too) or "POST"
  std::string pattern;  // "/api/v1/vehicles/{vid}/ckt/import": {name} matches one segment
  Access access = Access::read;
  std::optional<std::size_t> body_limit_bytes;  // none: the transport's default
  RouteHandler handler;
  // What the route answers in, the default first. The router refuses a request none of them
  // suits (406, or 400 for a `?format=` naming none) before the handler runs, so every route
  // negotiates alike; a handler offering several asks choose_representation which one to write.
  std::vector<Representation> representations = {kJsonRepresentation};
};

// How much work a route's answer takes (Admission::workload): immediate routes answer on the I/O
// thread, the rest on the transport's request workers; expensive ones (a fit, an evaluation of
// hundreds of candidates, an export) are limited in number and per client address.
struct RouteCost {
  Workload workload = Workload::cheap;
  // Query parameters that make a cheap route's request expensive when given (predict's
  // without_turn: a table built for the answer).
  std::vector<std::string> expensive_with = {};
};

// What a handler throws for a request it cannot take (a bad parameter, an unacceptable format);
// the router answers it as problem+json with this status.
class RequestError : public std::runtime_error {
 public:
  RequestError(int status, const std::string& detail,
               nlohmann::json extra = nlohmann::json::object())
      : std::runtime_error(detail), status_(status), extra_(std::move(extra)) {}
  int status() const { return status_; }
  const nlohmann::json& extra() const { return extra_; }

 private:
  int status_;
  nlohmann::json extra_;
};

// Which of `offered` (not empty, the default first) the request asks for. `?format=` names one
// by its short name and wins over Accept. Otherwise Accept's most preferred acceptable type: each
// offered type is weighed by the q of the most specific range matching it (type/subtype, then
// type/*, then */*), q=0 excludes it, ties go to the more specific range and then to the earlier
// offered. No Accept: the first. Throws RequestError: 400 naming `format` for a format not
// offered, 406 naming the media types offered (`acceptable`) when Accept allows none of them.
const Representation& choose_representation(const ApiRequest& request,
                                            const std::vector<Representation>& offered);

class Router : public Api {
 public:
  explicit Router(std::string token) : token_(std::move(token)) {}
  void add(Route route, RouteCost cost = {});
  const std::vector<Route>& routes() const { return routes_; }

  ApiResponse handle(const ApiRequest& request) override;
  bool may_open_stream(const ApiRequest& request) override;
  Admission admit(const ApiRequest& head) override;

 private:
  struct Match {
    const Route* route = nullptr;
    PathParams params;
    std::string allow;  // methods of the routes whose pattern matched, for a 405
  };
  Match match(const ApiRequest& request) const;
  bool authorised(const ApiRequest& request, Access access) const;
  std::optional<ApiResponse> refusal(const ApiRequest& request, Access access) const;

  std::string token_;
  std::vector<Route> routes_;
  std::vector<RouteCost> costs_;                    // routes_[i]'s
  std::vector<std::vector<std::string>> patterns_;  // routes_[i]'s pattern, split at '/'
};

}  // namespace avk::server
