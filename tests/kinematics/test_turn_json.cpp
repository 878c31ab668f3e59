#include "kinematics/turn_json.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "kinematics/turn_text.hpp"
#include "support/random_turns.hpp"
#include "support/synthetic_turns.hpp"

namespace avk::kinematics {
namespace {

using nlohmann::json;

using testing::example_turn;
using testing::offset_of;

// ---- random turns: the doubles and string pieces JSON finds hard ----

const double kSpecialDoubles[] = {0.1,
                                  -0.0,
                                  1e-300,
                                  1e21,
                                  123456789012345678.0,
                                  std::numeric_limits<double>::max(),
                                  std::numeric_limits<double>::lowest(),
                                  std::numeric_limits<double>::min(),
                                  std::numeric_limits<double>::denorm_min(),
                                  9007199254740993.0};

const std::string kStringPieces[] = {
    "a", "Z", "7", " ",  "\"", "\\",   "\\u0000", "/", "~", "{", "}", "[",    "]",
    ":", ",", "%", "\n", "\t", "\x1f", "\x7f",    "é", "ß", "→", "😀", "日本", std::string(1, '\0')};

const testing::RandomTurnAlphabet kAlphabet{kSpecialDoubles, kStringPieces};

void expect_round_trip(const TurnSequence& turn) {
  testing::expect_exact_round_trip(turn, parse_turn_json, to_json_string);
  EXPECT_EQ(turn_from_json(to_json(turn)), turn);
}

const std::string kExampleJson =
    R"({"commanded_speed_mps":1.5,"end_time_s":101.0,"format":"avk-turn",)"
    R"("goal_dheading_deg":90.0,"initial_heading_deg":45.0,"initial_speed_mps":1.5,)"
    R"("mission_id":"charles;2024","normalized":false,"observed_dheading_deg":88.5,)"
    R"("sample_fields":["t_s","x_m","y_m","heading_deg","speed_mps"],)"
    R"("samples":[[100.0,0.0,0.0,45.0,1.5],[100.5,0.53,0.53,60.25,1.49],)"
    R"([101.0,1.1,0.9,133.5,1.5]],"start_time_s":100.0,"status":"ok","status_reason":"",)"
    R"("vehicle_id":"m200 alpha","version":1,"warnings":["dropped 1 x"]})";

std::string example_with(const std::string& from, const std::string& to) {
  return testing::replace_first(kExampleJson, from, to);
}

void expect_text_error(const std::string& text, const std::string& field, std::size_t position) {
  testing::expect_parse_error_from(parse_turn_json, text, field, position);
}

// Checks the document both as parsed text and as an in-memory json handed to turn_from_json.
void expect_document_error(const json& j, const std::string& field, std::size_t position) {
  try {
    turn_from_json(j);
    ADD_FAILURE() << "accepted: " << j.dump();
  } catch (const ParseError& e) {
    EXPECT_EQ(e.field(), field) << e.what();
    EXPECT_EQ(e.position(), position) << e.what();
  }
  // A json holding NaN dumps it as null, which the parser then reports as not a number.
  expect_text_error(j.dump(), field, position);
}

json example_json() {
  return to_json(example_turn());
}

// ---- tests ----

TEST(TurnJson, WritesTheDocumentedExample) {
  EXPECT_EQ(to_json_string(example_turn()), kExampleJson);
  const TurnSequence back = parse_turn_json(kExampleJson);
  EXPECT_EQ(back, example_turn());
  EXPECT_EQ(back.warnings(), example_turn().warnings());
  EXPECT_EQ(example_json()["format"], "avk-turn");
  EXPECT_EQ(example_json()["version"], 1);
}

TEST(TurnJson, RoundTripsRandomTurnsExactly) {
  testing::for_random_turns(424242, 2000, kAlphabet, expect_round_trip);
}

TEST(TurnJson, RoundTripsSpecialDoubles) {
  TurnSequence turn = testing::example_turn_with_special_doubles();
  turn.meta().end_time_s = 1e300;
  const std::string text = to_json_string(turn);
  EXPECT_NE(text.find(R"("commanded_speed_mps":-0.0,)"), std::string::npos) << text;
  EXPECT_NE(text.find(R"("goal_dheading_deg":1e-300,)"), std::string::npos) << text;
  EXPECT_NE(text.find(R"("observed_dheading_deg":0.1,)"), std::string::npos) << text;
  EXPECT_TRUE(std::signbit(parse_turn_json(text).meta().commanded_speed_mps));
  expect_round_trip(turn);
}

TEST(TurnJson, RoundTripsEachStatusAndEmptyTurn) {
  for (const TurnStatus status : {TurnStatus::ok, TurnStatus::aborted, TurnStatus::rejected}) {
    const TurnSequence turn = testing::example_turn_with_status(status, "lost \"GPS\"\n\\ fix");
    expect_round_trip(turn);
    EXPECT_EQ(parse_turn_json(to_json_string(turn)).meta().status, status);
  }
  expect_round_trip(TurnSequence{});
  TurnSequence empty_warning;
  empty_warning.add_warning("");
  expect_round_trip(empty_warning);
}

TEST(TurnJson, NormalisedTurnKeepsItsFlag) {
  testing::ArcTurnSpec spec;
  spec.dheading_deg = -75.0;
  spec.start = {-3.0, 8.0, 310.0};
  const TurnSequence normalised = testing::make_arc_turn(spec).normalized();
  ASSERT_TRUE(normalised.meta().normalized);
  EXPECT_EQ(to_json(normalised)["normalized"], true);
  const TurnSequence back = parse_turn_json(to_json_string(normalised));
  EXPECT_TRUE(back.meta().normalized);
  EXPECT_EQ(back, normalised);
}

TEST(TurnJson, AcceptsIntegersAndAnyKeyOrderAndWhitespace) {
  const std::string text = example_with(R"("goal_dheading_deg":90.0)", R"("goal_dheading_deg":90)");
  EXPECT_EQ(parse_turn_json(text), example_turn());
  EXPECT_EQ(parse_turn_json(" \n" + example_json().dump(2) + "\n"), example_turn());
}

TEST(TurnJson, RejectsWhatJsonCannotHoldAtSerialisation) {
  for (const double bad :
       {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
        -std::numeric_limits<double>::infinity()}) {
    TurnSequence meta_bad = example_turn();
    meta_bad.meta().end_time_s = bad;
    EXPECT_THROW(to_json(meta_bad), std::invalid_argument);
    EXPECT_THROW(to_json_string(meta_bad), std::invalid_argument);
    TurnSequence sample_bad(example_turn().meta(), {{0.0, bad, 2.0, 3.0, 1.0}});
    EXPECT_THROW(to_json_string(sample_bad), std::invalid_argument);
  }
  TurnSequence bad_utf8 = example_turn();
  bad_utf8.meta().status_reason = "\xFF";
  EXPECT_THROW(to_json_string(bad_utf8), std::invalid_argument);
}

TEST(TurnJson, SyntaxErrorsGiveByteOffsets) {
  expect_text_error("", "json", 0);
  expect_text_error("{", "json", 1);
  const std::string bad_value = example_with(R"("status":"ok")", R"("status":ok)");
  expect_text_error(bad_value, "json", offset_of(bad_value, R"(ok,"status_reason")"));
  expect_text_error(kExampleJson + " x", "json", kExampleJson.size() + 1);
  expect_text_error(kExampleJson + "{}", "json", kExampleJson.size());
  const std::string truncated = kExampleJson.substr(0, kExampleJson.size() - 1);
  expect_text_error(truncated, "json", truncated.size());
  const std::string trailing_comma = example_with(R"("dropped 1 x"])", R"("dropped 1 x",])");
  expect_text_error(trailing_comma, "json", offset_of(trailing_comma, ",]") + 1);
  const std::string overflow = example_with(R"("end_time_s":101.0)", R"("end_time_s":1e400)");
  expect_text_error(overflow, "json", offset_of(overflow, "1e400") + 4);
  const std::string bad_utf8 = example_with("m200 alpha", "m200\xFF");
  expect_text_error(bad_utf8, "json", offset_of(bad_utf8, "\xFF"));
  const std::string nan = example_with(R"("end_time_s":101.0)", R"("end_time_s":NaN)");
  expect_text_error(nan, "json", offset_of(nan, "NaN"));
}

TEST(TurnJson, RejectsDuplicateKeysAndDeepNestingWhileParsing) {
  const std::string duplicate = "{\"status\":\"ok\"," + kExampleJson.substr(1);
  expect_text_error(duplicate, "/status", 0);
  const std::string nested_duplicate =
      example_with("[100.5,0.53,0.53,60.25,1.49]", R"({"a":1,"a":2})");
  expect_text_error(nested_duplicate, "/samples/1/a", 1);
  const std::string deep = example_with("[100.5,0.53,0.53,60.25,1.49]", "[1,[2]]");
  expect_text_error(deep, "/samples/1/1", 1);
  expect_text_error("[[[[[[[[[[[[[[[[[[[[[[[[[[[[", "/0/0/0", 0);
  expect_text_error(R"({"warnings":[[{}]]})", "/warnings/0/0", 0);
  const std::string slash_key = R"({"a/b~":1,"a/b~":2})";
  expect_text_error(slash_key, "/a~1b~0", 0);
}

TEST(TurnJson, RejectsOversizedArraysWhileParsing) {
  std::string text = R"({"samples":[)";
  for (std::size_t i = 0; i < kMaxTurnRecordSamples; ++i)
    text += "[],";
  text += "[]]}";
  expect_text_error(text, "/samples/" + std::to_string(kMaxTurnRecordSamples),
                    kMaxTurnRecordSamples);
  std::string too_long = kExampleJson;
  too_long.resize(kMaxTurnRecordBytes + 1, ' ');
  expect_text_error(too_long, "json", kMaxTurnRecordBytes);
}

TEST(TurnJson, RejectsWrongKindOfDocument) {
  expect_document_error(json::array(), "", 0);
  expect_document_error(json(), "", 0);
  json j = example_json();
  j["format"] = "avk-ckt";
  expect_document_error(j, "/format", 0);
  j = example_json();
  j.erase("format");
  expect_document_error(j, "/format", 0);
  for (const json& version : {json(2), json("1"), json(1.0), json(-1), json(nullptr)}) {
    j = example_json();
    j["version"] = version;
    expect_document_error(j, "/version", 0);
  }
}

TEST(TurnJson, RejectsUnknownAndMissingKeys) {
  json j = example_json();
  j["colour"] = "red";
  expect_document_error(j, "/colour", 0);
  for (const char* key : {"vehicle_id", "normalized", "end_time_s", "warnings", "sample_fields",
                          "samples", "status_reason"}) {
    j = example_json();
    j.erase(key);
    expect_document_error(j, std::string("/") + key, 0);
  }
}

TEST(TurnJson, RejectsWrongTypesAndValues) {
  const auto with = [](const char* key, json value) {
    json j = example_json();
    j[key] = std::move(value);
    return j;
  };
  expect_document_error(with("vehicle_id", 7), "/vehicle_id", 0);
  expect_document_error(with("status", "maybe"), "/status", 0);
  expect_document_error(with("status", "OK"), "/status", 0);
  expect_document_error(with("normalized", 1), "/normalized", 0);
  expect_document_error(with("commanded_speed_mps", "1.5"), "/commanded_speed_mps", 0);
  expect_document_error(with("commanded_speed_mps", true), "/commanded_speed_mps", 0);
  expect_document_error(with("end_time_s", std::numeric_limits<double>::quiet_NaN()), "/end_time_s",
                        0);
  expect_document_error(with("warnings", json::array({"ok", 3})), "/warnings/1", 0);
  expect_document_error(with("warnings", "one"), "/warnings", 0);
  expect_document_error(with("sample_fields", json::array({"x_m", "t_s"})), "/sample_fields", 0);
  expect_document_error(with("samples", json::object()), "/samples", 0);
  json j = example_json();
  j["warnings"][0] = "\xC0\x80";  // an overlong NUL, only possible in a json built in memory
  EXPECT_THROW(turn_from_json(j), ParseError);
}

TEST(TurnJson, RejectsBadSamplesWithTheirIndex) {
  json j = example_json();
  j["samples"][1] = json::array({1.0, 2.0, 3.0, 4.0});
  expect_document_error(j, "/samples/1", 1);
  j = example_json();
  j["samples"][2].push_back(6.0);
  expect_document_error(j, "/samples/2", 2);
  j = example_json();
  j["samples"][1] = 5.0;
  expect_document_error(j, "/samples/1", 1);
  j = example_json();
  j["samples"][2][3] = "60";
  expect_document_error(j, "/samples/2/3", 2);
  j = example_json();
  j["samples"][0][4] = nullptr;
  expect_document_error(j, "/samples/0/4", 0);
  j = example_json();
  j["samples"][2][0] = std::numeric_limits<double>::infinity();
  expect_document_error(j, "/samples/2/0", 2);
}

// ---- mutation robustness: a cheap stand-in for the libFuzzer target in tests/fuzz ----

const std::string kMutationInserts[] = {"\"",
                                        "{",
                                        "}",
                                        "[",
                                        "]",
                                        ",",
                                        ":",
                                        "\\",
                                        "\\u0000",
                                        "\\ud800",
                                        "1e400",
                                        "-",
                                        "null",
                                        "NaN",
                                        "\xFF",
                                        std::string(1, '\0'),
                                        R"("status":"ok",)",
                                        "[[[[",
                                        "0.0",
                                        "true"};

TEST(TurnJsonMutation, MutatedDocumentsParseOrThrowParseErrorOnly) {
  const testing::MutationOutcome outcome = testing::run_mutations(
      11, {kExampleJson, to_json_string(TurnSequence{}), example_json().dump(1)}, kAlphabet,
      kMutationInserts, 20000, parse_turn_json, to_json_string, parse_text_record, to_text_record);
  // Both outcomes must occur or the mutations are not exercising the parser.
  EXPECT_GT(outcome.accepted, 100);
  EXPECT_GT(outcome.rejected, 10000);
}

// A harvested turn carries its source and quality; a document without them
// (every document written before) is a collection turn without quality.
TEST(TurnJson, SourceAndQualityAreOptionalKeys) {
  EXPECT_EQ(example_json().count("source"), 0u);
  EXPECT_EQ(example_json().count("quality"), 0u);
  EXPECT_EQ(parse_turn_json(kExampleJson).meta().source, TurnSource::collection);
  EXPECT_FALSE(parse_turn_json(kExampleJson).meta().quality);
  TurnSequence harvested = example_turn();
  harvested.meta().source = TurnSource::harvested;
  harvested.meta().quality = 0.8125;
  const json j = to_json(harvested);
  EXPECT_EQ(j["source"], "harvested");
  EXPECT_EQ(j["quality"], 0.8125);
  expect_round_trip(harvested);
  json bad = j;
  bad["source"] = "guessed";
  expect_document_error(bad, "/source", 0);
  bad = j;
  bad["quality"] = 1.5;
  expect_document_error(bad, "/quality", 0);
}

}  // namespace
}  // namespace avk::kinematics
