#include "server/serialize/values.hpp"

#include <stdexcept>

#include "kinematics/number_text.hpp"

namespace avk::server {

using nlohmann::json;
namespace kin = avk::kinematics;

std::string num(double v) {
  return kin::number_text(v);
}

std::string fixed(double v, int decimals) {
  return kin::fixed_text(v, decimals);
}

std::optional<std::int64_t> record_id(const std::string& text) {
  std::size_t used = 0;
  long long id = 0;
  try {
    id = std::stoll(text, &used);
  } catch (const std::exception&) {
    return std::nullopt;
  }
  if (used == 0 || used != text.size() || id <= 0) return std::nullopt;
  return static_cast<std::int64_t>(id);
}

json optional_json(const std::optional<double>& v) {
  return v ? json(*v) : json();
}

json optional_json(const std::optional<std::int64_t>& v) {
  return v ? json(*v) : json();
}

json mean_sd_json(const std::optional<kin::MeanSd>& v) {
  return v ? json{{"mean", v->mean}, {"sd", v->sd}} : json();
}

json points_json(const kin::Polyline& line) {
  json a = json::array();
  for (const auto& p : line)
    a.push_back({p.x_m, p.y_m});
  return a;
}

std::string describe_value(const json& v) {
  // Dumping a container whole would grow the message with the input, and recurse as deep as it
  // nests.
  if (v.is_structured()) return std::string("an ") + v.type_name();
  std::string text = v.dump(-1, ' ', false, json::error_handler_t::replace);
  constexpr std::size_t kMax = 40;
  if (text.size() > kMax) text = text.substr(0, kMax) + "...";
  return text;
}

}  // namespace avk::server
