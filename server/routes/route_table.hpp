#pragma once
// How the REST API's adapters join the station's route table: each resource's file adds its
// routes through a RouteTable, which sets their access, representations and cost, and writes
// their answers with the helpers below. docs/api.md lists the routes.

#include <cstddef>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "app/result.hpp"
#include "server/api_errors.hpp"
#include "server/http/router.hpp"

namespace avk::server {

// A collection or table: JSON, or CSV with units in its column names (docs/api.md, "CSV").
inline const std::vector<Representation> kJsonOrCsv{kJsonRepresentation, kCsvRepresentation};

class RouteTable {
 public:
  // What a route's answer costs, by "METHOD pattern"; a route not named is cheap.
  using Costs = std::map<std::string, RouteCost>;

  RouteTable(Router& router, const Costs& costs);

  // A read: open on loopback.
  void get(std::string pattern, RouteHandler h,
           std::vector<Representation> representations = {kJsonRepresentation});
  // A write or a command: a control endpoint.
  void post(std::string pattern, RouteHandler h, std::optional<std::size_t> limit = std::nullopt);
  // A question sent as a document that changes nothing and commands nothing: open on loopback,
  // like the reads.
  void post_question(std::string pattern, RouteHandler h);

  // Every cost names a route: throws std::logic_error naming one that does not.
  void check_costs() const;

 private:
  void route(std::string method, std::string pattern, Access access, RouteHandler h,
             std::optional<std::size_t> limit, std::vector<Representation> representations);

  Router& router_;
  std::map<std::string, std::pair<RouteCost, bool>> costs_;  // with whether a route took it
};

ApiResponse json_response(const nlohmann::json& j, int status = 200);
ApiResponse csv_response(std::string body, const std::string& filename = "");
ApiResponse created(const nlohmann::json& j, const std::string& location);

// The use case's value, or its error as problem+json.
template <class T, class F>
ApiResponse answer(const app::Result<T>& r, bool document, F&& write) {
  if (!r) return problem_of(r.error(), document);
  return write(*r);
}

// A request document: an object, else 400 (not JSON at all) before any field is looked at.
nlohmann::json body_object(const ApiRequest& r, const std::string& what);
RequestError bad_field(const std::string& pointer, const std::string& why);

}  // namespace avk::server
