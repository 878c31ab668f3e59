#include "server/serialize/csv.hpp"

#include "server/serialize/values.hpp"

namespace avk::server {

std::string csv_cell(const std::string& s) {
  if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) {
    if (c == '"') q += '"';
    q += c;
  }
  return q + "\"";
}

std::string optional_csv(const std::optional<double>& v) {
  return v ? num(*v) : std::string();
}

std::string mean_csv(const std::optional<kinematics::MeanSd>& v) {
  return v ? num(v->mean) : std::string();
}

std::string sd_csv(const std::optional<kinematics::MeanSd>& v) {
  return v ? num(v->sd) : std::string();
}

}  // namespace avk::server
