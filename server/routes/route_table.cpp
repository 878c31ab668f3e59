#include "server/routes/route_table.hpp"

#include <stdexcept>

#include "server/api_params.hpp"

namespace avk::server {

using nlohmann::json;

RouteTable::RouteTable(Router& router, const Costs& costs) : router_(router) {
  for (const auto& [key, cost] : costs)
    costs_.emplace(key, std::pair{cost, false});
}

void RouteTable::route(std::string method, std::string pattern, Access access, RouteHandler h,
                       std::optional<std::size_t> limit,
                       std::vector<Representation> representations) {
  RouteCost cost;
  if (const auto it = costs_.find(method + " " + pattern); it != costs_.end()) {
    cost = it->second.first;
    it->second.second = true;
  }
  Route r;
  r.method = std::move(method);
  r.pattern = std::move(pattern);
  r.access = access;
  r.body_limit_bytes = limit;
  r.handler = std::move(h);
  r.representations = std::move(representations);
  router_.add(std::move(r), std::move(cost));
}

void RouteTable::get(std::string pattern, RouteHandler h,
                     std::vector<Representation> representations) {
  route("GET", std::move(pattern), Access::read, std::move(h), std::nullopt,
        std::move(representations));
}

void RouteTable::post(std::string pattern, RouteHandler h, std::optional<std::size_t> limit) {
  route("POST", std::move(pattern), Access::control, std::move(h), limit, {kJsonRepresentation});
}

void RouteTable::post_question(std::string pattern, RouteHandler h) {
  route("POST", std::move(pattern), Access::read, std::move(h), std::nullopt,
        {kJsonRepresentation});
}

void RouteTable::check_costs() const {
  for (const auto& [key, cost] : costs_)
    if (!cost.second) throw std::logic_error("Station: a cost for no route: " + key);
}

ApiResponse json_response(const json& j, int status) {
  return {status, "application/json", j.dump(), {}};
}

ApiResponse csv_response(std::string body, const std::string& filename) {
  ApiResponse r{200, "text/csv; charset=utf-8", std::move(body), {}};
  if (!filename.empty())
    r.headers.push_back({"Content-Disposition", "attachment; filename=\"" + filename + "\""});
  return r;
}

ApiResponse created(const json& j, const std::string& location) {
  ApiResponse r = json_response(j, 201);
  r.headers.push_back({"Location", location});
  return r;
}

json body_object(const ApiRequest& r, const std::string& what) {
  require_media_type(r, "application/json", "send " + what + " as JSON");
  json body = json::parse(r.body, nullptr, false);
  if (body.is_discarded() || !body.is_object())
    throw RequestError(400, "the body is not a JSON object");
  return body;
}

RequestError bad_field(const std::string& pointer, const std::string& why) {
  return RequestError(422, pointer + " " + why, {{"pointer", pointer}});
}

}  // namespace avk::server
