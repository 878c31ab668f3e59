// The frontseat protocol parser's framing: checksums, line endings, size, characters and address,
// the checksum rules of the two directions, and random mutations that must never crash it.
#include <gtest/gtest.h>

#include "vehicle/nmea_lines.hpp"

namespace {

using namespace avk::testing::nmea_lines;

// ---- Checksums and framing ------------------------------------------------------------------

TEST(NmeaChecksum, XorsTheBytesBetweenDollarAndStar) {
  EXPECT_EQ(nmea_checksum(""), 0);
  EXPECT_EQ(nmea_checksum("A"), 0x41);
  EXPECT_EQ(nmea_checksum("AA"), 0);
  EXPECT_EQ(nmea_checksum("GPGSA,A,3,29,02,26,05,13,15,,,,,,,4.45,2.80,3.46"), 0x02);
  EXPECT_EQ(nmea_checksum("PYDIR,0,0"), 0x56);
  EXPECT_EQ(nmea_checksum("PYDIR,0,0"), nmea_checksum("PYDIR"));  // ",0" twice cancels out
  for (const char* line : kRealLines) {
    const std::string_view s(line);
    const std::size_t star = s.find('*');
    EXPECT_EQ(nmea_checksum(s.substr(1, star - 1)),
              std::stoi(std::string(s.substr(star + 1)), nullptr, 16))
        << line;
  }
}

TEST(NmeaParse, RealFrontseatOutputParses) {
  for (const char* line : kRealLines) {
    const NmeaParseResult r = parse_sentence(line, kFromFrontseat);
    ASSERT_TRUE(r.ok()) << line << ": " << r.error()->message;
    EXPECT_EQ(r.checksum, NmeaChecksum::upper_case);
  }
}

TEST(NmeaParse, StripsTrailingLineEndings) {
  for (const char* ending : {"", "\r\n", "\n", "\r", "\r\n\r\n", "\n\r"}) {
    const std::string line = std::string(kRealCpnvr) + ending;
    const Cpnvr s = parse_as<Cpnvr>(line);
    EXPECT_DOUBLE_EQ(s.yaw_rate_dps, -0.061132) << "ending of " << std::string_view(ending).size();
  }
  // A line ending inside the sentence is not a line ending.
  expect_error("$PYDIR,1\r\n,2*00", Code::bad_character, 0, "0x0D");
}

TEST(NmeaParse, EmptyLines) {
  for (const char* line : {"", "\r\n", "\n", "\r\r\n"})
    expect_error(line, Code::empty, 0);
}

TEST(NmeaParse, MissingDollar) {
  expect_error("GPRMC,,V,,,,,,,,,,N*53", Code::no_dollar, 0);
  expect_error(" $PYDIR,0,0*56", Code::no_dollar, 0);
  expect_error("!AIVDM,1,1,,A,13aEOK?P00PD2wVMdLDRhgvL289?,0*26", Code::no_dollar, 0);
  expect_error("*", Code::no_dollar, 0);
}

TEST(NmeaParse, OversizedLines) {
  // An unknown sentence padded to exactly the limit parses; one byte more does not. The line
  // ending does not count.
  const std::string head = "CPXXX,";
  std::string body = head + std::string(kNmeaMaxLineBytes - 4 - head.size(), '7');
  const std::string at_limit = sentence(body);
  ASSERT_EQ(at_limit.size(), kNmeaMaxLineBytes + 2);
  EXPECT_TRUE(parse_sentence(at_limit, kFromFrontseat).ok());
  expect_error(sentence(body + "7"), Code::oversized, 0, "257");
  // Without a checksum, a backseat line counts the three bytes the checksum would take.
  EXPECT_TRUE(parse_sentence("$" + body, kToFrontseat).ok());
  expect_error("$" + body + "7", Code::oversized, 0, "257", kToFrontseat);
  expect_error("$" + body + "7*", Code::oversized, 0, "257", kToFrontseat);
  expect_error("$" + std::string(1 << 20, 'A'), Code::oversized, 0);
  expect_error(std::string(1000, '\0'), Code::oversized, 0);
}

TEST(NmeaParse, BadCharacters) {
  std::string with_nul = "$PYDIR,1,2*00";
  with_nul[8] = '\0';
  expect_error(with_nul, Code::bad_character, 0, "0x00");
  expect_error("$PYDIR,1,\xff*00", Code::bad_character, 0, "0xFF");
  expect_error("$PYDIR,1,\t2*00", Code::bad_character, 0, "0x09");
  // Two sentences run together (a lost line ending).
  expect_error("$PYDIR,1,2$PYDIR,1,2*00", Code::bad_character, 0, "0x24");
}

TEST(NmeaParse, BadAddress) {
  expect_error(sentence("gprmc,,V,,,,,,,,,,N"), Code::bad_address, 0, "gprmc");
  expect_error(sentence(",1,2"), Code::bad_address, 0);
  expect_error(sentence("P,1,2"), Code::bad_address, 0);
  expect_error(sentence("PYDIR ,1,2"), Code::bad_address, 0);
  expect_error(sentence("ABCDEFGHIJK,1"), Code::bad_address, 0);
  expect_error(sentence(""), Code::bad_address, 0);
}

// ---- Checksum rules per direction -----------------------------------------------------------

TEST(NmeaParse, FrontseatSentencesNeedAChecksum) {
  expect_error("$CPNVR,164959.063,0.02941,-0.068552,0,0.060938,0,-0.061132", Code::missing_checksum,
               0);
  expect_error("$CPNVR,164959.063,0.02941,-0.068552,0,0.060938,0,-0.061132*",
               Code::missing_checksum, 0);
  expect_error("$PYDIR,0,0\r\n", Code::missing_checksum, 0);
}

TEST(NmeaParse, ChecksumMustMatchInBothDirections) {
  for (NmeaDirection d : {kFromFrontseat, kToFrontseat}) {
    expect_error("$CPNVR,164959.063,0.02941,-0.068552,0,0.060938,0,-0.061132*58",
                 Code::bad_checksum, 0, "59", d);
    expect_error("$PYDIR,0,0*57", Code::bad_checksum, 0, "56", d);
    expect_error("$PYDIR,0,0*5", Code::bad_checksum, 0, "two hex digits", d);
    expect_error("$PYDIR,0,0*560", Code::bad_checksum, 0, "two hex digits", d);
    expect_error("$PYDIR,0,0*G6", Code::bad_checksum, 0, "two hex digits", d);
    expect_error("$PYDIR,0,0* 56", Code::bad_checksum, 0, "two hex digits", d);
    expect_error("$PYDIR,0,0*56*56", Code::bad_checksum, 0, "two hex digits", d);
  }
}

TEST(NmeaParse, LowerCaseChecksumIsAcceptedAndNoted) {
  const NmeaParseResult r =
      parse_sentence("$GPVTG,156.78,T,,M,0.145,N,0.269,K,A*3d\r\n", kFromFrontseat);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r.checksum, NmeaChecksum::lower_case);
  const NmeaParseResult upper = parse_sentence(kRealGpvtg, kFromFrontseat);
  EXPECT_EQ(upper.checksum, NmeaChecksum::upper_case);
  EXPECT_EQ(*r.sentence(), *upper.sentence());
  expect_error("$GPVTG,156.78,T,,M,0.145,N,0.269,K,A*3e", Code::bad_checksum, 0);
}

TEST(NmeaParse, BackseatSentencesMayOmitTheChecksum) {
  // As older drivers sent them: no digits after `*`, or no `*` at all.
  const NmeaParseResult blank = parse_sentence("$PYDIR,25.5,-40*\r\n", kToFrontseat);
  ASSERT_TRUE(blank.ok());
  EXPECT_EQ(blank.checksum, NmeaChecksum::blank);
  EXPECT_EQ(std::get<Pydir>(*blank.sentence()), (Pydir{25.5, -40.0}));
  const NmeaParseResult absent = parse_sentence("$PYDIR,25.5,-40", kToFrontseat);
  ASSERT_TRUE(absent.ok());
  EXPECT_EQ(absent.checksum, NmeaChecksum::absent);
  const NmeaParseResult present = parse_sentence(sentence("PYDIR,25.5,-40"), kToFrontseat);
  ASSERT_TRUE(present.ok());
  EXPECT_EQ(present.checksum, NmeaChecksum::upper_case);
  // The frontseat holds its own sentences to the stricter rule.
  expect_error("$PYDIR,25.5,-40*", Code::missing_checksum, 0);
}

// ---- Hostile input --------------------------------------------------------------------------

// Random mutations of valid sentences: byte flips, insertions, deletions, truncations, swaps,
// spliced delimiters and field garbage, half of them with the checksum fixed afterwards so the
// field parsers see them too. Nothing may throw or crash, and every result is a sentence or an
// error; an accepted sentence writes and reads back as the same type.
TEST(NmeaParse, RandomMutationsNeverCrash) {
  std::vector<std::string> seeds(std::begin(kRealLines), std::end(kRealLines));
  for (const char* body :
       {"PYDIR,-12.5,40", "PYDEV,270,1.5", "PYDEP,-3,50", "PYCLT,1", "CPALT,101010,1",
        "CPRBS,150218.154,2,15.2,14.9,15.4,31.5", "GNRMC,,V,,,,,,,,,,N",
        "GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230394,003.1,W",
        "GNRMC,001031.00,A,4404.13993,N,12118.86023,W,0.146,,100117,,,A,V",
        "GPGGA,,,,,,0,00,99.99,,,,,,", "GPVTG,054.7,T,034.4,M,005.5,N,010.2,K"})
    seeds.push_back(sentence(body));
  const std::string specials = ",*$.-+0123456789ENSWAV\r\n";

  std::mt19937_64 rng(8);
  auto below = [&](std::size_t n) {
    return n == 0 ? std::size_t{0} : std::uniform_int_distribution<std::size_t>(0, n - 1)(rng);
  };
  std::size_t parsed = 0, failed = 0, thrown = 0;
  std::size_t codes[16] = {};
  for (int i = 0; i < 100000; ++i) {
    std::string s = seeds[below(seeds.size())];
    const std::size_t mutations = 1 + below(4);
    for (std::size_t m = 0; m < mutations; ++m) {
      const std::size_t at = below(s.size() + 1);
      const char byte = static_cast<char>(below(256));
      const char special = specials[below(specials.size())];
      switch (below(8)) {
        case 0:
          if (at < s.size()) s[at] = byte;
          break;
        case 1:
          s.insert(s.begin() + static_cast<std::ptrdiff_t>(at), special);
          break;
        case 2:
          if (at < s.size()) s.erase(at, 1 + below(4));
          break;
        case 3:
          s.resize(at);
          break;
        case 4:
          if (at < s.size()) std::swap(s[at], s[below(s.size())]);
          break;
        case 5:
          if (at < s.size()) s[at] = special;
          break;
        case 6:  // a field's digits into something else
          s.insert(at, std::string(1 + below(12), "9.-e"[below(4)]));
          break;
        case 7:
          s.insert(at, s.substr(below(s.size()), below(40)));
          break;
      }
    }
    if (below(2) == 0) {
      // Fix the checksum so the mutation reaches the field parsers.
      const std::size_t star = s.find('*');
      if (!s.empty() && s[0] == '$' && star != std::string::npos) {
        char sum[4];
        std::snprintf(
            sum, sizeof sum, "%02X",
            static_cast<unsigned>(nmea_checksum(std::string_view(s).substr(1, star - 1))));
        s.replace(star + 1, std::min<std::size_t>(2, s.size() - star - 1), sum);
      }
    }
    for (NmeaDirection d : {kFromFrontseat, kToFrontseat}) {
      try {
        const NmeaParseResult r = parse_sentence(s, d);
        ASSERT_FALSE(r.value.valueless_by_exception());
        if (const NmeaError* e = r.error()) {
          ++failed;
          ++codes[static_cast<int>(e->code)];
          ASSERT_FALSE(e->message.empty());
          ASSERT_LE(e->field, 16u) << e->message;
        } else {
          ++parsed;
          ASSERT_FALSE(r.sentence()->valueless_by_exception());
          const std::string again = format_sentence(*r.sentence());
          const NmeaParseResult back = parse_sentence(again, kFromFrontseat);
          ASSERT_TRUE(back.ok()) << s << " -> " << again;
          ASSERT_EQ(back.sentence()->index(), r.sentence()->index()) << s << " -> " << again;
          ASSERT_EQ(format_sentence(*back.sentence()), again) << s;
        }
      } catch (const std::exception& e) {
        ++thrown;
        ADD_FAILURE() << "threw on '" << s << "': " << e.what();
      }
    }
  }
  RecordProperty("parsed", static_cast<int>(parsed));
  RecordProperty("failed", static_cast<int>(failed));
  EXPECT_EQ(thrown, 0u);
  EXPECT_EQ(parsed + failed, 200000u);
  // Both outcomes are common, and the field-level errors are reached, not only the framing.
  EXPECT_GT(parsed, 10000u);
  EXPECT_GT(failed, 50000u);
  for (Code c : {Code::bad_checksum, Code::bad_field_count, Code::non_numeric, Code::out_of_range,
                 Code::missing_field, Code::bad_value, Code::bad_character})
    EXPECT_GT(codes[static_cast<int>(c)], 100u) << to_string(c);
}

TEST(NmeaError, CodesHaveNames) {
  EXPECT_STREQ(to_string(Code::bad_checksum), "bad_checksum");
  EXPECT_STREQ(to_string(Code::out_of_range), "out_of_range");
  EXPECT_STREQ(to_string(Code::empty), "empty");
}

}  // namespace
