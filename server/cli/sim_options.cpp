#include "server/cli/sim_options.hpp"

#include <charconv>
#include <cmath>

#include "server/cli/files.hpp"

namespace avk::server {

namespace {

// --ticks plant=4,controller=4,helm=4
void apply_ticks(const std::string& spec, sim::SimSetup& setup) {
  std::size_t pos = 0;
  while (pos <= spec.size()) {
    std::size_t end = spec.find(',', pos);
    if (end == std::string::npos) end = spec.size();
    const std::string item = spec.substr(pos, end - pos);
    const auto eq = item.find('=');
    if (eq == std::string::npos)
      throw UsageError("--ticks expects name=Hz pairs, got '" + item + "'");
    const std::string name = item.substr(0, eq);
    const std::string value = item.substr(eq + 1);
    double hz = 0.0;
    const auto r = std::from_chars(value.data(), value.data() + value.size(), hz);
    if (r.ec != std::errc() || r.ptr != value.data() + value.size() || !(hz > 0.0) ||
        !std::isfinite(hz)) {
      throw UsageError("--ticks " + name + " needs a positive rate in Hz, got '" + value + "'");
    }
    if (name == "plant") {
      setup.vehicle.plant_hz = hz;
    } else if (name == "controller") {
      setup.vehicle.controller_hz = hz;
    } else if (name == "helm") {
      setup.helm_hz = hz;
    } else {
      throw UsageError("--ticks knows plant, controller and helm, not '" + name + "'");
    }
    pos = end + 1;
  }
}

}  // namespace

sim::SimSetup sim_setup_from(const Args& a, Io& io, const std::string& default_kind) {
  const std::string kind = a.get("vehicle").value_or(default_kind);
  sim::SimSetup setup;
  if (const auto path = a.get("sim-config")) {
    try {
      setup = sim::parse_sim_config(read_file(*path, io.in), kind);
    } catch (const std::exception& e) {
      throw std::runtime_error(*path + ": " + e.what());
    }
  } else {
    try {
      setup = sim::default_sim_setup(kind);
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--vehicle: ") + e.what());
    }
  }
  if (const auto ticks = a.get("ticks")) apply_ticks(*ticks, setup);
  if (const auto seed = a.number("seed")) {
    if (*seed < 0 || std::floor(*seed) != *seed)
      throw UsageError("--seed needs a whole number >= 0");
    setup.scheduler.seed = static_cast<std::uint64_t>(*seed);
  }
  if (a.flag("jitter")) {
    setup.scheduler.random_phases = true;
    if (setup.scheduler.jitter_fraction == 0.0) setup.scheduler.jitter_fraction = 0.05;
  }
  return setup;
}

double realtime_factor_from(const Args& a) {
  const double f = a.number("realtime-factor").value_or(1.0);
  if (!(f > 0.0 && f <= 10000.0)) throw UsageError("--realtime-factor must be in (0, 10000]");
  return f;
}

}  // namespace avk::server
