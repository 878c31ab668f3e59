// The collision watch: which pairs it watches and their predicted CPA (pure), and on a fleet of
// two simulated vehicles (400x the wall clock) sent toward each other, the alarm raised while
// they are still apart, before their closest approach; none for two that pass wide. Every wait
// is for a state, bounded at 60 s; nothing measures time.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <map>
#include <mutex>
#include <optional>
#include <thread>

#include "app/collision_watch.hpp"
#include "app/context.hpp"
#include "app/vehicle_commands.hpp"
#include "support/sim_vehicle_loop.hpp"
#include "support/temp_db.hpp"

namespace {

using namespace avk;

app::WatchedParty party(const std::string& id, bool vehicle, double x, double y, double course,
                        double speed) {
  auto p = app::course_party(id, id, vehicle ? "course" : "ais", 0.0, x, y, course, speed, 60.0);
  p.vehicle = vehicle;
  return p;
}

TEST(CollisionWatchPairs, WatchesEveryPairWithAVehicleNearestFirst) {
  const std::vector<app::WatchedParty> parties = {
      party("bravo", true, 100, 0, 270, 1.0),    // toward alpha: meets it
      party("alpha", true, 0, 0, 90, 1.0),       //
      party("ais:1", false, 0, 200, 90, 2.0),    // far north, parallel
      party("ais:2", false, 50, -300, 0, 1.0)};  // crosses ahead of both at a distance
  const auto pairs = app::watch_pairs(parties);
  ASSERT_EQ(pairs.size(), 5u);  // alpha-bravo, and each vehicle with each contact; not ais-ais
  for (const auto& p : pairs) {
    EXPECT_TRUE(p.a == "alpha" || p.a == "bravo") << p.a;  // a vehicle first
    EXPECT_FALSE(p.b.starts_with("ais:") && p.a.starts_with("ais:"));
  }
  EXPECT_EQ(pairs.front().a, "alpha");  // two vehicles: the first by id
  EXPECT_EQ(pairs.front().b, "bravo");
  EXPECT_NEAR(pairs.front().cpa_m, 0.0, 1e-9);
  EXPECT_NEAR(pairs.front().cpa_t_s, 50.0, 1e-9);
  EXPECT_NEAR(pairs.front().distance_now_m, 100.0, 1e-9);
  for (std::size_t i = 1; i < pairs.size(); ++i)
    EXPECT_LE(pairs[i - 1].cpa_m, pairs[i].cpa_m);
}

TEST(CollisionWatchPairs, PartiesThatDoNotOverlapInTimeAreSkipped) {
  auto late = party("bravo", true, 0, 0, 0, 1.0);
  for (auto& pt : late.path)
    pt.t_s += 1000.0;
  const auto pairs = app::watch_pairs({party("alpha", true, 0, 0, 0, 1.0), late});
  EXPECT_TRUE(pairs.empty());
}

// Every vehicle's telemetry and every station event, shared by the fleet's feeds.
class FleetLog {
 public:
  class Feed final : public app::LiveFeed {
   public:
    Feed(FleetLog& log, std::string id) : log_(log), id_(std::move(id)) {}
    void telemetry(const app::VehicleSnapshot& s) override {
      if (s.nav) log_.nav(id_, *s.nav);
    }
    void station_event(double t_s, mission::EventKind kind, const std::string& message) override {
      log_.event(id_, t_s, kind, message);
    }
    std::unique_ptr<mission::MissionObserver> follow(std::int64_t,
                                                     const mission::MissionRunner&) override {
      return std::make_unique<mission::MissionObserver>();
    }

   private:
    FleetLog& log_;
    std::string id_;
  };

  struct Alarm {
    double t_s;
    double distance_m;  // between the two vehicles' last reports when it was raised
    std::string message;
  };

  void nav(const std::string& id, const vehicle::NavSample& n) {
    std::lock_guard lock(mutex_);
    last_[id] = n;
    if (last_.size() == 2) {
      const auto& a = last_.begin()->second;
      const auto& b = std::next(last_.begin())->second;
      const double d = std::hypot(a.x_m - b.x_m, a.y_m - b.y_m);
      if (!closest_ || d < *closest_) closest_ = d;
    }
  }
  void event(const std::string&, double t_s, mission::EventKind kind, const std::string& message) {
    std::lock_guard lock(mutex_);
    if (kind != mission::EventKind::collision_watch) return;
    double d = -1.0;
    if (last_.size() == 2) {
      const auto& a = last_.begin()->second;
      const auto& b = std::next(last_.begin())->second;
      d = std::hypot(a.x_m - b.x_m, a.y_m - b.y_m);
    }
    alarms_.push_back({t_s, d, message});
  }
  std::vector<Alarm> alarms() const {
    std::lock_guard lock(mutex_);
    return alarms_;
  }
  std::optional<vehicle::NavSample> last(const std::string& id) const {
    std::lock_guard lock(mutex_);
    const auto it = last_.find(id);
    return it == last_.end() ? std::nullopt : std::optional(it->second);
  }
  std::optional<double> closest() const {
    std::lock_guard lock(mutex_);
    return closest_;
  }

 private:
  mutable std::mutex mutex_;
  std::map<std::string, vehicle::NavSample> last_;
  std::optional<double> closest_;
  std::vector<Alarm> alarms_;
};

constexpr double kStandoffM = 20.0;

class CollisionWatchFleet : public ::testing::Test {
 protected:
  // alpha at (0, 0) facing east; bravo at (400, bravo_y) facing west.
  void start(double bravo_y) {
    std::vector<app::FleetVehicle> fleet;
    fleet.push_back({vehicle("alpha", {0.0, 0.0, 90.0}), &alpha_feed_});
    fleet.push_back({vehicle("bravo", {400.0, bravo_y, 270.0}), &bravo_feed_});
    ctx_.emplace(db_.path(), std::move(fleet));
    app::CollisionWatchOptions o;
    o.standoff_m = kStandoffM;
    o.horizon_s = 60.0;
    ctx_->watch_collisions(o);
    ctx_->start();
  }
  static app::VehicleLoopOptions vehicle(const std::string& id, kinematics::Pose start) {
    auto v = avk::testing::sim_usim_loop_options(400.0);
    v.setup.vehicle.id = id;
    v.start = start;
    return v;
  }
  void go_to(const std::string& id, double x, double y) {
    app::VehicleCommandRequest r;
    r.kind = mission::VehicleCommandKind::go_to;
    r.x_m = x;
    r.y_m = y;
    r.speed_mps = 1.0;
    ASSERT_TRUE(app::command_vehicle(*ctx_, id, r).ok());
  }
  template <class Done>
  bool wait_for(Done done) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (!done()) {
      if (std::chrono::steady_clock::now() > deadline) return false;
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return true;
  }

  avk::testing::TempDb db_;
  FleetLog log_;
  FleetLog::Feed alpha_feed_{log_, "alpha"};
  FleetLog::Feed bravo_feed_{log_, "bravo"};
  std::optional<app::Context> ctx_;
};

TEST_F(CollisionWatchFleet, VehiclesSentTowardEachOtherRaiseTheAlarmBeforeTheirCpa) {
  start(0.0);
  ASSERT_TRUE(wait_for([&] { return log_.last("alpha") && log_.last("bravo"); }));
  go_to("alpha", 400.0, 0.0);
  go_to("bravo", 0.0, 0.0);
  ASSERT_TRUE(wait_for([&] { return !log_.alarms().empty(); }))
      << "no alarm; closest " << log_.closest().value_or(-1);
  const auto alarm = log_.alarms().front();
  // Raised while the two were still well apart: before the standoff was crossed, let alone the
  // CPA.
  EXPECT_GT(alarm.distance_m, 2.0 * kStandoffM) << alarm.message;
  EXPECT_NE(alarm.message.find("alpha and bravo"), std::string::npos) << alarm.message;
  const auto view = ctx_->collision_watch()->view();
  ASSERT_FALSE(view.pairs.empty());
  EXPECT_EQ(view.pairs.front().a, "alpha");
  EXPECT_TRUE(view.pairs.front().alarm);
}

TEST_F(CollisionWatchFleet, VehiclesThatPassWideRaiseNoAlarm) {
  start(100.0);  // bravo's track is 100 m north of alpha's
  ASSERT_TRUE(wait_for([&] { return log_.last("alpha") && log_.last("bravo"); }));
  go_to("alpha", 400.0, 0.0);
  go_to("bravo", 0.0, 100.0);
  // Until they have passed each other and opened to 150 m again.
  ASSERT_TRUE(wait_for([&] {
    const auto a = log_.last("alpha");
    const auto b = log_.last("bravo");
    return a && b && a->x_m > b->x_m + 110.0;
  }));
  EXPECT_TRUE(log_.alarms().empty()) << log_.alarms().front().message;
  ASSERT_TRUE(log_.closest().has_value());
  EXPECT_GT(*log_.closest(), 80.0);  // they did pass wide
  const auto view = ctx_->collision_watch()->view();
  ASSERT_FALSE(view.pairs.empty());
  EXPECT_FALSE(view.pairs.front().alarm);
}

}  // namespace
