// .alog import throughput: the reader alone and the reader + navigation builder, in MB/s, on a
// ~50 MB log generated in memory once (outside the timed loop). Logs run to hundreds of MB, so
// this is what decides whether an import takes seconds or minutes.

#include <benchmark/benchmark.h>

#include <charconv>
#include <cmath>
#include <istream>
#include <streambuf>
#include <string>

#include "vehicle/alog.hpp"

namespace {

// Reads a string in place: the timed loop measures parsing, not a copy of 50 MB.
class MemoryBuf : public std::streambuf {
 public:
  explicit MemoryBuf(const std::string& s) {
    char* p = const_cast<char*>(s.data());
    setg(p, p, p + s.size());
  }
};

void append_num(std::string& out, double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, 3);
  out.append(buf, r.ptr);
}

void post(std::string& out, double t, const char* var, const char* src, double v) {
  append_num(out, t);
  out += "   ";
  out += var;
  out += "   ";
  out += src;
  out += "   ";
  append_num(out, v);
  out += '\n';
}

// A pLogger log of a vehicle reporting navigation at 10 Hz, a helm posting guidance, and the
// chatter of other processes (string values with spaces), until it reaches the size.
const std::string& log_text() {
  static const std::string text = [] {
    constexpr std::size_t kBytes = std::size_t{50} << 20;
    std::string out;
    out.reserve(kBytes + 4096);
    out += "%% LOGFILE: bench.alog\n%% FILE OPENED ON Wed Jun 12 10:21:07 2013\n";
    double x = 0.0, y = 0.0, heading = 0.0;
    for (long i = 0; out.size() < kBytes; ++i) {
      const double t = static_cast<double>(i) * 0.1;
      heading = std::fmod(heading + 0.7, 360.0);
      x += 0.15 * std::sin(heading * 0.0174533);
      y += 0.15 * std::cos(heading * 0.0174533);
      post(out, t, "NAV_X", "uSimMarine", x);
      post(out, t, "NAV_Y", "uSimMarine", y);
      post(out, t, "NAV_HEADING", "uSimMarine", heading);
      post(out, t, "NAV_SPEED", "uSimMarine", 1.5);
      if (i % 4 == 0) {
        post(out, t + 0.02, "DESIRED_HEADING", "pHelmIvP", std::floor(heading / 10.0) * 10.0);
        post(out, t + 0.02, "DESIRED_SPEED", "pHelmIvP", 1.5);
      }
      if (i % 10 == 0) {
        append_num(out, t + 0.05);
        out += "   IVPHELM_SUMMARY   pHelmIvP   iter=";
        out += std::to_string(i);
        out += ",ofnum=1,warnings=0,time=0.01, solve_time=0.00,active_bhvs=constant_heading\n";
      }
    }
    return out;
  }();
  return text;
}

void BM_AlogReader(benchmark::State& state) {
  const std::string& text = log_text();
  std::size_t entries = 0;
  for (auto _ : state) {
    MemoryBuf buf(text);
    std::istream in(&buf);
    avk::vehicle::AlogReader reader(in);
    avk::vehicle::AlogEntry e;
    while (reader.next(e))
      benchmark::DoNotOptimize(e.t_s);
    entries = reader.stats().entries;
  }
  state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(text.size()));
  state.counters["entries"] = static_cast<double>(entries);
  state.counters["MB"] = static_cast<double>(text.size()) / 1e6;
}
BENCHMARK(BM_AlogReader)->Unit(benchmark::kMillisecond);

void BM_AlogReaderAndNavBuilder(benchmark::State& state) {
  const std::string& text = log_text();
  std::size_t samples = 0;
  for (auto _ : state) {
    MemoryBuf buf(text);
    std::istream in(&buf);
    avk::vehicle::AlogReader reader(in);
    avk::vehicle::AlogNavBuilder builder;
    avk::vehicle::AlogEntry e;
    avk::vehicle::GuidedNav g;
    samples = 0;
    while (reader.next(e)) {
      if (builder.feed(e, g)) {
        ++samples;
        benchmark::DoNotOptimize(g.nav.x_m);
      }
    }
    if (builder.finish(g)) ++samples;
  }
  state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(text.size()));
  state.counters["samples"] = static_cast<double>(samples);
}
BENCHMARK(BM_AlogReaderAndNavBuilder)->Unit(benchmark::kMillisecond);

}  // namespace
