// libFuzzer target for the .alog reader and navigation builder (vehicle/alog.cpp), built by
// tests/CMakeLists.txt. Nothing may throw; every sample is finite and samples never go back in
// time; every line is either read, a header, blank or counted as malformed.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>

#include "vehicle/alog.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace avk::vehicle;
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  // A small line limit so that the oversized-line path is reached with short inputs too.
  AlogReader reader(in, 256);
  AlogNavBuilder builder;
  AlogEntry e;
  GuidedNav s;
  double last_t = -INFINITY;
  const auto check = [&](const GuidedNav& g) {
    if (!std::isfinite(g.nav.t_s) || !std::isfinite(g.nav.x_m) || !std::isfinite(g.nav.y_m) ||
        !std::isfinite(g.nav.heading_deg) || !std::isfinite(g.nav.speed_mps))
      std::abort();
    if (g.nav.t_s < last_t - 1e-3) std::abort();
    last_t = g.nav.t_s;
  };
  while (reader.next(e)) {
    if (!std::isfinite(e.t_s) || e.t_s < 0.0 || e.t_s > 1e15) std::abort();
    if (builder.feed(e, s)) check(s);
  }
  if (builder.finish(s)) check(s);
  const AlogStats& st = reader.stats();
  if (st.entries + st.header_lines + st.blank_lines + st.malformed.count != st.lines) std::abort();
  if (st.malformed.first.size() > kAlogReportedProblems) std::abort();
  return 0;
}
