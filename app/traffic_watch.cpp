#include "app/traffic_watch.hpp"

#include <chrono>
#include <utility>

#include "app/context.hpp"

namespace avk::app {

namespace {

// The reports' clock and the table's must be one: an age is the difference of the two.
std::function<double()> report_clock(const vehicle::GpsdAisOptions& gpsd) {
  if (gpsd.clock) return gpsd.clock;
  return [] {
    return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch())
        .count();
  };
}

vehicle::GpsdAisOptions with_clock(vehicle::GpsdAisOptions gpsd, std::function<double()> clock) {
  gpsd.clock = std::move(clock);
  return gpsd;
}

}  // namespace

TrafficWatch::TrafficWatch(TrafficOptions options)
    : source_("gpsd " + options.gpsd.host + ":" + options.gpsd.port),
      now_s_(report_clock(options.gpsd)),
      contacts_(options.datum, now_s_, options.ages),
      client_(
          with_clock(options.gpsd, now_s_),
          [this](const vehicle::AisReport& r) { contacts_.update(r); },
          [this](bool up) { link_up_ = up; }) {}

TrafficWatch::~TrafficWatch() {
  stop();
}

void TrafficWatch::start() {
  client_.start();
}

void TrafficWatch::stop() {
  client_.stop();
}

TrafficView TrafficWatch::view() const {
  TrafficView v;
  v.watching = true;
  v.source = source_;
  v.link_up = link_up_;
  v.contacts = contacts_.snapshot();
  return v;
}

TrafficView traffic(Context& ctx) {
  if (const TrafficWatch* w = ctx.traffic()) return w->view();
  return {};
}

}  // namespace avk::app
