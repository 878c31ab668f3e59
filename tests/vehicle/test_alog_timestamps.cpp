// Regression: one implausible timestamp discarded the rest of a log. Now the line is refused and
// counted with its number, and the time it claims never becomes "the newest".
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "vehicle/alog.hpp"

namespace {

using avk::vehicle::AlogEntry;
using avk::vehicle::AlogNavBuilder;
using avk::vehicle::AlogReader;
using avk::vehicle::GuidedNav;

struct Built {
  std::vector<GuidedNav> samples;
  avk::vehicle::AlogProblems malformed;  // reader's and builder's together
};

Built build(const std::string& text) {
  std::istringstream in(text);
  AlogReader reader(in);
  AlogNavBuilder builder;
  Built out;
  AlogEntry e;
  GuidedNav s;
  while (reader.next(e))
    if (builder.feed(e, s)) out.samples.push_back(s);
  if (builder.finish(s)) out.samples.push_back(s);
  out.malformed = reader.stats().malformed;
  out.malformed.merge(builder.stats().malformed);
  return out;
}

// `n` navigation groups, one a second from t = 1 s, three postings each.
std::string nav_log(int n, int bad_after, const std::string& bad_line) {
  std::string text = "%% LOGSTART 1000\n";
  for (int i = 1; i <= n; ++i) {
    const std::string t = std::to_string(i);
    text += t + " NAV_X a " + t + "\n" + t + " NAV_Y a 0\n" + t + " NAV_HEADING a 90\n";
    if (i == bad_after) text += bad_line + "\n";
  }
  return text;
}

}  // namespace

TEST(AlogTimestamps, OneLineStampedAtTheEndOfTimeIsRefusedAndTheLogKept) {
  // The line; it is line 1 + 3 * 10 + 1 = 32.
  const Built b = build(nav_log(100, 10, "1e308 NAV_X a 1"));
  EXPECT_EQ(b.samples.size(), 100u);
  EXPECT_EQ(b.malformed.count, 1u);
  ASSERT_EQ(b.malformed.first.size(), 1u);
  EXPECT_EQ(b.malformed.first[0].line, 32u);
  for (std::size_t i = 0; i < b.samples.size(); ++i)
    EXPECT_EQ(b.samples[i].nav.t_s, static_cast<double>(i + 1));
}

TEST(AlogTimestamps, AFarFutureFirstPostingDoesNotHideTheLog) {
  std::string text = "1e9 NAV_X a 1\n" + nav_log(20, 0, "");
  const Built b = build(text);
  EXPECT_EQ(b.samples.size(), 20u);
  EXPECT_EQ(b.malformed.count, 1u);
  ASSERT_EQ(b.malformed.first.size(), 1u);
  EXPECT_EQ(b.malformed.first[0].line, 1u);
}

TEST(AlogTimestamps, ANegativeTimeIsRefused) {
  const Built b = build(nav_log(20, 5, "-1e308 NAV_Y a 1"));
  EXPECT_EQ(b.samples.size(), 20u);
  EXPECT_EQ(b.malformed.count, 1u);
}

TEST(AlogTimestamps, ARealGapOfAnHourIsKept) {
  // Logging paused and resumed within a run: an hour's silence is plausible and kept.
  std::string text = nav_log(5, 0, "");
  text += "3605 NAV_X a 1\n3605 NAV_Y a 1\n3605 NAV_HEADING a 1\n";
  text += "3606 NAV_X a 1\n3606 NAV_Y a 1\n3606 NAV_HEADING a 1\n";
  const Built b = build(text);
  EXPECT_EQ(b.samples.size(), 7u);
  EXPECT_EQ(b.malformed.count, 0u);
}
