#pragma once
// A frontseat's navigation as a link that delivers in bursts hands it to the driver: $CPNVG,
// $CPNVR and $GPRMC for each pose (5 Hz on a boat), grouped into reads of 2 to 20 lines, each
// read at once, some of them late. For tests of the driver's stamps (vehicle/m200_session.hpp).

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "kinematics/angles.hpp"
#include "vehicle/local_grid.hpp"
#include "vehicle/nmea.hpp"

namespace avk::testing {

// The frontseat's time of day (UTC) at mission clock 0.
inline constexpr double kFrontseatDay0_s = 43200.0;

struct BoatPose {
  double t_s = 0.0;  // mission clock
  double x_m = 0.0, y_m = 0.0, heading_deg = 0.0, speed_mps = 0.0, yaw_rate_dps = 0.0;
};

struct FrontseatLine {
  double sent_s = 0.0;  // mission clock
  std::string text;
};

// The three navigation sentences of one pose, their time fields day0_s + the pose's time
// (wrapping at midnight, as the formatters write them).
inline std::vector<FrontseatLine> navigation_lines(const BoatPose& p, const vehicle::LatLon& datum,
                                                   double day0_s = kFrontseatDay0_s) {
  const vehicle::LocalGrid grid(datum.lat_deg, datum.lon_deg);
  const vehicle::LatLon ll = grid.to_geodetic(p.x_m, p.y_m);
  const double tod = day0_s + p.t_s;
  const double heading_rad = kinematics::deg_to_rad(p.heading_deg);
  vehicle::Cpnvg nvg;
  nvg.time_s = nvg.nav_time_s = tod;
  nvg.lat_deg = ll.lat_deg;
  nvg.lon_deg = ll.lon_deg;
  nvg.position_ok = true;
  nvg.heading_deg = kinematics::wrap360_deg(p.heading_deg);
  vehicle::Cpnvr nvr;
  nvr.time_s = tod;
  nvr.v_east_mps = p.speed_mps * std::sin(heading_rad);
  nvr.v_north_mps = p.speed_mps * std::cos(heading_rad);
  nvr.yaw_rate_dps = p.yaw_rate_dps;
  vehicle::Gprmc rmc;
  rmc.time_s = tod;
  rmc.valid = true;
  rmc.lat_deg = ll.lat_deg;
  rmc.lon_deg = ll.lon_deg;
  rmc.speed_knots = p.speed_mps / vehicle::kMetresPerSecondPerKnot;
  return {{p.t_s, vehicle::format_cpnvg(nvg)},
          {p.t_s, vehicle::format_cpnvr(nvr)},
          {p.t_s, vehicle::format_gprmc(rmc)}};
}

struct Read {
  double read_s = 0.0;  // when the driver's read returned, on the mission clock
  std::string bytes;
  int lines = 0;
};

// The lines in reads of min_lines to max_lines (drawn uniformly from seed), each read delay_s
// after its last line was sent, plus up to late_s more for a third of them (a loaded reader).
// The first read is never late: the least delay is seen from the start.
inline std::vector<Read> in_bursts(const std::vector<FrontseatLine>& lines, unsigned seed,
                                   double delay_s, double late_s, int min_lines = 2,
                                   int max_lines = 20) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> size(min_lines, max_lines);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Read> out;
  for (std::size_t i = 0; i < lines.size();) {
    Read r;
    const std::size_t n =
        std::min<std::size_t>(static_cast<std::size_t>(size(rng)), lines.size() - i);
    for (std::size_t k = 0; k < n; ++k, ++i) {
      r.bytes += lines[i].text;
      r.read_s = lines[i].sent_s + delay_s;
      ++r.lines;
    }
    if (!out.empty() && unit(rng) < 1.0 / 3.0) r.read_s += late_s * unit(rng);
    // A read cannot return before the one before it.
    if (!out.empty()) r.read_s = std::max(r.read_s, out.back().read_s);
    out.push_back(std::move(r));
  }
  return out;
}

}  // namespace avk::testing
