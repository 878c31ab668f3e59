#pragma once
// A GpsdAis client that keeps what it receives, for tests: the last report of each (MMSI, message
// type), the link changes, and a wait for a condition on them with a deadline.

#include <chrono>
#include <functional>
#include <map>
#include <mutex>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "vehicle/gpsd_ais.hpp"

namespace avk::testing {

class AisCollector {
 public:
  using Key = std::pair<std::uint32_t, int>;  // MMSI, message type

  explicit AisCollector(const std::string& port)
      : client_(
            options(port),
            [this](const vehicle::AisReport& r) {
              std::lock_guard lock(mutex_);
              reports_[{r.mmsi, r.message_type}] = r;
              all_.push_back(r);
            },
            [this](bool up) {
              std::lock_guard lock(mutex_);
              links_.push_back(up);
            }) {
    client_.start();
  }

  void stop() { client_.stop(); }

  static vehicle::GpsdAisOptions options(const std::string& port) {
    vehicle::GpsdAisOptions o;
    o.host = "127.0.0.1";
    o.port = port;
    o.min_backoff_s = 0.05;  // quick to find gpsfake's gpsd once it listens
    o.max_backoff_s = 0.5;
    return o;
  }

  std::map<Key, vehicle::AisReport> reports() const {
    std::lock_guard lock(mutex_);
    return reports_;
  }
  std::vector<vehicle::AisReport> all() const {
    std::lock_guard lock(mutex_);
    return all_;
  }
  std::vector<bool> links() const {
    std::lock_guard lock(mutex_);
    return links_;
  }

  // Polls until done() holds or the deadline passes; returns whether it held. A generous deadline:
  // gpsfake's gpsd starts slowly on a loaded machine.
  bool wait_for(const std::function<bool(const AisCollector&)>& done,
                std::chrono::seconds deadline = std::chrono::seconds(60)) const {
    const auto end = std::chrono::steady_clock::now() + deadline;
    while (!done(*this)) {
      if (std::chrono::steady_clock::now() > end) return false;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return true;
  }

  bool has_all(const std::set<Key>& keys) const {
    const auto r = reports();
    for (const auto& k : keys)
      if (!r.count(k)) return false;
    return true;
  }

  // The keys received so far, for a failure message.
  std::string received() const {
    std::ostringstream s;
    for (const auto& [k, r] : reports())
      s << k.first << "/" << k.second << " ";
    return s.str();
  }

 private:
  mutable std::mutex mutex_;
  std::map<Key, vehicle::AisReport> reports_;
  std::vector<vehicle::AisReport> all_;
  std::vector<bool> links_;
  vehicle::GpsdAis client_;  // last: stopped first, while the rest is still there
};

}  // namespace avk::testing
