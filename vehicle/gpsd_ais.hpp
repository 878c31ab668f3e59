#pragma once
// AIS traffic from gpsd: a client of gpsd's socket (libgps) that watches its JSON stream and hands
// every AIS report it decodes (docs/ais.md) to a callback, on a thread of its own. gpsd does the
// AIVDM work (fragment reassembly, six-bit decoding, Class B part A/B pairing); this client turns
// its fields into AisReport's units. When gpsd is not there, or goes away, the client reconnects
// with a backoff that doubles from min_backoff_s up to max_backoff_s and reports the link.
// libgps's header stays in the .cpp.

#include <atomic>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

#include "vehicle/ais_report.hpp"

namespace avk::vehicle {

struct GpsdAisOptions {
  std::string host = "127.0.0.1";
  std::string port = "2947";  // gpsd's registered port
  double min_backoff_s = 0.5;
  double max_backoff_s = 10.0;
  // Stamps AisReport::received_s; the default is the system clock, seconds since the epoch.
  std::function<double()> clock;
};

class GpsdAis {
 public:
  using ReportHandler = std::function<void(const AisReport&)>;
  using LinkHandler = std::function<void(bool up)>;

  // Both handlers run on the client's thread; they must not call stop().
  GpsdAis(GpsdAisOptions options, ReportHandler on_report, LinkHandler on_link = {});
  ~GpsdAis();
  GpsdAis(const GpsdAis&) = delete;
  GpsdAis& operator=(const GpsdAis&) = delete;

  void start();
  // Closes the connection and joins the thread, within about a quarter second (longer only while
  // a connect to an unresponsive remote host is pending). Idempotent.
  void stop();

 private:
  void run();
  // Waits up to seconds unless stop() is called; false when it was.
  bool pause(double seconds);

  GpsdAisOptions options_;
  ReportHandler on_report_;
  LinkHandler on_link_;
  std::thread thread_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::atomic<bool> stopping_{false};
};

}  // namespace avk::vehicle
