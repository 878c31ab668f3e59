#include "server/api_params.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string_view>

#include "server/routes/route_table.hpp"
#include "server/serialize.hpp"

namespace avk::server {

RequestError bad_parameter(const std::string& name, const std::string& why) {
  return RequestError(400, "parameter '" + name + "': " + why, {{"parameter", name}});
}

std::optional<double> number_param(const ApiRequest& r, const std::string& name, double min,
                                   double max) {
  const auto it = r.query.find(name);
  if (it == r.query.end()) return std::nullopt;
  const std::string& v = it->second;
  if (v.empty()) throw bad_parameter(name, "empty");
  std::size_t used = 0;
  double d = 0.0;
  try {
    d = std::stod(v, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != v.size()) throw bad_parameter(name, "not a number: '" + v + "'");
  if (!std::isfinite(d)) throw bad_parameter(name, "must be finite");
  if (d < min || d > max)
    throw bad_parameter(name, "must be in [" + num(min) + ", " + num(max) + "], got " + v);
  return d;
}

double required_number(const ApiRequest& r, const std::string& name, double min, double max) {
  const auto v = number_param(r, name, min, max);
  if (!v) throw bad_parameter(name, "missing");
  return *v;
}

std::vector<double> required_numbers(const ApiRequest& r, const std::vector<NumberSpec>& specs) {
  std::vector<double> values;
  std::vector<RequestError> problems;
  for (const auto& spec : specs) {
    try {
      values.push_back(required_number(r, spec.name, spec.min, spec.max));
    } catch (const RequestError& e) {
      problems.push_back(e);
    }
  }
  if (problems.empty()) return values;
  if (problems.size() == 1) throw problems.front();
  std::string detail;
  nlohmann::json errors = nlohmann::json::array();
  for (const auto& p : problems) {
    if (!detail.empty()) detail += "; ";
    detail += p.what();
    errors.push_back({{"field", p.extra()["parameter"]}, {"message", p.what()}});
  }
  throw RequestError(400, detail,
                     {{"parameter", problems.front().extra()["parameter"]}, {"errors", errors}});
}

std::optional<std::int64_t> whole_param(const ApiRequest& r, const std::string& name,
                                        std::int64_t min, std::int64_t max) {
  const auto v = number_param(r, name, static_cast<double>(min), static_cast<double>(max));
  if (!v) return std::nullopt;
  if (std::floor(*v) != *v) throw bad_parameter(name, "must be a whole number");
  return static_cast<std::int64_t>(*v);
}

std::optional<std::int64_t> id_param(const ApiRequest& r, const std::string& name) {
  return whole_param(r, name, 0, 9'000'000'000'000'000);
}

std::optional<app::PredictionMethod> method_param(const ApiRequest& r) {
  const auto it = r.query.find("method");
  if (it == r.query.end()) return std::nullopt;
  const auto m = app::prediction_method_from_string(it->second);
  if (!m) throw bad_parameter("method", "must be avk, model or instantaneous");
  return m;
}

CurrentParam current_param(const ApiRequest& r) {
  CurrentParam out;
  const auto it = r.query.find("current");
  if (it == r.query.end()) return out;
  if (it->second == "live") {
    out.live = true;
    return out;
  }
  if (it->second == "none") {
    out.none = true;
    return out;
  }
  const auto comma = it->second.find(',');
  const auto part = [&](std::string_view text) -> std::optional<double> {
    const nlohmann::json v = nlohmann::json::parse(text, nullptr, false);
    if (!v.is_number()) return std::nullopt;
    return v.get<double>();
  };
  if (comma != std::string::npos) {
    const auto east = part(std::string_view(it->second).substr(0, comma));
    const auto north = part(std::string_view(it->second).substr(comma + 1));
    if (east && north) {
      out.current = kinematics::WaterCurrent{*east, *north};
      return out;
    }
  }
  throw bad_parameter("current", "must be live, none or EAST,NORTH in m/s (e.g. 0.1,-0.2)");
}

std::optional<bool> speed_reference_param(const ApiRequest& r) {
  const auto it = r.query.find("speed_reference");
  if (it == r.query.end()) return std::nullopt;
  if (it->second == "over_ground") return true;
  if (it->second == "through_water") return false;
  throw bad_parameter("speed_reference", "must be over_ground or through_water");
}

bool include_harvested_param(const ApiRequest& r) {
  const auto it = r.query.find("include");
  if (it == r.query.end() || it->second == "collection") return false;
  if (it->second == "harvested") return true;
  throw bad_parameter("include", "must be collection or harvested");
}

bool pool_param(const ApiRequest& r) {
  const auto it = r.query.find("pool");
  if (it == r.query.end() || it->second == "vehicle") return false;
  if (it->second == "class") return true;
  throw bad_parameter("pool", "must be vehicle or class");
}

std::int64_t path_id(const PathParams& p, const std::string& key, const std::string& what) {
  const std::string& segment = p.at(key);
  const auto id = record_id(segment);
  if (!id) throw RequestError(404, "no " + what + " '" + segment + "'");
  return *id;
}

namespace {

std::string media_type(const std::string& header) {
  std::string t;
  for (char c : header.substr(0, header.find(';')))
    if (c != ' ') t += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return t;
}

}  // namespace

Format negotiate(const ApiRequest& r, bool csv_available) {
  static const std::vector<Representation> json_only{kJsonRepresentation};
  static const std::vector<Representation> json_csv{kJsonRepresentation, kCsvRepresentation};
  const Representation& chosen = choose_representation(r, csv_available ? json_csv : json_only);
  return chosen.format == "csv" ? Format::csv : Format::json;
}

void require_media_type(const ApiRequest& r, const std::string& type, const std::string& what) {
  if (media_type(r.content_type) != type) throw RequestError(415, what + " (" + type + ")");
}

std::optional<double> BodyNumbers::get(const std::string& name) const {
  const auto it = values.find(name);
  if (it == values.end()) return std::nullopt;
  return it->second;
}

BodyNumbers body_numbers(const ApiRequest& r, const std::vector<std::string>& names,
                         const std::string& what) {
  BodyNumbers out;
  if (r.body.empty()) return out;
  const nlohmann::json body = body_object(r, what);
  for (const auto& [key, value] : body.items()) {
    if (std::find(names.begin(), names.end(), key) == names.end())
      throw bad_field("/" + key, "is not a field of " + what);
    if (value.is_null()) continue;
    if (!value.is_number()) throw bad_field("/" + key, "must be a number");
    out.values[key] = value.get<double>();
  }
  return out;
}

}  // namespace avk::server
