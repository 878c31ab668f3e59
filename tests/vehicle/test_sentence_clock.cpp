// SentenceClock: a frontseat's time of day onto the mission clock, by the least transport delay
// over a sliding window; drift followed, flukes forgotten, garbage refused, midnight crossed.
#include <gtest/gtest.h>

#include <stdexcept>

#include "vehicle/sentence_clock.hpp"

namespace {

using avk::vehicle::SentenceClock;
using avk::vehicle::SentenceClockConfig;

constexpr double kNoon = 43200.0;

TEST(SentenceClock, TheLeastDelayMapsEveryTime) {
  SentenceClock c;
  EXPECT_DOUBLE_EQ(c.map(kNoon, 5.0), 5.0);  // nothing seen yet: the read's own time
  // Sent at 0, 0.2, 0.4; read at 0.3, 0.45 and 0.5 (delays 0.3, 0.25, 0.1).
  ASSERT_TRUE(c.observe(kNoon + 0.0, 0.3));
  ASSERT_TRUE(c.observe(kNoon + 0.2, 0.45));
  ASSERT_TRUE(c.observe(kNoon + 0.4, 0.5));
  EXPECT_NEAR(c.map(kNoon + 0.0, 0.5), 0.1, 1e-9);
  EXPECT_NEAR(c.map(kNoon + 0.2, 0.5), 0.3, 1e-9);
  EXPECT_NEAR(c.map(kNoon + 0.4, 0.5), 0.5, 1e-9);
  // Never after the read that brought it.
  EXPECT_NEAR(c.map(kNoon + 0.6, 0.6), 0.6, 1e-9);
}

TEST(SentenceClock, FollowsAFrontseatClockThatRunsSlow) {
  SentenceClock c;
  // The frontseat's clock loses 0.5 ms a second; every sentence is read 20 ms after it is sent.
  double mapped_minus_sent = 0.0;
  for (int k = 0; k <= 5000; ++k) {
    const double sent = 0.2 * k;
    const double tod = kNoon + sent * (1.0 - 5e-4);
    ASSERT_TRUE(c.observe(tod, sent + 0.02)) << k;
    mapped_minus_sent = c.map(tod, sent + 0.02) - sent;
  }
  // After 1000 s the frontseat is 0.5 s behind; the stamps lag by the window's drift (20 s x
  // 0.5 ms/s), not by the half second a fixed offset would have grown to.
  EXPECT_GT(mapped_minus_sent, 0.0);
  EXPECT_LT(mapped_minus_sent, 0.02 + 0.011);
  EXPECT_GT(mapped_minus_sent, 0.02 - 0.011);
}

TEST(SentenceClock, AFlukeWithinTheLimitsIsForgottenAfterTheWindow) {
  SentenceClockConfig config;
  config.window_s = 20.0;
  SentenceClock c(config);
  for (int k = 0; k < 50; ++k)
    ASSERT_TRUE(c.observe(kNoon + 0.2 * k, 0.2 * k + 0.1));
  // One time 1.5 s ahead of the others: under the garbage limit, so it moves the offset...
  ASSERT_TRUE(c.observe(kNoon + 10.0 + 1.5, 10.1));
  EXPECT_NEAR(c.map(kNoon + 10.0, 10.1), 10.1 - 1.5, 1e-9);
  // ...until it has left the window.
  for (int k = 51; k < 200; ++k)
    ASSERT_TRUE(c.observe(kNoon + 0.2 * k, 0.2 * k + 0.1));
  EXPECT_NEAR(c.map(kNoon + 0.2 * 199, 0.2 * 199 + 0.1), 0.2 * 199 + 0.1, 1e-9);
}

TEST(SentenceClock, GarbageIsRefusedAndMovesNothing) {
  SentenceClock c;
  for (int k = 0; k < 10; ++k)
    ASSERT_TRUE(c.observe(kNoon + 0.2 * k, 0.2 * k + 0.1));
  EXPECT_FALSE(c.observe(kNoon + 2.0 + 3.0, 2.1));      // 3 s ahead
  EXPECT_FALSE(c.observe(kNoon + 2.0 - 600.0, 2.1));    // 10 minutes behind
  EXPECT_FALSE(c.observe(kNoon + 2.0 + 18000.0, 2.1));  // five hours ahead
  ASSERT_TRUE(c.observe(kNoon + 2.0, 2.1));
  EXPECT_NEAR(c.map(kNoon + 2.0, 2.1), 2.1, 1e-9);
  EXPECT_NEAR(c.map(kNoon + 1.0, 2.1), 1.1, 1e-9);
}

TEST(SentenceClock, StartsAgainWhenTheFrontseatClockJumps) {
  SentenceClockConfig config;
  config.reanchor_after = 10;
  SentenceClock c(config);
  for (int k = 0; k < 10; ++k)
    ASSERT_TRUE(c.observe(kNoon + 0.2 * k, 0.2 * k + 0.1));
  // The frontseat set its clock from GPS: an hour later from now on. Nine in a row are refused,
  // the tenth starts the clock again, and the rest map from it.
  for (int k = 10; k < 19; ++k)
    EXPECT_FALSE(c.observe(kNoon + 3600.0 + 0.2 * k, 0.2 * k + 0.1)) << k;
  EXPECT_TRUE(c.observe(kNoon + 3600.0 + 0.2 * 19, 0.2 * 19 + 0.1));
  EXPECT_TRUE(c.observe(kNoon + 3600.0 + 0.2 * 20, 0.2 * 20 + 0.1));
  EXPECT_NEAR(c.map(kNoon + 3600.0 + 0.2 * 20, 0.2 * 20 + 0.1), 0.2 * 20 + 0.1, 1e-9);
}

TEST(SentenceClock, CrossesMidnight) {
  SentenceClock c;
  ASSERT_TRUE(c.observe(86399.9, 100.0));
  ASSERT_TRUE(c.observe(0.1, 100.2));  // 00:00:00.1 the next day
  EXPECT_NEAR(c.map(0.1, 100.2), 100.2, 1e-9);
  EXPECT_NEAR(c.map(86399.9, 100.2), 100.0, 1e-9);
  // And a clock anchored just after midnight maps a time from just before it.
  SentenceClock d;
  ASSERT_TRUE(d.observe(0.3, 50.0));
  EXPECT_NEAR(d.map(86399.7, 50.0), 49.4, 1e-9);
}

TEST(SentenceClock, ResetForgetsTheOffset) {
  SentenceClock c;
  ASSERT_TRUE(c.observe(kNoon, 1.0));
  c.reset();
  // A frontseat with a clock six hours off is not garbage to a clock that starts again.
  ASSERT_TRUE(c.observe(kNoon + 21600.0, 2.0));
  EXPECT_NEAR(c.map(kNoon + 21600.0, 2.0), 2.0, 1e-9);
}

TEST(SentenceClock, RejectsLimitsThatAreNotPositive) {
  SentenceClockConfig config;
  config.window_s = 0.0;
  EXPECT_THROW(SentenceClock{config}, std::invalid_argument);
}

}  // namespace
