#include "kinematics/turn_text.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "kinematics/turn_json.hpp"
#include "support/random_turns.hpp"
#include "support/synthetic_turns.hpp"

namespace avk::kinematics {
namespace {

using testing::example_turn;
using testing::offset_of;

// ---- random turns: the doubles and string pieces the text record finds hard ----

const double kSpecialDoubles[] = {0.1,
                                  -0.0,
                                  0.0,
                                  1e-300,
                                  -1e300,
                                  1e21,
                                  1e22,
                                  123456789012345678.0,
                                  std::numeric_limits<double>::max(),
                                  std::numeric_limits<double>::lowest(),
                                  std::numeric_limits<double>::min(),
                                  std::numeric_limits<double>::denorm_min(),
                                  -std::numeric_limits<double>::denorm_min(),
                                  std::numeric_limits<double>::epsilon(),
                                  9007199254740993.0};

const std::string kStringPieces[] = {"a",          "Z",          "7",
                                     " ",          ";",          "=",
                                     ",",          "|",          "%",
                                     "%20",        "%%",         "\"",
                                     "'",          "\\",         "\n",
                                     "\t",         "\r",         "~",
                                     "/",          "{",          "}",
                                     "[",          "]",          ":",
                                     "é",          "ß",          "→",
                                     "😀",          "日本",       "\x7f",
                                     "AVKTURN/1 ", "n_samples=", std::string(1, '\0')};

const testing::RandomTurnAlphabet kAlphabet{kSpecialDoubles, kStringPieces};

void expect_round_trip(const TurnSequence& turn) {
  testing::expect_exact_round_trip(turn, parse_text_record, to_text_record);
}

const std::string kExampleLine =
    "AVKTURN/1 vehicle_id=m200%20alpha;mission_id=charles%3B2024;status=ok;status_reason=;"
    "normalized=0;commanded_speed_mps=1.5;goal_dheading_deg=90;observed_dheading_deg=88.5;"
    "initial_heading_deg=45;initial_speed_mps=1.5;start_time_s=100;end_time_s=101;n_warnings=1;"
    "warnings=dropped%201%20x;n_samples=3;"
    "samples=100,0,0,45,1.5|100.5,0.53,0.53,60.25,1.49|101,1.1,0.9,133.5,1.5";

// Replaces the first occurrence of `from` (which must exist) in the example line.
std::string example_with(const std::string& from, const std::string& to) {
  return testing::replace_first(kExampleLine, from, to);
}

void expect_parse_error(const std::string& line, const std::string& field, std::size_t position) {
  testing::expect_parse_error_from(parse_text_record, line, field, position);
}

// ---- tests ----

// The initial yaw rate and the speed after travel in the record when a turn has them,
// and a record without them (every older one) reads as it always did.
TEST(TurnText, OptionalYawRateAndSpeedAfterRoundTrip) {
  TurnSequence t = example_turn();
  const std::string plain = to_text_record(t);
  EXPECT_EQ(plain.find("initial_yaw_rate_dps"), std::string::npos);
  EXPECT_FALSE(parse_text_record(plain).meta().initial_yaw_rate_dps);
  t.meta().initial_yaw_rate_dps = -7.25;
  t.meta().speed_after_mps = 0.75;
  const std::string text = to_text_record(t);
  EXPECT_NE(text.find("initial_yaw_rate_dps=-7.25;speed_after_mps=0.75;"), std::string::npos);
  EXPECT_EQ(parse_text_record(text), t);
  t.meta().initial_yaw_rate_dps = std::nan("");
  EXPECT_THROW(to_text_record(t), std::invalid_argument);
  try {
    parse_text_record(plain + ";speed_after_mps=1;speed_after_mps=2");
    FAIL() << "a duplicate optional key must be refused";
  } catch (const ParseError& e) {
    EXPECT_EQ(e.field(), "speed_after_mps");
  }
}

TEST(TurnText, WritesTheDocumentedExample) {
  EXPECT_EQ(to_text_record(example_turn()), kExampleLine);
  const TurnSequence back = parse_text_record(kExampleLine);
  EXPECT_EQ(back, example_turn());
  EXPECT_EQ(back.meta().mission_id, "charles;2024");
  ASSERT_EQ(back.warnings().size(), 1u);
  EXPECT_EQ(back.warnings()[0], "dropped 1 x");
}

TEST(TurnText, RoundTripsRandomTurnsExactly) {
  testing::for_random_turns(20240611, 2000, kAlphabet, expect_round_trip);
}

TEST(TurnText, RoundTripsSpecialDoubles) {
  TurnSequence turn = testing::example_turn_with_special_doubles();
  turn.meta().end_time_s = -std::numeric_limits<double>::min();
  const std::string line = to_text_record(turn);
  EXPECT_NE(line.find("commanded_speed_mps=-0;"), std::string::npos) << line;
  EXPECT_NE(line.find("goal_dheading_deg=1e-300;"), std::string::npos) << line;
  EXPECT_NE(line.find("observed_dheading_deg=0.1;"), std::string::npos) << line;
  const TurnSequence back = parse_text_record(line);
  EXPECT_TRUE(std::signbit(back.meta().commanded_speed_mps));
  EXPECT_EQ(back.meta().initial_speed_mps, std::numeric_limits<double>::denorm_min());
  expect_round_trip(turn);
}

TEST(TurnText, RoundTripsEachStatus) {
  for (const TurnStatus status : {TurnStatus::ok, TurnStatus::aborted, TurnStatus::rejected}) {
    const TurnSequence turn = testing::example_turn_with_status(status, "heading jumped 40% ; =,|");
    expect_round_trip(turn);
    EXPECT_EQ(parse_text_record(to_text_record(turn)).meta().status, status);
  }
}

TEST(TurnText, RoundTripsEmptyTurnAndEmptyStrings) {
  expect_round_trip(TurnSequence{});
  TurnSequence one_empty_warning;
  one_empty_warning.add_warning("");
  expect_round_trip(one_empty_warning);
  EXPECT_EQ(parse_text_record(to_text_record(one_empty_warning)).warnings().size(), 1u);
  TurnSequence two_empty_warnings = one_empty_warning;
  two_empty_warnings.add_warning("");
  EXPECT_EQ(parse_text_record(to_text_record(two_empty_warnings)).warnings().size(), 2u);
}

TEST(TurnText, NormalisedTurnKeepsItsFlag) {
  testing::ArcTurnSpec spec;
  spec.dheading_deg = -120.0;
  spec.start = {10.0, -5.0, 200.0};
  const TurnSequence raw = testing::make_arc_turn(spec);
  const TurnSequence normalised = raw.normalized();
  ASSERT_TRUE(normalised.meta().normalized);
  const TurnSequence back_raw = parse_text_record(to_text_record(raw));
  const TurnSequence back = parse_text_record(to_text_record(normalised));
  EXPECT_FALSE(back_raw.meta().normalized);
  EXPECT_TRUE(back.meta().normalized);
  EXPECT_EQ(back, normalised);
  EXPECT_EQ(back.normalized(), normalised);  // already normalised: not transformed twice
}

TEST(TurnText, AcceptsKeysInAnyOrder) {
  // Move the first pair to the end: the reader must not depend on the writer's order.
  const std::string body = kExampleLine.substr(10);
  const auto semi = body.find(';');
  const std::string line = "AVKTURN/1 " + body.substr(semi + 1) + ";" + body.substr(0, semi);
  EXPECT_EQ(parse_text_record(line), example_turn());
  EXPECT_EQ(to_text_record(parse_text_record(line)), kExampleLine);
}

TEST(TurnText, RejectsWhatNoRecordCanHoldAtSerialisation) {
  for (const double bad :
       {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
        -std::numeric_limits<double>::infinity()}) {
    TurnSequence meta_bad = example_turn();
    meta_bad.meta().goal_dheading_deg = bad;
    EXPECT_THROW(to_text_record(meta_bad), std::invalid_argument);
    TurnMeta m = example_turn().meta();
    TurnSequence sample_bad(m, {{0.0, 1.0, 2.0, bad, 1.0}});
    EXPECT_THROW(to_text_record(sample_bad), std::invalid_argument);
  }
  TurnSequence bad_utf8 = example_turn();
  bad_utf8.meta().vehicle_id = "\xC0\xAF";  // overlong '/'
  EXPECT_THROW(to_text_record(bad_utf8), std::invalid_argument);
  TurnSequence bad_warning = example_turn();
  bad_warning.add_warning("\xED\xA0\x80");  // a UTF-16 surrogate
  EXPECT_THROW(to_text_record(bad_warning), std::invalid_argument);
}

TEST(TurnText, Utf8CheckIsStrict) {
  EXPECT_TRUE(is_valid_utf8(""));
  EXPECT_TRUE(is_valid_utf8("plain"));
  EXPECT_TRUE(is_valid_utf8("é→😀\xF4\x8F\xBF\xBF"));
  EXPECT_FALSE(is_valid_utf8("\x80"));
  EXPECT_FALSE(is_valid_utf8("\xC3"));              // truncated
  EXPECT_FALSE(is_valid_utf8("\xE0\x80\xAF"));      // overlong
  EXPECT_FALSE(is_valid_utf8("\xED\xBF\xBF"));      // surrogate
  EXPECT_FALSE(is_valid_utf8("\xF4\x90\x80\x80"));  // past U+10FFFF
  EXPECT_FALSE(is_valid_utf8("\xF0\x9F\x98"));      // truncated 4-byte
}

TEST(TurnText, RejectsBadPrefixAndVersion) {
  expect_parse_error("", "format", 0);
  expect_parse_error("AVKTURM/1 " + kExampleLine.substr(10), "format", 0);
  expect_parse_error(example_with("AVKTURN/1 ", "AVKTURN/2 "), "version", 8);
  expect_parse_error(example_with("AVKTURN/1 ", "AVKTURN/x "), "version", 8);
  expect_parse_error(example_with("AVKTURN/1 ", "AVKTURN/ "), "version", 8);
  expect_parse_error("AVKTURN/1", "version", 9);
}

TEST(TurnText, RejectsBadKeysNamingThem) {
  const std::string unknown = kExampleLine + ";colour=red";
  expect_parse_error(unknown, "colour", offset_of(unknown, "colour"));
  const std::string duplicate = kExampleLine + ";status=ok";
  expect_parse_error(duplicate, "status", duplicate.rfind("status=ok"));
  const std::string missing = example_with("normalized=0;", "");
  expect_parse_error(missing, "normalized", missing.size());
  const std::string no_equals = example_with("normalized=0;", "normalized;");
  expect_parse_error(no_equals, "record", offset_of(no_equals, "normalized;"));
  const std::string empty_pair = example_with(";normalized=0;", ";;normalized=0;");
  expect_parse_error(empty_pair, "record", offset_of(empty_pair, ";;") + 1);
  const std::string empty_key = example_with(";normalized=0;", ";=0;normalized=0;");
  expect_parse_error(empty_key, "record", offset_of(empty_key, ";=0;") + 1);
  expect_parse_error(kExampleLine + ";", "record", kExampleLine.size() + 1);
}

TEST(TurnText, RejectsBadNumbersAtTheOffendingByte) {
  const auto value_at = [](const std::string& line, const std::string& key) {
    return offset_of(line, key + "=") + key.size() + 1;
  };
  for (const std::string bad : {"", "x", "nan", "inf", "-inf", "infinity", "1e400", "+1", " 1"}) {
    const std::string line =
        example_with("goal_dheading_deg=90;", "goal_dheading_deg=" + bad + ";");
    expect_parse_error(line, "goal_dheading_deg", value_at(line, "goal_dheading_deg"));
  }
  const std::string junk = example_with("goal_dheading_deg=90;", "goal_dheading_deg=1.5x;");
  expect_parse_error(junk, "goal_dheading_deg", value_at(junk, "goal_dheading_deg") + 3);
  const std::string hex = example_with("start_time_s=100;", "start_time_s=0x10;");
  expect_parse_error(hex, "start_time_s", value_at(hex, "start_time_s") + 1);
}

TEST(TurnText, RejectsBadEnumsAndFlags) {
  const std::string status = example_with("status=ok;", "status=maybe;");
  expect_parse_error(status, "status", offset_of(status, "maybe"));
  const std::string encoded = example_with("status=ok;", "status=%6Fk;");
  expect_parse_error(encoded, "status", offset_of(encoded, "%6Fk"));
  const std::string flag = example_with("normalized=0;", "normalized=true;");
  expect_parse_error(flag, "normalized", offset_of(flag, "true"));
}

TEST(TurnText, RejectsBadStrings) {
  const std::string bad_hex = example_with("m200%20alpha", "m200%2Galpha");
  expect_parse_error(bad_hex, "vehicle_id", offset_of(bad_hex, "%2G"));
  const std::string cut = example_with("m200%20alpha", "m200alpha%2");
  expect_parse_error(cut, "vehicle_id", offset_of(cut, "%2;"));
  const std::string raw_space = example_with("m200%20alpha", "m200 alpha");
  expect_parse_error(raw_space, "vehicle_id", offset_of(raw_space, " alpha"));
  const std::string raw_equals = example_with("m200%20alpha", "m200=alpha");
  expect_parse_error(raw_equals, "vehicle_id", offset_of(raw_equals, "=alpha"));
  const std::string raw_utf8 = example_with("m200%20alpha", "m200\xC3\xA9");
  expect_parse_error(raw_utf8, "vehicle_id", offset_of(raw_utf8, "\xC3"));
  const std::string bad_utf8 = example_with("m200%20alpha", "m200%FF");
  expect_parse_error(bad_utf8, "vehicle_id", offset_of(bad_utf8, "m200%FF"));
  const std::string nl = kExampleLine + "\n";
  expect_parse_error(nl, "samples", kExampleLine.size());
  const std::string bad_warning = example_with("dropped%201%20x", "dropped%2");
  expect_parse_error(bad_warning, "warnings[0]", offset_of(bad_warning, "%2;"));
}

TEST(TurnText, RejectsBadCounts) {
  const std::string more = example_with("n_samples=3", "n_samples=4");
  expect_parse_error(more, "samples", more.size());
  const std::string fewer = example_with("n_samples=3", "n_samples=2");
  expect_parse_error(fewer, "samples", offset_of(fewer, "101,1.1"));
  const std::string zero = example_with("n_samples=3", "n_samples=0");
  expect_parse_error(zero, "samples", offset_of(zero, ";samples=") + 9);
  // The declared count is checked against the limit before anything is sized from it.
  const std::string huge = example_with("n_samples=3", "n_samples=1000001");
  expect_parse_error(huge, "n_samples", offset_of(huge, "1000001"));
  const std::string overflow = example_with("n_samples=3", "n_samples=99999999999999999999999");
  expect_parse_error(overflow, "n_samples", offset_of(overflow, "9999"));
  const std::string negative = example_with("n_samples=3", "n_samples=-3");
  expect_parse_error(negative, "n_samples", offset_of(negative, "-3"));
  const std::string junk = example_with("n_samples=3", "n_samples=3x");
  expect_parse_error(junk, "n_samples", offset_of(junk, "x;samples"));
  const std::string warnings = example_with("n_warnings=1", "n_warnings=2");
  expect_parse_error(warnings, "warnings", offset_of(warnings, ";n_samples"));
  const std::string too_many_warnings = example_with("n_warnings=1", "n_warnings=10001");
  expect_parse_error(too_many_warnings, "n_warnings", offset_of(too_many_warnings, "10001"));
}

TEST(TurnText, RejectsBadSamples) {
  const std::string short_sample =
      example_with("100.5,0.53,0.53,60.25,1.49", "100.5,0.53,0.53,60.25");
  expect_parse_error(short_sample, "samples[1]", offset_of(short_sample, "100.5"));
  const std::string long_sample =
      example_with("100.5,0.53,0.53,60.25,1.49", "100.5,0.53,0.53,60.25,1.49,7");
  expect_parse_error(long_sample, "samples[1]", offset_of(long_sample, "100.5"));
  const std::string empty_value =
      example_with("100.5,0.53,0.53,60.25,1.49", "100.5,0.53,,60.25,1.49");
  expect_parse_error(empty_value, "samples[1].y_m", offset_of(empty_value, ",,") + 1);
  const std::string junk =
      example_with("100.5,0.53,0.53,60.25,1.49", "100.5,0.53,0.53,60.25x,1.49");
  expect_parse_error(junk, "samples[1].heading_deg", offset_of(junk, "x,1.49"));
  const std::string nan = example_with("101,1.1,0.9,133.5,1.5", "101,1.1,0.9,133.5,nan");
  expect_parse_error(nan, "samples[2].speed_mps", offset_of(nan, "nan"));
  const std::string trailing_bar = kExampleLine + "|";
  expect_parse_error(trailing_bar, "samples", trailing_bar.size());
  const std::string empty_sample = example_with("1.5|100.5", "1.5||100.5");
  expect_parse_error(empty_sample, "samples[1]", offset_of(empty_sample, "||") + 1);
}

TEST(TurnText, RejectsOverlongLineBeforeReadingIt) {
  std::string line = kExampleLine;
  line.resize(kMaxTurnRecordBytes + 1, '0');
  expect_parse_error(line, "record", kMaxTurnRecordBytes);
}

TEST(TurnText, RejectsOversizedTurnAtSerialisation) {
  TurnSequence many_warnings;
  for (std::size_t i = 0; i <= kMaxTurnRecordWarnings; ++i)
    many_warnings.add_warning("w");
  EXPECT_THROW(to_text_record(many_warnings), std::invalid_argument);
}

// ---- mutation robustness: a cheap stand-in for the libFuzzer target in tests/fuzz ----

const std::string kMutationInserts[] = {";",
                                        "=",
                                        ",",
                                        "|",
                                        "%",
                                        " ",
                                        "\n",
                                        std::string(1, '\0'),
                                        "\xFF",
                                        "%ZZ",
                                        "n_samples=",
                                        "samples=",
                                        "99999999999999999999",
                                        "-",
                                        "e",
                                        "nan",
                                        "inf",
                                        "1e400",
                                        ";status=ok"};

TEST(TurnTextMutation, MutatedRecordsParseOrThrowParseErrorOnly) {
  const testing::MutationOutcome outcome = testing::run_mutations(
      7, {kExampleLine, to_text_record(TurnSequence{})}, kAlphabet, kMutationInserts, 20000,
      parse_text_record, to_text_record, parse_turn_json, to_json_string);
  // Both outcomes must occur or the mutations are not exercising the parser.
  EXPECT_GT(outcome.accepted, 100);
  EXPECT_GT(outcome.rejected, 10000);
}

}  // namespace
}  // namespace avk::kinematics
