// The frontseat emulator's faults over real sockets: dropped, corrupted, delayed and bursty
// sentences, a cut link, and bad input from one client among others; at 5-20x real time.
#include <gtest/gtest.h>

#include "sim/frontseat_link.hpp"

using namespace avk::testing::frontseat_link;

namespace {

double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

TEST(FrontseatEmulator, DropsAboutTheConfiguredFraction) {
  FrontseatEmulatorOptions o = fast_options(20.0);
  o.faults.drop_fraction = 0.2;
  FrontseatEmulator emu(o);
  RawClient c(emu.port());
  ASSERT_TRUE(run_until_clock(emu, {&c}, 41.5));
  auto n = count_in_window(c.lines(), o, 0.95, 40.95);
  const int expected = static_cast<int>(std::lround(40.0 * (3 * o.nav_hz + o.battery_hz)));
  const int received = n["CPNVG"] + n["CPNVR"] + n["GPRMC"] + n["CPRBS"];
  const double kept = static_cast<double>(received) / expected;
  std::cout << "drop 0.2: received " << received << " of " << expected << " (" << kept << ")\n";
  // 620 sentences: the binomial sd of the kept fraction is 0.016, so this is 6 sd wide.
  EXPECT_GT(kept, 0.7);
  EXPECT_LT(kept, 0.9);
  for (const auto& r : c.lines())
    EXPECT_TRUE(parse_fs(r.line).ok()) << r.line;
  const FrontseatStatus s = emu.status();
  const double dropped =
      static_cast<double>(s.sentences_dropped) / (s.sentences_sent + s.sentences_dropped);
  EXPECT_GT(dropped, 0.1);
  EXPECT_LT(dropped, 0.3);
  EXPECT_EQ(s.sentences_corrupted, 0u);
}

TEST(FrontseatEmulator, CorruptsAboutTheConfiguredFractionInTheChecksumOnly) {
  FrontseatEmulatorOptions o = fast_options(20.0);
  o.faults.corrupt_fraction = 0.2;
  FrontseatEmulator emu(o);
  RawClient c(emu.port());
  ASSERT_TRUE(run_until_clock(emu, {&c}, 41.0));
  int bad = 0;
  for (const auto& r : c.lines()) {
    const auto p = parse_fs(r.line);
    if (p.ok()) continue;
    ++bad;
    EXPECT_EQ(p.error()->code, veh::NmeaError::Code::bad_checksum) << r.line;
    // Only the checksum was touched: with the right one the sentence reads again.
    const std::string fixed =
        avk::testing::nmea_sentence(std::string_view(r.line).substr(1, r.line.rfind('*') - 1));
    EXPECT_TRUE(parse_fs(fixed).ok()) << fixed;
  }
  const double fraction = static_cast<double>(bad) / c.lines().size();
  std::cout << "corrupt 0.2: " << bad << " of " << c.lines().size() << " fail (" << fraction
            << ")\n";
  EXPECT_GT(c.lines().size(), 550u);
  EXPECT_GT(fraction, 0.1);
  EXPECT_LT(fraction, 0.3);
  const FrontseatStatus s = emu.status();
  EXPECT_EQ(s.sentences_dropped, 0u);
  EXPECT_NEAR(static_cast<double>(s.sentences_corrupted) / s.sentences_sent, 0.2, 0.1);
}

TEST(FrontseatEmulator, NavDelayHoldsNavigationBackButNotTheBattery) {
  FrontseatEmulatorOptions o = fast_options(10.0);
  FrontseatEmulator emu(o);
  RawClient c(emu.port());
  ASSERT_TRUE(run_until_clock(emu, {&c}, 4.0));
  const double switched = emu.now_s();
  emu.set_faults(FrontseatFaults{0.0, 0.0, 1.0});
  ASSERT_TRUE(run_until_clock(emu, {&c}, 12.0));

  // Age of each sentence when read: the emulator's clock minus its time field.
  std::vector<double> nav_before, nav_after, battery_after;
  for (const auto& r : c.lines()) {
    const auto p = parse_fs(r.line);
    ASSERT_TRUE(p.ok());
    const double t = time_field(*p.sentence()) - o.start_of_day_s;
    const double age = r.at_s - t;
    const std::string type = type_of(*p.sentence());
    if (type == "CPNVG" && t >= 1.0 && t < switched - 0.3) nav_before.push_back(age);
    if (type == "CPNVG" && t > switched + 0.3) nav_after.push_back(age);
    if (type == "CPRBS" && t > switched + 0.3) battery_after.push_back(age);
  }
  ASSERT_GE(nav_before.size(), 10u);
  ASSERT_GE(nav_after.size(), 20u);
  ASSERT_GE(battery_after.size(), 2u);
  const double before = median(nav_before), after = median(nav_after);
  std::cout << "CPNVG age when read: " << before << " s undelayed, " << after
            << " s with nav_delay_s 1; CPRBS " << median(battery_after) << " s\n";
  // A loaded machine reads late, which only adds to an age: the bounds from below hold on any
  // machine, and those from above use the freshest sentence of each kind (a reader that was late
  // for every one of dozens of sentences would be a stall of the whole test, not load).
  const auto freshest = [](const std::vector<double>& v) {
    return *std::min_element(v.begin(), v.end());
  };
  EXPECT_GE(freshest(nav_before), -1e-9);
  EXPECT_LT(freshest(nav_before), 0.5);
  // Held back by the delay: never released early, and released when due.
  EXPECT_GE(freshest(nav_after), 1.0 - 1e-9);
  EXPECT_LT(freshest(nav_after), 1.5);
  EXPECT_GT(after - before, 0.5);
  EXPECT_GE(freshest(battery_after), -1e-9);
  EXPECT_LT(freshest(battery_after), 0.5);
  // Time fields still increase: delayed, not reordered.
  double last = -1.0;
  for (const auto& r : c.lines()) {
    const auto p = parse_fs(r.line);
    if (!std::holds_alternative<veh::Cpnvg>(*p.sentence())) continue;
    EXPECT_GT(time_field(*p.sentence()), last);
    last = time_field(*p.sentence());
  }
}

TEST(FrontseatEmulator, BurstsHoldSentencesBackAndWriteTwoToTwentyAtOnce) {
  FrontseatEmulatorOptions o = fast_options(20.0);
  o.faults.burst_max_lines = 20;
  FrontseatEmulator emu(o);
  RawClient c(emu.port());
  ASSERT_TRUE(run_until_clock(emu, {&c}, 30.0));
  const FrontseatStatus s = emu.status();
  ASSERT_GT(c.lines().size(), 300u);
  // Bursts of 2 to 20: between a twentieth and a half as many bursts as sentences.
  EXPECT_GE(s.bursts * 20, s.sentences_sent);
  EXPECT_LE(s.bursts * 2, s.sentences_sent);
  // A burst is one write, so it is read whole: never more reads than bursts, where a sentence
  // at a time would take a read for each plant step.
  std::set<double> reads;
  for (const auto& r : c.lines())
    reads.insert(r.at_s);
  EXPECT_LE(reads.size(), s.bursts);
  // Held back, not reordered: the time fields of each kind still increase.
  std::map<std::string, double> last;
  for (const auto& r : c.lines()) {
    const auto p = parse_fs(r.line);
    ASSERT_TRUE(p.ok()) << r.line;
    const std::string type = type_of(*p.sentence());
    const double t = time_field(*p.sentence());
    if (last.count(type)) {
      EXPECT_GT(t, last[type]) << type;
    }
    last[type] = t;
  }
  EXPECT_THROW(emu.set_faults(FrontseatFaults{0.0, 0.0, 0.0, 101}), std::invalid_argument);
}

TEST(FrontseatEmulator, CutLinkClosesAndRefusesUntilItEnds) {
  FrontseatEmulatorOptions o = fast_options(5.0);
  FrontseatEmulator emu(o);
  RawClient a(emu.port());
  ASSERT_TRUE(run_until(emu, {&a}, [&] { return a.lines().size() >= 3; }));
  EXPECT_EQ(emu.status().clients, 1u);
  EXPECT_FALSE(emu.status().link_cut);

  // A cut of 10 s of emulator clock (2 s of wall time): long enough that closing the open
  // connection and refusing a new one both fall inside it however late a loaded machine runs
  // this thread.
  constexpr double kCutS = 10.0;
  const double cut_at = emu.now_s();
  emu.cut_link(kCutS);
  EXPECT_TRUE(emu.status().link_cut);
  ASSERT_TRUE(run_until(
      emu, {&a}, [&] { return a.closed(); }, {}, 30.0));
  EXPECT_EQ(a.close_error(), net::error::eof) << a.close_error().message();

  // Connecting during the cut: the connection is taken, then closed at once.
  RawClient b(emu.port());
  ASSERT_TRUE(run_until(
      emu, {&b}, [&] { return b.closed(); }, {}, 30.0));
  // Asserted only when the cut was still on, which it is unless this thread stalled for 2 s.
  if (emu.now_s() < cut_at + kCutS) {
    EXPECT_TRUE(b.lines().empty());
    EXPECT_EQ(emu.status().clients, 0u);
  }

  ASSERT_TRUE(run_until(
      emu, {}, [&] { return !emu.status().link_cut; }, {}, 30.0));
  EXPECT_GE(emu.now_s(), cut_at + kCutS);
  RawClient d(emu.port());
  ASSERT_TRUE(run_until(emu, {&d}, [&] {
    for (const auto& r : d.lines())
      if (r.line.rfind("$CPNVG", 0) == 0) return true;
    return false;
  }));
  EXPECT_FALSE(d.closed());
  const FrontseatStatus s = emu.status();
  EXPECT_EQ(s.connections, 3u);
  EXPECT_EQ(s.clients, 1u);
}

TEST(FrontseatEmulator, BadInputIsCountedAndOtherClientsKeepBeingServed) {
  FrontseatEmulatorOptions o = fast_options(10.0);
  FrontseatEmulator emu(o);
  RawClient good(emu.port());
  RawClient bad(emu.port());
  ASSERT_TRUE(run_until(emu, {&good, &bad}, [&] { return emu.status().clients == 2; }));

  ASSERT_TRUE(bad.send("hello frontseat\r\n"));
  ASSERT_TRUE(bad.send(with_bad_checksum(veh::format_pydir(50, 50))));
  ASSERT_TRUE(bad.send(std::string("$PYDIR,\x01\xff,2\r\n")));
  ASSERT_TRUE(bad.send("$PYDIR,500,500\r\n"));            // out of range
  ASSERT_TRUE(bad.send("$PYDEV,90,1\r\n$PYCLT,1\r\n"));   // well-formed: no effect
  ASSERT_TRUE(bad.send(std::string(300, 'x') + "\r\n"));  // too long for a sentence
  ASSERT_TRUE(run_until(emu, {&good, &bad}, [&] { return emu.status().lines_received >= 7; }));
  FrontseatStatus s = emu.status();
  EXPECT_EQ(s.lines_received, 7u);
  EXPECT_EQ(s.bad_lines_received, 5u);
  EXPECT_EQ(s.left_pct, 0.0);
  EXPECT_FALSE(s.last_pydir_s.has_value());
  EXPECT_FALSE(bad.closed());

  // A line that never ends: the emulator hangs up on that client only.
  bad.send(std::string(10000, 'A'));
  ASSERT_TRUE(run_until(emu, {&good, &bad}, [&] { return bad.closed(); }));
  ASSERT_TRUE(run_until(emu, {&good, &bad}, [&] { return emu.status().clients == 1; }));
  EXPECT_EQ(emu.status().bad_lines_received, 6u);

  const std::size_t before = good.lines().size();
  ASSERT_TRUE(good.send(veh::format_pydir(40, 40)));
  ASSERT_TRUE(run_until(emu, {&good}, [&] {
    return good.lines().size() >= before + 10 && emu.status().left_pct == 40.0;
  }));
  EXPECT_FALSE(good.closed());
  EXPECT_EQ(emu.status().connections, 2u);
}
