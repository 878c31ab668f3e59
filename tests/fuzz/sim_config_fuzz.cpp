// libFuzzer target for the simulator configuration reader (parse_sim_config), built by
// tests/CMakeLists.txt. Only kinematics::ParseError may leave it, naming a field.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "kinematics/parse_error.hpp"
#include "sim/sim_config.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  try {
    const avk::sim::SimSetup s = avk::sim::parse_sim_config(input, "usim");
    if (!std::isfinite(s.helm_hz) || !(s.helm_hz > 0.0)) std::abort();
  } catch (const avk::kinematics::ParseError& e) {
    if (e.field().empty()) std::abort();
  }
  return 0;
}
