// libFuzzer target for the M200 driver's receive path: arbitrary bytes from the frontseat, cut
// into lines as the transport cuts them, interleaved with controller ticks. Built by CMake when
// clang++ is found (build/tests/m200_session_fuzz); by hand:
//   clang++ -std=c++20 -g -O1 -fsanitize=fuzzer,address,undefined -I. -I/usr/include/eigen3
//     -o m200_session_fuzz tests/fuzz/m200_session_fuzz.cpp vehicle/m200_session.cpp
//     vehicle/nmea.cpp vehicle/local_grid.cpp vehicle/marine_pid.cpp vehicle/thrust_mixing.cpp
//     vehicle/vehicle.cpp kinematics/angles.cpp
// Nothing may throw, and whatever navigation comes out must be finite and on the earth: a
// hostile frontseat must not be able to put the vehicle at NaN or a million km away.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "vehicle/m200_session.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  avk::vehicle::M200Session s{avk::vehicle::M200Config{}};
  s.on_connected(0.0);
  s.command({0.0, 45.0, 1.0});
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  double t = 0.0;
  std::size_t start = 0;
  while (start <= bytes.size()) {
    std::size_t end = bytes.find('\n', start);
    if (end == std::string_view::npos) end = bytes.size();
    t += 0.05;
    s.on_line(bytes.substr(start, end - start), t);
    const std::string out = s.control_tick(t);
    const auto r =
        avk::vehicle::parse_sentence(out, avk::vehicle::NmeaDirection::backseat_to_frontseat);
    if (!r.ok()) std::abort();
    start = end + 1;
  }
  for (const auto& n : s.take_nav()) {
    if (!std::isfinite(n.x_m) || !std::isfinite(n.y_m) || !std::isfinite(n.heading_deg) ||
        !std::isfinite(n.speed_mps) || std::hypot(n.x_m, n.y_m) > 2.1e7)
      std::abort();
  }
  return 0;
}
