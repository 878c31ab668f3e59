#include "server/serialize/predictions.hpp"

#include "server/serialize/csv.hpp"
#include "server/serialize/values.hpp"

namespace avk::server {

namespace kin = avk::kinematics;

std::string trajectory_csv(const kin::Polyline& line) {
  std::string csv = "vertex_index,x_m,y_m\n";
  for (std::size_t i = 0; i < line.size(); ++i)
    csv += std::to_string(i) + ',' + num(line[i].x_m) + ',' + num(line[i].y_m) + '\n';
  return csv;
}

}  // namespace avk::server
