// The M200 driver's time stamps: navigation read in bursts keeps its sentences' spacing and is
// strictly increasing, across midnight, past garbage times and reconnects; lines without a usable
// time are spread over their read; GPS fixes and speeds are aged on the same clock.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "support/frontseat_bursts.hpp"
#include "support/nmea_sentence.hpp"
#include "vehicle/m200_session.hpp"

namespace {

using namespace avk::vehicle;
using avk::testing::BoatPose;
using avk::testing::FrontseatLine;
using avk::testing::kFrontseatDay0_s;
using avk::testing::navigation_lines;

const LatLon kDatum{42.358456, -71.087589};

M200Config config() {
  M200Config c;
  c.datum = kDatum;
  return c;
}

// A boat going east at 1 m/s, one pose every 0.2 s from mission time 0.
std::vector<FrontseatLine> eastward(int poses, double day0_s = kFrontseatDay0_s) {
  std::vector<FrontseatLine> out;
  for (int k = 0; k < poses; ++k) {
    const double t = 0.2 * k;
    for (auto& l : navigation_lines(BoatPose{t, t, 0.0, 90.0, 1.0, 0.5}, kDatum, day0_s))
      out.push_back(std::move(l));
  }
  return out;
}

// Every read through the transport's entry point; the samples each read gave, in order.
std::vector<NavSample> receive(M200Session& s, const std::vector<avk::testing::Read>& reads) {
  std::vector<NavSample> out;
  for (const auto& r : reads) {
    s.on_received(r.bytes, r.read_s);
    for (const NavSample& n : s.take_nav()) {
      EXPECT_LE(n.t_s, r.read_s + 1e-9) << "a stamp after the read that brought it";
      out.push_back(n);
    }
  }
  return out;
}

// Strictly increasing, and spaced as the sentences were sent (0.2 s) to within a millisecond.
void expect_sentence_spacing(const std::vector<NavSample>& nav, double first_s) {
  ASSERT_FALSE(nav.empty());
  EXPECT_NEAR(nav[0].t_s, first_s, 1e-3);
  for (std::size_t i = 1; i < nav.size(); ++i) {
    ASSERT_GT(nav[i].t_s, nav[i - 1].t_s) << "sample " << i;
    ASSERT_NEAR(nav[i].t_s - nav[0].t_s, 0.2 * static_cast<double>(i), 1e-3) << "sample " << i;
  }
}

TEST(M200Stamps, BurstsOfTwoToTwentyLinesKeepTheSentenceSpacing) {
  for (unsigned seed = 1; seed <= 5; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    M200Session s(config());
    s.on_connected(0.0);
    const auto reads = avk::testing::in_bursts(eastward(500), seed, 0.05, 1.0);
    int multi_nav_reads = 0;
    for (const auto& r : reads)
      if (r.lines >= 4) ++multi_nav_reads;  // at least two CPNVG in one read
    ASSERT_GT(multi_nav_reads, 50);
    const auto nav = receive(s, reads);
    ASSERT_EQ(nav.size(), 500u);
    // Sent at 0, read with the least delay (0.05 s) at best.
    expect_sentence_spacing(nav, 0.05);
    // CPNVR arrives after its CPNVG: each sample takes the previous one's speed and yaw rate,
    // 0.2 s old on the sentence clock however late the read that brought both.
    for (std::size_t i = 1; i < nav.size(); ++i) {
      ASSERT_NEAR(nav[i].speed_mps, 1.0, 1e-3) << i;
      ASSERT_TRUE(nav[i].yaw_rate_dps) << i;
    }
    EXPECT_EQ(s.counters().sentence_times_rejected, 0u);
    EXPECT_EQ(s.counters().errors, 0u);
  }
}

TEST(M200Stamps, AcrossMidnight) {
  M200Session s(config());
  s.on_connected(0.0);
  // Midnight UTC comes 30 s into the run: the time fields go from 235959.8 to 000000.
  const auto reads = avk::testing::in_bursts(eastward(300, 86400.0 - 30.0), 3, 0.05, 1.0);
  const auto nav = receive(s, reads);
  ASSERT_EQ(nav.size(), 300u);
  expect_sentence_spacing(nav, 0.05);
  EXPECT_EQ(s.counters().sentence_times_rejected, 0u);
}

// The lines of each pose in one read, as a prompt link delivers them.
std::vector<avk::testing::Read> one_read_per_pose(const std::vector<FrontseatLine>& lines) {
  return avk::testing::in_bursts(lines, 1, 0.05, 0.0, 3, 3);
}

TEST(M200Stamps, AGarbageTimeIsStampedOnArrivalAndDoesNotMoveTheClock) {
  M200Session s(config());
  s.on_connected(0.0);
  auto lines = eastward(100);
  // Pose 50's CPNVG says it is 5 s later, pose 60's an hour earlier, pose 70's three hours
  // later: a frontseat glitch, with a valid checksum.
  const auto garbled = [&](int pose, double shift_s) {
    auto l = navigation_lines(BoatPose{0.2 * pose, 0.2 * pose, 0.0, 90.0, 1.0, 0.5}, kDatum,
                              kFrontseatDay0_s + shift_s);
    lines[3 * static_cast<std::size_t>(pose)] = l[0];
  };
  garbled(50, 5.0);
  garbled(60, -3600.0);
  garbled(70, 3.0 * 3600.0);
  const auto nav = receive(s, one_read_per_pose(lines));
  ASSERT_EQ(nav.size(), 100u);
  EXPECT_EQ(s.counters().sentence_times_rejected, 3u);
  for (int k = 0; k < 100; ++k) {
    const double sent = 0.2 * k;
    if (k == 50 || k == 60 || k == 70) {
      // The first of its read's three lines: a third of the way from the previous read.
      EXPECT_NEAR(nav[k].t_s, sent - 0.2 + 0.05 + 0.2 / 3.0, 1e-6) << k;
    } else {
      EXPECT_NEAR(nav[k].t_s, sent + 0.05, 1e-6) << k;  // the clock did not move
    }
    if (k > 0) {
      EXPECT_GT(nav[k].t_s, nav[k - 1].t_s) << k;
    }
  }
}

TEST(M200Stamps, AReconnectStartsTheClockAgain) {
  M200Session s(config());
  s.on_connected(0.0);
  const auto before = receive(s, one_read_per_pose(eastward(50)));
  ASSERT_EQ(before.size(), 50u);
  s.on_disconnected(10.0);
  // The frontseat restarted with its clock at 01:00 UTC: nothing of the old offset applies.
  s.on_connected(20.0);
  auto later = avk::testing::in_bursts(eastward(50, 3600.0), 2, 0.05, 1.0);
  for (auto& r : later)
    r.read_s += 20.0;
  const auto after = receive(s, later);
  ASSERT_EQ(after.size(), 50u);
  expect_sentence_spacing(after, 20.05);
  EXPECT_GT(after.front().t_s, before.back().t_s);
  EXPECT_EQ(s.counters().sentence_times_rejected, 0u);
}

TEST(M200Stamps, LinesWithoutAUsableTimeAreSpreadOverTheirRead) {
  M200Session s(config());
  s.on_connected(0.0);
  receive(s, one_read_per_pose(eastward(51)));  // the last read at 10.05
  // Then five CPNVG in one read at 11.05, their times garbage: the read's lines came in since
  // the previous read, so they are put at 10.25, 10.45, ... 11.05.
  std::string bytes;
  for (int k = 0; k < 5; ++k) {
    bytes += navigation_lines(BoatPose{10.2 + 0.2 * k, 0.0, 0.0, 90.0, 1.0, 0.0}, kDatum,
                              kFrontseatDay0_s + 7200.0)[0]
                 .text;
  }
  s.on_received(bytes, 11.05);
  const auto nav = s.take_nav();
  ASSERT_EQ(nav.size(), 5u);
  for (int k = 0; k < 5; ++k)
    EXPECT_NEAR(nav[k].t_s, 10.05 + 0.2 * (k + 1), 1e-9) << k;
  EXPECT_EQ(s.counters().sentence_times_rejected, 5u);
}

TEST(M200Stamps, ARepeatedSentenceTimeStillMovesTheStampForward) {
  M200Session s(config());
  s.on_connected(0.0);
  const std::string line =
      navigation_lines(BoatPose{1.0, 1.0, 0.0, 90.0, 1.0, 0.0}, kDatum)[0].text;
  s.on_received(line + line + line, 1.05);
  const auto nav = s.take_nav();
  ASSERT_EQ(nav.size(), 3u);
  EXPECT_NEAR(nav[0].t_s, 1.05, 1e-9);
  EXPECT_NEAR(nav[1].t_s, 1.05 + kMinNavStep_s, 1e-9);
  EXPECT_NEAR(nav[2].t_s, 1.05 + 2.0 * kMinNavStep_s, 1e-9);
}

TEST(M200Stamps, FixesAndSpeedsAreAgedOnTheSentenceClock) {
  M200Session s(config());
  s.on_connected(0.0);
  // A prompt first read sets both clocks, the frontseat's and the GPS receiver's.
  std::string first;
  for (const auto& l : navigation_lines(BoatPose{0.0, 0.0, 0.0, 90.0, 1.0, 0.0}, kDatum))
    first += l.text;
  s.on_received(first, 0.05);
  ASSERT_EQ(s.take_nav().size(), 1u);

  Gprmc fix;
  fix.valid = true;
  const LatLon p = LocalGrid(kDatum.lat_deg, kDatum.lon_deg).to_geodetic(30.0, 0.0);
  fix.lat_deg = p.lat_deg;
  fix.lon_deg = p.lon_deg;
  fix.speed_knots = 1.2 / kMetresPerSecondPerKnot;
  Cpnvg heading;
  heading.position_ok = false;
  heading.heading_deg = 80.0;
  // A fix sent at 3.0 and a heading without GPS quality sent at 4.5 come in one read: they were
  // 1.5 s apart, more than a fix may be older than its heading, so they are not combined.
  fix.time_s = kFrontseatDay0_s + 3.0;
  heading.time_s = heading.nav_time_s = kFrontseatDay0_s + 4.5;
  s.on_received(format_sentence(fix) + format_sentence(heading), 4.6);
  EXPECT_TRUE(s.take_nav().empty());
  EXPECT_EQ(s.counters().nav_without_position, 1u);
  // Sent 0.2 s apart and read 1.6 s late in one read: combined, with the fix's speed.
  fix.time_s = kFrontseatDay0_s + 6.2;
  heading.time_s = heading.nav_time_s = kFrontseatDay0_s + 6.4;
  s.on_received(format_sentence(fix) + format_sentence(heading), 8.0);
  const auto nav = s.take_nav();
  ASSERT_EQ(nav.size(), 1u);
  EXPECT_NEAR(nav[0].t_s, 6.45, 1e-6);
  EXPECT_NEAR(nav[0].x_m, 30.0, 0.01);
  EXPECT_NEAR(nav[0].speed_mps, 1.2, 1e-3);
}

TEST(M200Stamps, ReadsAreSplitIntoLinesAcrossTheirBoundaries) {
  M200Session s(config());
  s.on_connected(0.0);
  const std::string line =
      navigation_lines(BoatPose{1.0, 1.0, 0.0, 90.0, 1.0, 0.0}, kDatum)[0].text;
  s.on_received(line.substr(0, 20), 1.0);
  EXPECT_EQ(s.counters().lines, 0u);
  s.on_received(line.substr(20), 1.1);
  EXPECT_EQ(s.take_nav().size(), 1u);
  // A line longer than the driver buffers is counted once as oversized and skipped to its end.
  for (int i = 0; i < 5; ++i)
    s.on_received(std::string(500, 'x'), 2.0 + i * 0.01);
  s.on_received("tail\n" + line, 2.1);
  EXPECT_EQ(s.counters().errors_by_code.at("oversized"), 1u);
  EXPECT_EQ(s.counters().errors, 1u);
  EXPECT_EQ(s.take_nav().size(), 1u);
  // A line cut by a reconnect is not completed by the next link's bytes.
  s.on_received(line.substr(0, 20), 3.0);
  s.on_disconnected(3.1);
  s.on_connected(3.2);
  s.on_received(line.substr(20), 3.3);
  EXPECT_TRUE(s.take_nav().empty());
  EXPECT_EQ(s.counters().errors, 2u);
}

}  // namespace
