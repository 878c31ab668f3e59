#include <gtest/gtest.h>

#include <chrono>

#include "sim/scheduler.hpp"

using namespace avk::sim;

TEST(Scheduler, RatesAndPhasesAndOrder) {
  Scheduler s;
  std::vector<std::pair<std::string, double>> log;
  s.add("plant", 4.0, [&](double t) { log.push_back({"plant", t}); });
  s.add("pid", 4.0, [&](double t) { log.push_back({"pid", t}); });
  s.add(
      "helm", 2.0,
      [&](double t) {
        log.push_back({"helm", t});
      },
      0.1);
  EXPECT_TRUE(s.run_until(1.0));
  // plant and pid at 0, .25, .5, .75, 1.0; helm at .1, .6
  ASSERT_EQ(log.size(), 12u);
  EXPECT_EQ(log[0], (std::pair<std::string, double>{"plant", 0.0}));
  EXPECT_EQ(log[1], (std::pair<std::string, double>{"pid", 0.0}));  // same instant: added order
  EXPECT_EQ(log[2], (std::pair<std::string, double>{"helm", 0.1}));
  EXPECT_EQ(log[3], (std::pair<std::string, double>{"plant", 0.25}));
  EXPECT_EQ(log.back(), (std::pair<std::string, double>{"pid", 1.0}));
  EXPECT_DOUBLE_EQ(s.now_s(), 1.0);
  EXPECT_EQ(s.ticks_run(), 12u);
}

TEST(Scheduler, NoDriftOverALongRun) {
  Scheduler s;
  double last = -1.0;
  std::uint64_t n = 0;
  s.add("x", 10.0, [&](double t) {
    last = t;
    ++n;
  });
  s.run_until(3600.0);
  EXPECT_EQ(n, 36001u);
  EXPECT_DOUBLE_EQ(last, 3600.0);
}

TEST(Scheduler, StopFromInsideATick) {
  Scheduler s;
  int n = 0;
  s.add("x", 1.0, [&](double) {
    if (++n == 3) s.request_stop();
  });
  EXPECT_FALSE(s.run_until(100.0));
  EXPECT_DOUBLE_EQ(s.now_s(), 2.0);
  EXPECT_TRUE(s.run_until(4.0));  // continues where it stopped
  EXPECT_EQ(n, 5);
}

TEST(Scheduler, JitterIsSeededAndBounded) {
  auto times = [](std::uint64_t seed) {
    Scheduler s({seed, 0.5, false});
    std::vector<double> t;
    s.add("x", 4.0, [&](double now) { t.push_back(now); });
    s.run_until(10.0);
    return t;
  };
  const auto a = times(7), b = times(7), c = times(8);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_GE(a[k], k * 0.25);
    EXPECT_LT(a[k], k * 0.25 + 0.125);
  }
}

TEST(Scheduler, RejectsBadRates) {
  Scheduler s;
  EXPECT_THROW(s.add("x", 0.0, [](double) {}), std::invalid_argument);
  EXPECT_THROW(s.add("x", -1.0, [](double) {}), std::invalid_argument);
  EXPECT_THROW(Scheduler({1, 1.5, false}), std::invalid_argument);
}

// Real time through the same loop: 0.5 simulated seconds at 5x take about 0.1 s of wall time.
TEST(Scheduler, RealtimePacerFollowsTheWallClock) {
  Scheduler s;
  int n = 0;
  s.add("x", 20.0, [&](double) { ++n; });
  RealtimePacer pacer(5.0);
  const auto start = std::chrono::steady_clock::now();
  s.run_until(0.5, pacer);
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(n, 11);
  EXPECT_GE(wall, 0.099);  // a lower bound only: the pacer must not run ahead of the clock
}
