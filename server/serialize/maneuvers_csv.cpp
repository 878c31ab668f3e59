#include "server/serialize/maneuvers.hpp"

#include "server/serialize/values.hpp"

namespace avk::server {

std::string timed_path_csv(const kinematics::TimedPath& path, double step_s) {
  std::string csv = "t_s,x_m,y_m\n";
  for (const std::size_t i : thinned_indices(path, step_s))
    csv += num(path[i].t_s) + ',' + num(path[i].x_m) + ',' + num(path[i].y_m) + '\n';
  return csv;
}

}  // namespace avk::server
