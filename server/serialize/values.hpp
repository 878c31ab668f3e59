#pragma once
// The values every document is made of: numbers as text, record ids, optional values, a mean with
// its spread, a polyline; and a client's value quoted in an error message.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "kinematics/ckt.hpp"
#include "kinematics/geometry.hpp"

namespace avk::server {

// Numbers in CSV and messages: the shortest text that reads back as the same double.
std::string num(double v);
// Fixed decimals, for tables an operator reads.
std::string fixed(double v, int decimals);
// A record id as a path or an option gives it: a positive whole number, nothing else.
std::optional<std::int64_t> record_id(const std::string& text);
nlohmann::json optional_json(const std::optional<double>& v);
nlohmann::json optional_json(const std::optional<std::int64_t>& v);
nlohmann::json mean_sd_json(const std::optional<kinematics::MeanSd>& v);
nlohmann::json points_json(const kinematics::Polyline& line);  // [[x_m, y_m], ...]

// A page of a listing: {items: [to_json(item), ...], next: the cursor of the next page or null}.
template <class Page, class ToJson>
nlohmann::json page_json(const Page& page, ToJson to_json) {
  nlohmann::json items = nlohmann::json::array();
  for (const auto& item : page.items)
    items.push_back(to_json(item));
  return {{"items", std::move(items)}, {"next", optional_json(page.next)}};
}

// A value a client sent, for an error message: a scalar shortened, a container by its kind only.
std::string describe_value(const nlohmann::json& v);

}  // namespace avk::server
