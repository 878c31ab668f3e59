#pragma once
// The collision watch: every vehicle of the station's fleet predicted over the next horizon_s
// seconds (a vehicle in a turn along its turn's AVK prediction with its corridor, else straight
// on at its heading and speed), every AIS contact along its course, and an alarm for every pair
// whose predicted closest approach falls below the standoff. A pair's alarm is raised once and
// cleared once the predicted CPA opens past the standoff by a margin, so a pair hovering at the
// standoff does not flood the operator's log.

#include <condition_variable>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "kinematics/timed_path.hpp"

namespace avk::app {

class Context;

struct CollisionWatchOptions {
  double standoff_m = 20.0;  // a predicted CPA below this raises the alarm
  double horizon_s = 60.0;   // how far ahead each party is predicted (station clock)
  double period_s = 1.0;     // how often the watch looks (station clock)
};

// One party of the watch, its predicted path on the station clock.
struct WatchedParty {
  std::string id;    // the vehicle id, or "ais:<MMSI>"
  std::string name;  // how an operator knows it: the vehicle id, the ship's name or MMSI
  bool vehicle = false;
  std::string basis;  // "turn" (its turn's AVK prediction), "course", or "ais"
  kinematics::TimedPath path;
  std::vector<double> half_width_m;  // per path point; empty without a corridor
};

struct WatchPair {
  std::string a, b;  // party ids: a is a vehicle (the first of two vehicles by id)
  std::string a_name, b_name;
  std::string a_basis, b_basis;
  double distance_now_m = 0.0;
  double cpa_m = 0.0;    // between the corridors' nearer edges where a party has one
  double cpa_t_s = 0.0;  // station clock
  bool alarm = false;    // the watch's alarm for the pair is raised
};

// Every pair with a vehicle in it (two vehicles, or a vehicle and an AIS contact; never two
// contacts), nearest predicted CPA first. Parties whose paths do not overlap in time are skipped.
std::vector<WatchPair> watch_pairs(const std::vector<WatchedParty>& parties);

struct CollisionWatchView {
  bool enabled = false;
  CollisionWatchOptions options;
  std::optional<double> t_s;     // the station clock of the last look
  std::vector<WatchPair> pairs;  // of the last look
  std::vector<WatchedParty> parties;
};

class CollisionWatch {
 public:
  // realtime_factor: how much faster than the wall clock the station clock runs.
  CollisionWatch(Context& ctx, CollisionWatchOptions options, double realtime_factor);
  ~CollisionWatch();
  CollisionWatch(const CollisionWatch&) = delete;
  CollisionWatch& operator=(const CollisionWatch&) = delete;

  // Looks every period on a thread of its own until stop().
  void start();
  void stop();
  // One look now, on the caller's thread: predicts every party, raises and clears alarms (told
  // as events through the first vehicle of the pair), keeps the view.
  void check();
  CollisionWatchView view() const;

 private:
  std::vector<WatchedParty> parties(double& now_s);

  Context& ctx_;
  CollisionWatchOptions options_;
  double realtime_factor_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false;
  std::thread thread_;
  CollisionWatchView view_;
  std::map<std::pair<std::string, std::string>, bool> raised_;  // pair -> alarm up
};

// What the station's watch saw last; enabled = false when the station does not watch.
CollisionWatchView collision_watch_view(Context& ctx);

// A party for the vehicle's live state alone: straight on from (x, y) at heading and speed from
// t_s to until_s.
WatchedParty course_party(const std::string& id, const std::string& name, const std::string& basis,
                          double t_s, double x_m, double y_m, double course_deg, double speed_mps,
                          double until_s);

}  // namespace avk::app
