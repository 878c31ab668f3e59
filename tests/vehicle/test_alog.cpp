// The .alog reader (fields, headers, malformed lines, line endings) and the navigation builder
// (grouping by timestamp, sample-and-hold guidance, renamed variables).
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "vehicle/alog.hpp"

namespace {

using avk::vehicle::AlogEntry;
using avk::vehicle::AlogNames;
using avk::vehicle::AlogNavBuilder;
using avk::vehicle::AlogReader;
using avk::vehicle::GuidedNav;

std::vector<AlogEntry> read_all(const std::string& text, avk::vehicle::AlogStats* stats = nullptr,
                                std::size_t max_line = avk::vehicle::kAlogMaxLineBytes) {
  std::istringstream in(text);
  AlogReader reader(in, max_line);
  std::vector<AlogEntry> out;
  AlogEntry e;
  while (reader.next(e))
    out.push_back(e);
  if (stats) *stats = reader.stats();
  return out;
}

std::vector<GuidedNav> build(const std::string& text, AlogNavBuilder& builder) {
  std::istringstream in(text);
  AlogReader reader(in);
  std::vector<GuidedNav> out;
  AlogEntry e;
  GuidedNav s;
  while (reader.next(e))
    if (builder.feed(e, s)) out.push_back(s);
  if (builder.finish(s)) out.push_back(s);
  return out;
}

TEST(AlogReader, ReadsFieldsSeparatedByRunsOfBlanksAndSkipsHeaderAndBlankLines) {
  avk::vehicle::AlogStats stats;
  const auto e = read_all(
      "%%%%%%%%%%%%%%%%%%%%\n"
      "%% LOGFILE:       /home/m200/log.alog\n"
      "%% FILE OPENED ON Wed Jun 12 10:00:00 2013\n"
      "\n"
      "   \t \n"
      "0.125   NAV_X        uSimMarine    12.5\n"
      "0.125\tNAV_Y\t\tuSimMarine\t-3\n"
      "  1.5  DB_CLIENTS   MOOSDB_alpha  pHelmIvP,uSimMarine,  pLogger\n"
      "2 APPCAST_REQ pMarineViewer node=all,app=all,duration=3.0, key=x   \n",
      &stats);
  ASSERT_EQ(e.size(), 4u);
  EXPECT_DOUBLE_EQ(e[0].t_s, 0.125);
  EXPECT_EQ(e[0].variable, "NAV_X");
  EXPECT_EQ(e[0].source, "uSimMarine");
  EXPECT_EQ(e[0].value, "12.5");
  EXPECT_EQ(e[0].line, 6u);
  EXPECT_EQ(e[1].variable, "NAV_Y");
  EXPECT_EQ(e[1].value, "-3");
  // The value is the rest of the line, inner spaces kept, trailing blanks dropped.
  EXPECT_EQ(e[2].value, "pHelmIvP,uSimMarine,  pLogger");
  EXPECT_EQ(e[2].source, "MOOSDB_alpha");
  EXPECT_EQ(e[3].value, "node=all,app=all,duration=3.0, key=x");
  EXPECT_EQ(e[3].line, 9u);
  EXPECT_EQ(stats.lines, 9u);
  EXPECT_EQ(stats.header_lines, 3u);
  EXPECT_EQ(stats.blank_lines, 2u);
  EXPECT_EQ(stats.entries, 4u);
  EXPECT_EQ(stats.malformed.count, 0u);
}

TEST(AlogReader, CountsMalformedLinesWithLineNumbersAndKeepsGoing) {
  avk::vehicle::AlogStats stats;
  const auto e = read_all(
      "1.0 NAV_X src 1\n"             // 1 ok
      "garbage\n"                     // 2 one field
      "2.0 NAV_X src\n"               // 3 no value
      "abc NAV_X src 1\n"             // 4 time not a number
      "nan NAV_X src 1\n"             // 5 time not finite
      "inf NAV_X src 1\n"             // 6
      "1.5x NAV_X src 1\n"            // 7 trailing characters
      "3.0 NAV_Y src hello world\n",  // 8 ok (the value need not be a number here)
      &stats);
  ASSERT_EQ(e.size(), 2u);
  EXPECT_EQ(e[1].line, 8u);
  EXPECT_EQ(stats.malformed.count, 6u);
  ASSERT_EQ(stats.malformed.first.size(), 6u);
  const std::size_t lines[] = {2, 3, 4, 5, 6, 7};
  for (std::size_t i = 0; i < 6; ++i)
    EXPECT_EQ(stats.malformed.first[i].line, lines[i]);
  EXPECT_NE(stats.malformed.first[0].reason.find("expected time, variable, source and value"),
            std::string::npos);
  EXPECT_NE(stats.malformed.first[2].reason.find("'abc'"), std::string::npos);
}

TEST(AlogReader, KeepsOnlyTheFirstTenMalformedLinesButCountsAll) {
  std::string text;
  for (int i = 0; i < 25; ++i)
    text += "junk\n1 A b c\n";
  avk::vehicle::AlogStats stats;
  EXPECT_EQ(read_all(text, &stats).size(), 25u);
  EXPECT_EQ(stats.malformed.count, 25u);
  ASSERT_EQ(stats.malformed.first.size(), avk::vehicle::kAlogReportedProblems);
  EXPECT_EQ(stats.malformed.first.front().line, 1u);
  EXPECT_EQ(stats.malformed.first.back().line, 19u);
}

TEST(AlogReader, HandlesCrlfAndAFinalLineWithoutNewline) {
  avk::vehicle::AlogStats stats;
  const auto e = read_all("%% header\r\n1.0 NAV_X src 4.5\r\n\r\n2.0 NAV_Y src two words", &stats);
  ASSERT_EQ(e.size(), 2u);
  EXPECT_EQ(e[0].value, "4.5");
  EXPECT_EQ(e[1].value, "two words");
  EXPECT_EQ(e[1].line, 4u);
  EXPECT_EQ(stats.lines, 4u);
  EXPECT_EQ(stats.header_lines, 1u);
  EXPECT_EQ(stats.blank_lines, 1u);
  EXPECT_EQ(stats.malformed.count, 0u);
}

TEST(AlogReader, EmptyInputHasNoLines) {
  avk::vehicle::AlogStats stats;
  EXPECT_TRUE(read_all("", &stats).empty());
  EXPECT_EQ(stats.lines, 0u);
}

TEST(AlogReader, OversizedLinesAreMalformedAndSkippedWithoutBuffering) {
  const std::string big(200'000, 'x');
  avk::vehicle::AlogStats stats;
  // Lines across several buffer refills, including an oversized last line without a newline.
  const auto e = read_all("1 A s " + big + "\n2 B s ok\n3 C s " + std::string(70'000, 'y') +
                              "\n4 D s ok\n" + std::string(3'000'000, 'z'),
                          &stats);
  ASSERT_EQ(e.size(), 2u);
  EXPECT_EQ(e[0].variable, "B");
  EXPECT_EQ(e[0].line, 2u);
  EXPECT_EQ(e[1].variable, "D");
  EXPECT_EQ(stats.lines, 5u);
  EXPECT_EQ(stats.malformed.count, 3u);
  ASSERT_EQ(stats.malformed.first.size(), 3u);
  EXPECT_EQ(stats.malformed.first[0].line, 1u);
  EXPECT_EQ(stats.malformed.first[1].line, 3u);
  EXPECT_EQ(stats.malformed.first[2].line, 5u);
  EXPECT_NE(stats.malformed.first[0].reason.find("longer than 65536"), std::string::npos);
}

TEST(AlogReader, ALineJustUnderTheLimitIsRead) {
  const std::string value(1000, 'v');
  const auto e = read_all("1 A s " + value + "\n", nullptr, 6 + value.size());
  ASSERT_EQ(e.size(), 1u);
  EXPECT_EQ(e[0].value, value);
}

TEST(AlogProblems, MergeKeepsTheLowestLineNumbersAndTheTotal) {
  avk::vehicle::AlogProblems a, b;
  for (std::size_t line = 100; line < 120; ++line)
    a.add(line, "a");
  for (std::size_t line = 1; line < 30; line += 5)
    b.add(line, "b");
  a.merge(b);
  EXPECT_EQ(a.count, 26u);
  ASSERT_EQ(a.first.size(), 10u);
  EXPECT_EQ(a.first[0].line, 1u);
  EXPECT_EQ(a.first[5].line, 26u);
  EXPECT_EQ(a.first[6].line, 100u);
  EXPECT_EQ(a.first[9].line, 103u);
}

TEST(AlogNavBuilder, GroupsPostingsOfOneTimestampIntoOneSample) {
  AlogNavBuilder b;
  const auto s = build(
      "1.000 NAV_X uSimMarine 10\n"
      "1.000 NAV_Y uSimMarine 20\n"
      "1.0004 NAV_HEADING uSimMarine 90\n"  // within 1 ms: the same report
      "1.000 NAV_SPEED uSimMarine 1.5\n"
      "1.100 NAV_X uSimMarine 11\n"
      "1.100 NAV_Y uSimMarine 21\n"
      "1.100 NAV_HEADING uSimMarine 91\n"
      "1.200 NAV_X uSimMarine 12\n"  // no y or heading at 1.2: not a sample
      "1.300 NAV_X uSimMarine 13\n"
      "1.300 NAV_Y uSimMarine 23\n"
      "1.300 NAV_HEADING uSimMarine 93\n"
      "1.300 NAV_SPEED uSimMarine 1.7\n",
      b);
  ASSERT_EQ(s.size(), 3u);
  EXPECT_DOUBLE_EQ(s[0].nav.t_s, 1.0);
  EXPECT_DOUBLE_EQ(s[0].nav.x_m, 10.0);
  EXPECT_DOUBLE_EQ(s[0].nav.y_m, 20.0);
  EXPECT_DOUBLE_EQ(s[0].nav.heading_deg, 90.0);
  EXPECT_DOUBLE_EQ(s[0].nav.speed_mps, 1.5);
  EXPECT_DOUBLE_EQ(s[1].nav.t_s, 1.1);
  EXPECT_DOUBLE_EQ(s[1].nav.x_m, 11.0);
  EXPECT_DOUBLE_EQ(s[1].nav.speed_mps, 1.5);  // the latest speed
  EXPECT_DOUBLE_EQ(s[2].nav.t_s, 1.3);
  EXPECT_DOUBLE_EQ(s[2].nav.speed_mps, 1.7);  // posted in its own group, after x, y, heading
  EXPECT_FALSE(s[0].desired_heading_deg);
  EXPECT_FALSE(s[0].desired_speed_mps);
  EXPECT_EQ(b.stats().samples, 3u);
  EXPECT_EQ(b.stats().incomplete_groups, 1u);
  EXPECT_DOUBLE_EQ(*b.stats().max_speed_mps, 1.7);
}

TEST(AlogNavBuilder, DesiredHeadingAndSpeedAreSampleAndHold) {
  AlogNavBuilder b;
  std::string log;
  const auto nav = [&](double t, double h) {
    for (const char* v : {"NAV_X", "NAV_Y", "NAV_SPEED"})
      log += std::to_string(t) + " " + v + " uSimMarine 1\n";
    log += std::to_string(t) + " NAV_HEADING uSimMarine " + std::to_string(h) + "\n";
  };
  nav(0.0, 10);
  log += "0.1 DESIRED_HEADING pHelmIvP 45\n";
  nav(0.25, 11);
  log += "0.3 DESIRED_SPEED pHelmIvP 1.2\n";
  nav(0.5, 12);
  nav(0.75, 13);                                // held
  log += "0.75 DESIRED_HEADING pHelmIvP 80\n";  // same stamp: in force for that sample
  log += "0.9 DESIRED_HEADING pHelmIvP not-a-number\n";
  nav(1.0, 14);
  const auto s = build(log, b);
  ASSERT_EQ(s.size(), 5u);
  EXPECT_FALSE(s[0].desired_heading_deg);
  EXPECT_FALSE(s[0].desired_speed_mps);
  EXPECT_DOUBLE_EQ(*s[1].desired_heading_deg, 45.0);
  EXPECT_FALSE(s[1].desired_speed_mps);
  EXPECT_DOUBLE_EQ(*s[2].desired_heading_deg, 45.0);
  EXPECT_DOUBLE_EQ(*s[2].desired_speed_mps, 1.2);
  EXPECT_DOUBLE_EQ(*s[3].desired_heading_deg, 80.0);
  EXPECT_DOUBLE_EQ(*s[4].desired_heading_deg, 80.0);  // the unreadable value changed nothing
  EXPECT_DOUBLE_EQ(*s[4].desired_speed_mps, 1.2);
  EXPECT_DOUBLE_EQ(s[4].nav.heading_deg, 14.0);
  EXPECT_EQ(b.stats().malformed.count, 1u);
  ASSERT_EQ(b.stats().malformed.first.size(), 1u);
  EXPECT_NE(b.stats().malformed.first[0].reason.find("DESIRED_HEADING"), std::string::npos);
}

TEST(AlogNavBuilder, UnreadableNavigationValuesAndTimeGoingBackAreMalformed) {
  AlogNavBuilder b;
  const auto s = build(
      "1 NAV_X a 1\n"
      "1 NAV_Y a inf\n"  // 2: not finite, so the group has no y
      "1 NAV_HEADING a 3\n"
      "2 NAV_X a 1\n"
      "2 NAV_Y a 2\n"
      "2 NAV_HEADING a 3\n"
      "3 NAV_X a 1\n"
      "1.5 NAV_Y a 2\n",  // 8: before the open group
      b);
  EXPECT_EQ(s.size(), 1u);
  EXPECT_EQ(b.stats().malformed.count, 2u);
  ASSERT_EQ(b.stats().malformed.first.size(), 2u);
  EXPECT_EQ(b.stats().malformed.first[0].line, 2u);
  EXPECT_EQ(b.stats().malformed.first[1].line, 8u);
  EXPECT_EQ(b.stats().incomplete_groups, 2u);  // at 1 (no y) and at 3 (no y or heading)
}

// The ranges every reader of navigation holds (vehicle/nav_ranges.hpp): a value outside them is
// malformed and changes nothing, so a log's mission can be exported and imported again.
TEST(AlogNavBuilder, NavigationValuesOutOfRangeAreMalformed) {
  AlogNavBuilder b;
  const auto s = build(
      "1 NAV_X a -1e308\n"  // 1: farther than any point of the earth
      "1 NAV_Y a 2\n"
      "1 NAV_HEADING a 3\n"
      "2 NAV_X a 1\n"
      "2 NAV_Y a 2\n"
      "2 NAV_HEADING a 400\n"  // 6
      "2 NAV_SPEED a -5\n"     // 7
      "3 NAV_X a 1\n"
      "3 NAV_Y a 2\n"
      "3 NAV_HEADING a 360\n"      // in: 360 is 0
      "3 DESIRED_SPEED a 1000\n"   // 11
      "3 DESIRED_HEADING a -10\n"  // 12
      "4 NAV_X a 1\n",
      b);
  ASSERT_EQ(s.size(), 1u);  // at 3; 1 has no x, 2 no heading
  EXPECT_DOUBLE_EQ(s[0].nav.heading_deg, 360.0);
  EXPECT_DOUBLE_EQ(s[0].nav.speed_mps, 0.0);  // -5 was not taken
  EXPECT_FALSE(s[0].desired_speed_mps);
  EXPECT_FALSE(s[0].desired_heading_deg);
  ASSERT_EQ(b.stats().malformed.count, 5u);
  const auto& p = b.stats().malformed.first;
  EXPECT_EQ(p[0].line, 1u);
  EXPECT_EQ(p[0].reason, "NAV_X value '-1e308' is out of range [-12756274.0, 12756274.0]");
  EXPECT_EQ(p[1].line, 6u);
  EXPECT_EQ(p[1].reason, "NAV_HEADING value '400' is out of range [0.0, 360.0]");
  EXPECT_EQ(p[2].line, 7u);
  EXPECT_EQ(p[2].reason, "NAV_SPEED value '-5' is out of range [0.0, 100.0]");
  EXPECT_EQ(p[3].line, 11u);
  EXPECT_EQ(p[4].line, 12u);
}

TEST(AlogNavBuilder, RenamedVariablesAndTurnRecords) {
  const AlogNames names = avk::vehicle::parse_alog_names(
      "NAV_X=GPS_X,NAV_Y=GPS_Y,NAV_HEADING=COMPASS_HEADING,"
      "DESIRED_HEADING=HELM_HEADING,TURN_RECORD_RAW=MY_TURN");
  EXPECT_EQ(names.nav_x, "GPS_X");
  EXPECT_EQ(names.nav_speed, "NAV_SPEED");
  AlogNavBuilder b(names);
  const auto s = build(
      "1 GPS_X gps 5\n"
      "1 GPS_Y gps 6\n"
      "1 COMPASS_HEADING compass 7\n"
      "1 NAV_X other 99\n"  // the default name is now just another variable
      "1.5 HELM_HEADING pHelmIvP 33\n"
      "1.6 MY_TURN pDynamicsMonitor AVKTURN/1 a=b\n"
      "2 GPS_X gps 8\n"
      "2 GPS_Y gps 9\n"
      "2 COMPASS_HEADING compass 10\n",
      b);
  ASSERT_EQ(s.size(), 2u);
  EXPECT_DOUBLE_EQ(s[0].nav.x_m, 5.0);
  EXPECT_DOUBLE_EQ(s[0].nav.heading_deg, 7.0);
  EXPECT_FALSE(s[0].desired_heading_deg);
  EXPECT_DOUBLE_EQ(*s[1].desired_heading_deg, 33.0);
  const auto records = b.take_turn_records();
  ASSERT_EQ(records.size(), 1u);
  EXPECT_DOUBLE_EQ(records[0].t_s, 1.6);
  EXPECT_EQ(records[0].value, "AVKTURN/1 a=b");
  EXPECT_EQ(records[0].line, 6u);
  EXPECT_TRUE(b.take_turn_records().empty());
  EXPECT_EQ(b.stats().turn_records, 1u);
}

TEST(AlogNames, RejectsUnknownDuplicateAndEmptyNames) {
  EXPECT_THROW(avk::vehicle::parse_alog_names("NAV_Z=A"), std::invalid_argument);
  EXPECT_THROW(avk::vehicle::parse_alog_names("NAV_X=A,NAV_X=B"), std::invalid_argument);
  EXPECT_THROW(avk::vehicle::parse_alog_names("NAV_X="), std::invalid_argument);
  EXPECT_THROW(avk::vehicle::parse_alog_names("NAV_X"), std::invalid_argument);
  EXPECT_EQ(avk::vehicle::parse_alog_names("").nav_x, "NAV_X");
}

}  // namespace
