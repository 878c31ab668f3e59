// A real Kingfisher M200 over its frontseat link as a vehicle source.

#include <sstream>
#include <stdexcept>

#include "app/vehicle_source_maker.hpp"
#include "vehicle/m200_session.hpp"

namespace avk::app {

namespace {

// Paces a scheduler to the vehicle's clock, so helm ticks and navigation share one time.
class ClockPacer final : public sim::Pacer {
 public:
  explicit ClockPacer(const vehicle::ScaledClock& clock) : clock_(clock) {}
  void wait_until(double t_s) override { clock_.sleep_until(t_s); }

 private:
  const vehicle::ScaledClock& clock_;
};

class M200Source final : public VehicleSource {
 public:
  explicit M200Source(const VehicleSourceOptions& o)
      : options_(*o.m200), clock_(o.realtime_factor, o.start_clock_s), m200_(options_, clock_) {}

  vehicle::Vehicle& vehicle() override { return m200_; }
  std::unique_ptr<sim::Pacer> pacer() override { return std::make_unique<ClockPacer>(clock_); }
  const vehicle::ScaledClock* wall_clock() const override { return &clock_; }
  std::optional<vehicle::M200Status> frontseat_status() const override { return m200_.status(); }

  std::string link_name() const override {
    return "the M200 frontseat at " + options_.endpoint.host + ":" +
           std::to_string(options_.endpoint.port);
  }

  std::optional<std::string> wait_for_nav(std::chrono::milliseconds timeout) override {
    if (m200_.wait_for_nav(timeout)) return std::nullopt;
    const auto st = m200_.status();
    const auto& e = options_.endpoint;
    return "no navigation from the M200 at " + e.host + ":" + std::to_string(e.port) + " within " +
           std::to_string(timeout.count() / 1000) + " s" +
           (st.last_link_error.empty() ? std::string(" (connected, but no $CPNVG with a position)")
                                       : " (" + st.last_link_error + ")");
  }

  void park() override {
    // Three controller periods: the frontseat acts on the all stop before the link closes.
    m200_.all_stop(clock_.now_s());
    clock_.sleep_until(clock_.now_s() + 3.0 / options_.config.controller_hz);
    m200_.stop();
  }

  std::string link_report() const override {
    const auto st = m200_.status();
    const auto& c = st.counters;
    std::ostringstream out;
    out << "M200 link: " << c.sentences << " sentences, " << c.errors << " bad lines";
    for (const auto& [code, n] : c.errors_by_code)
      out << (code == c.errors_by_code.begin()->first ? " (" : ", ") << code << " " << n;
    if (!c.errors_by_code.empty()) out << ")";
    out << ", " << c.nav_samples << " nav samples, " << c.pydir_sent << " $PYDIR sent, "
        << c.failsafe_stops << " failsafe stops, " << c.disconnects << " disconnects";
    if (st.battery) {
      out.setf(std::ios::fixed);
      out.precision(2);
      out << ", battery " << st.battery->stack_v << " V";
    }
    return out.str();
  }

 private:
  vehicle::M200Options options_;
  vehicle::ScaledClock clock_;
  vehicle::M200 m200_;
};

vehicle::VehicleInfo planned_info(const VehicleSourceOptions& o) {
  if (!o.m200) throw std::invalid_argument("an M200 needs its frontseat link (host and port)");
  return vehicle::m200_info(o.m200->config);
}

std::unique_ptr<VehicleSource> make(const VehicleSourceOptions& o, sim::Scheduler&) {
  if (!o.m200) throw std::invalid_argument("an M200 needs its frontseat link (host and port)");
  return std::make_unique<M200Source>(o);
}

}  // namespace

VehicleSourceMaker m200_vehicle_source() {
  return {planned_info, make};
}

}  // namespace avk::app
