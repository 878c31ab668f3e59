// Frontseat protocol parse throughput, in sentences/s: the 5 Hz navigation stream an M200 sends
// (CPNVG, GPRMC, CPNVR in equal parts), as lines written by the formatters from a simulated
// track once, outside the timed loop. The driver parses on its network thread, so this is the
// budget it has per sentence.

#include <benchmark/benchmark.h>

#include <cmath>
#include <string>
#include <vector>

#include "vehicle/m200_session.hpp"
#include "vehicle/nmea.hpp"

namespace {

using namespace avk::vehicle;

constexpr int kSamples = 1000;

// A boat circling off the MIT Sailing Pavilion at about 1.5 m/s.
const std::vector<std::string>& lines(int kinds) {
  static std::vector<std::string> out[4];
  std::vector<std::string>& v = out[kinds];
  if (!v.empty()) return v;
  for (int i = 0; i < kSamples; ++i) {
    const double t = 43200.0 + i * 0.2;
    const double heading = std::fmod(i * 1.7, 360.0);
    const double lat = 42.3584 + 1e-4 * std::sin(i * 0.01);
    const double lon = -71.0876 + 1e-4 * std::cos(i * 0.01);
    if (kinds == 0 || kinds == 1) {
      Cpnvg g{t, lat, lon, true, std::nullopt, std::nullopt, heading, 1.25, -0.5, t - 0.03};
      v.push_back(format_cpnvg(g));
    }
    if (kinds == 0 || kinds == 2) {
      Gprmc m;
      m.time_s = t;
      m.valid = true;
      m.lat_deg = lat;
      m.lon_deg = lon;
      m.speed_knots = 2.9;
      m.course_deg = heading;
      m.date = NmeaDate{2013, 6, 12};
      m.mode = 'D';
      v.push_back(format_gprmc(m));
    }
    if (kinds == 0 || kinds == 3) {
      const double rad = heading * 3.14159265358979 / 180.0;
      v.push_back(format_cpnvr(
          Cpnvr{t, 1.5 * std::sin(rad), 1.5 * std::cos(rad), 0.0, 0.1, -0.2, 1.7 * 5.0}));
    }
  }
  return v;
}

void parse_lines(benchmark::State& state, int kinds) {
  const std::vector<std::string>& v = lines(kinds);
  std::size_t bytes = 0;
  for (const std::string& s : v)
    bytes += s.size();
  for (auto _ : state) {
    for (const std::string& s : v) {
      NmeaParseResult r = parse_sentence(s, NmeaDirection::frontseat_to_backseat);
      benchmark::DoNotOptimize(r);
    }
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * v.size()));
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * bytes));
}

void BM_ParseNavigationMix(benchmark::State& state) {
  parse_lines(state, 0);
}
BENCHMARK(BM_ParseNavigationMix);

void BM_ParseCpnvg(benchmark::State& state) {
  parse_lines(state, 1);
}
BENCHMARK(BM_ParseCpnvg);

void BM_ParseGprmc(benchmark::State& state) {
  parse_lines(state, 2);
}
BENCHMARK(BM_ParseGprmc);

void BM_ParseCpnvr(benchmark::State& state) {
  parse_lines(state, 3);
}
BENCHMARK(BM_ParseCpnvr);

// What the backseat sends at 10 Hz: formatting includes the read-back check.
void BM_FormatPydir(benchmark::State& state) {
  int i = 0;
  for (auto _ : state) {
    const double left = -100.0 + std::fmod(++i * 0.37, 200.0);
    std::string s = format_pydir(left, -left);
    benchmark::DoNotOptimize(s);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_FormatPydir);

// The M200 driver's whole receive path per line (parse, local grid, navigation sample) and one
// controller tick (PID, mixing, $PYDIR) per CPNVG: the driver's budget on its network thread.
void BM_M200SessionReceive(benchmark::State& state) {
  const std::vector<std::string>& v = lines(0);
  M200Session session{M200Config{}};
  session.on_connected(0.0);
  double t = 0.0;
  for (auto _ : state) {
    for (const std::string& s : v) {
      t += 0.0667;
      session.on_line(s, t);
      if (s[3] == 'N' && s[4] == 'V' && s[5] == 'G') {
        session.command({t, 90.0, 1.0});
        std::string out = session.control_tick(t);
        benchmark::DoNotOptimize(out);
      }
    }
    benchmark::DoNotOptimize(session.take_nav());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * v.size()));
}
BENCHMARK(BM_M200SessionReceive);

}  // namespace
