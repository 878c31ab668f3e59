#include "kinematics/yaw_model_json.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

#include "kinematics/json_parse.hpp"
#include "kinematics/parse_error.hpp"

namespace avk::kinematics {

using nlohmann::json;

std::string yaw_model_to_json(const YawModel& m) {
  json j = {{"form", to_string(m.form)},
            {"history", m.history},
            {"rate_hz", m.rate_hz},
            {"error_coeffs", m.error_coeffs},
            {"heading_coeffs", m.heading_coeffs},
            {"ridge_lambda", m.ridge_lambda},
            {"refined", m.refined}};
  if (m.speed) {
    j["speed_model"] = {{"gain", m.speed->gain},
                        {"sag_per_deg", m.speed->sag_per_deg},
                        {"bias_mps", m.speed->bias_mps}};
  }
  return j.dump();
}

namespace {

const json& field(const json& j, const char* key, const std::string& path) {
  const auto it = j.find(key);
  if (it == j.end()) throw ParseError(path + "/" + key, 0, "missing field");
  return *it;
}

double number(const json& j, const char* key, const std::string& path) {
  const json& v = field(j, key, path);
  if (!v.is_number() || !std::isfinite(v.get<double>()))
    throw ParseError(path + "/" + key, 0, "expected a finite number");
  return v.get<double>();
}

std::vector<double> numbers(const json& j, const char* key) {
  const json& v = field(j, key, "");
  if (!v.is_array()) throw ParseError(std::string("/") + key, 0, "expected an array of numbers");
  std::vector<double> out;
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (!v[i].is_number() || !std::isfinite(v[i].get<double>()))
      throw ParseError("/" + std::string(key) + "/" + std::to_string(i), 0,
                       "expected a finite number");
    out.push_back(v[i].get<double>());
  }
  return out;
}

}  // namespace

YawModel parse_yaw_model_json(std::string_view text) {
  json j;
  try {
    j = parse_json_bounded(text);
  } catch (const JsonSyntaxError& e) {
    if (e.number_out_of_range()) throw ParseError(e.pointer(), e.position(), e.reason());
    throw;
  }
  if (!j.is_object()) throw ParseError("/", 0, "expected an object");
  YawModel m;
  const json& form = field(j, "form", "");
  const auto f =
      form.is_string() ? yaw_model_form_from_string(form.get<std::string>()) : std::nullopt;
  if (!f) throw ParseError("/form", 0, "must be 'thesis' or 'invariant'");
  m.form = *f;
  const double history = number(j, "history", "");
  if (history < 1 || history > 10000 || std::floor(history) != history)
    throw ParseError("/history", 0, "must be a whole number of samples from 1 to 10000");
  m.history = static_cast<std::size_t>(history);
  m.rate_hz = number(j, "rate_hz", "");
  if (!(m.rate_hz > 0.0)) throw ParseError("/rate_hz", 0, "must be positive");
  m.error_coeffs = numbers(j, "error_coeffs");
  m.heading_coeffs = numbers(j, "heading_coeffs");
  if (m.error_coeffs.size() != m.history || m.heading_coeffs.size() != m.history)
    throw ParseError("/error_coeffs", 0, "needs one coefficient per history sample");
  m.ridge_lambda = number(j, "ridge_lambda", "");
  const json& refined = field(j, "refined", "");
  if (!refined.is_boolean()) throw ParseError("/refined", 0, "expected true or false");
  m.refined = refined.get<bool>();
  if (const auto it = j.find("speed_model"); it != j.end()) {
    if (!it->is_object()) throw ParseError("/speed_model", 0, "expected an object");
    m.speed =
        SpeedModel{number(*it, "gain", "/speed_model"), number(*it, "sag_per_deg", "/speed_model"),
                   number(*it, "bias_mps", "/speed_model")};
  }
  return m;
}

}  // namespace avk::kinematics
