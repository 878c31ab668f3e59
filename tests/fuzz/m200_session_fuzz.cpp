// libFuzzer target for the M200 driver's receive path: arbitrary bytes from the frontseat, in
// reads of 1 to 200 bytes as the transport hands them over (each read's length from its first
// byte), interleaved with controller ticks. Built by CMake when
// clang++ is found (build/tests/m200_session_fuzz); by hand:
//   clang++ -std=c++20 -g -O1 -fsanitize=fuzzer,address,undefined -I. -I/usr/include/eigen3
//     -o m200_session_fuzz tests/fuzz/m200_session_fuzz.cpp vehicle/m200_session.cpp
//     vehicle/nmea.cpp vehicle/sentence_clock.cpp vehicle/local_grid.cpp vehicle/marine_pid.cpp
//     vehicle/thrust_mixing.cpp vehicle/vehicle.cpp kinematics/angles.cpp
// Nothing may throw, and whatever navigation comes out must be finite and on the earth: a
// hostile frontseat must not be able to put the vehicle at NaN or a million km away, nor make
// navigation times repeat or run backwards, whatever times its sentences carry.

#include <algorithm>
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
  for (std::size_t at = 0; at < bytes.size();) {
    const std::size_t n =
        std::min<std::size_t>(bytes.size() - at, 1 + static_cast<unsigned char>(bytes[at]) % 200);
    t += 0.05;
    s.on_received(bytes.substr(at, n), t);
    const std::string out = s.control_tick(t);
    const auto r =
        avk::vehicle::parse_sentence(out, avk::vehicle::NmeaDirection::backseat_to_frontseat);
    if (!r.ok()) std::abort();
    at += n;
  }
  double previous_t = -INFINITY;
  for (const auto& n : s.take_nav()) {
    if (!std::isfinite(n.x_m) || !std::isfinite(n.y_m) || !std::isfinite(n.heading_deg) ||
        !std::isfinite(n.speed_mps) || std::hypot(n.x_m, n.y_m) > 2.1e7 || !(n.t_s > previous_t))
      std::abort();
    previous_t = n.t_s;
  }
  return 0;
}
