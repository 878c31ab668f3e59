// Parser input limits: the CKT, turn and yaw model readers throw only their own ParseError naming
// the field, never nlohmann's exceptions or their text (which quotes the input), and an imported
// table's grid is bounded so the fine table built from it stays small.
#include <gtest/gtest.h>

#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "kinematics/ckt.hpp"
#include "kinematics/ckt_file.hpp"
#include "kinematics/parse_error.hpp"
#include "kinematics/turn_json.hpp"
#include "kinematics/yaw_model_json.hpp"
#include "support/random_turns.hpp"
#include "support/synthetic_turns.hpp"

using namespace avk::kinematics;
using nlohmann::json;

namespace {

Ckt two_speed_table() {
  std::vector<TurnSequence> turns;
  unsigned seed = 1;
  for (double u : {0.5, 1.0}) {
    for (double d : {30.0, 90.0}) {
      avk::testing::ArcTurnSpec s;
      s.speed_mps = u;
      s.dheading_deg = d;
      s.lead_in_m = 1 + u;
      s.radius_m = 2 + u;
      s.seed = seed++;
      turns.push_back(avk::testing::make_arc_turn(s));
    }
  }
  Ckt t = Ckt::build(turns);
  t.vehicle_id = "v";
  t.created_utc = "2026-12-01T00:00:00Z";
  return t;
}

// The table's document with its top speed (1.0 m/s) moved to `speed_mps`, in grid and cells.
std::string with_top_speed(double speed_mps) {
  json doc = ckt_to_json(two_speed_table());
  doc["grid"]["speeds_mps"][1] = speed_mps;
  for (json& c : doc["cells"])
    if (c["speed_mps"] == 1.0) c["speed_mps"] = speed_mps;
  return doc.dump();
}

template <class F>
ParseError parse_error_of(F parse) {
  try {
    parse();
  } catch (const ParseError& e) {
    EXPECT_EQ(std::string(e.what()).find("json.exception"), std::string::npos) << e.what();
    return e;
  } catch (const std::exception& e) {
    ADD_FAILURE() << "threw something other than ParseError: " << e.what();
    return ParseError("<other>", 0, e.what());
  }
  ADD_FAILURE() << "accepted";
  return ParseError("<accepted>", 0, "");
}

}  // namespace

TEST(ParserLimits, CktNumberTooLargeForADoubleNamesItsField) {
  std::string text = ckt_to_json_string(two_speed_table());
  const std::string at = "\"pwl_epsilon_m\":0.05";
  ASSERT_NE(text.find(at), std::string::npos);
  text.replace(text.find(at), at.size(), "\"pwl_epsilon_m\":1e400");
  const ParseError e = parse_error_of([&] { parse_ckt_json(text); });
  EXPECT_EQ(e.field(), "/options/pwl_epsilon_m");
}

TEST(ParserLimits, CktTopSpeedOfTwoHundredMetresASecondIsRefused) {
  const std::string ok = with_top_speed(1.0);
  ASSERT_NO_THROW(parse_ckt_json(ok));
  const ParseError e = parse_error_of([&] { parse_ckt_json(with_top_speed(200.0)); });
  EXPECT_EQ(e.field(), "/grid/speeds_mps/1");
  const ParseError huge = parse_error_of([&] { parse_ckt_json(with_top_speed(1e300)); });
  EXPECT_EQ(huge.field(), "/grid/speeds_mps/1");
}

TEST(ParserLimits, CktNestingIsBoundedAndNeverDumped) {
  // schema_version was quoted into its error with dump(), which recurses once per level.
  std::string text = ckt_to_json_string(two_speed_table());
  const std::string at = "\"schema_version\": " + std::to_string(kCktSchemaVersion);
  ASSERT_NE(text.find(at), std::string::npos) << text.substr(0, 200);
  text.replace(text.find(at), at.size(),
               "\"schema_version\": " + std::string(200000, '[') + std::string(200000, ']'));
  const ParseError e = parse_error_of([&] { parse_ckt_json(text); });
  EXPECT_EQ(e.field().rfind("/schema_version", 0), 0u) << e.field();
}

TEST(ParserLimits, MaterialisedTableOfAHugeSpeedRangeStaysBounded) {
  // A table whose speeds span 0.5 .. 1e300 m/s (as an unbounded import allowed) overflowed the
  // fine table's row count; its size is capped, and lookups at both ends still answer.
  const Ckt t = two_speed_table();
  CktGrid grid = t.grid();
  grid.speeds_mps.back() = 1e300;
  std::vector<CktCell> cells;
  for (const CktCell& c : t.cells()) {
    if (!c.has_data()) continue;
    CktCell copy = c;
    if (copy.speed_mps == 1.0) copy.speed_mps = 1e300;
    cells.push_back(copy);
  }
  const Ckt wide = Ckt::from_cells(grid, cells, t.options());
  std::unique_ptr<MaterializedCkt> m;
  ASSERT_NO_THROW(m = std::make_unique<MaterializedCkt>(wide));
  EXPECT_LE(m->speed_count(), 1024u);
  EXPECT_NO_THROW(m->lookup(0.5, 30.0));
  EXPECT_NO_THROW(m->lookup(1e300, -90.0));
  EXPECT_THROW(m->lookup(1e308, 30.0), CktRangeError);
}

TEST(ParserLimits, TurnJsonErrorsAreTheProjectsOwnWords) {
  std::string text = to_json_string(avk::testing::example_turn());
  const std::string at = "\"end_time_s\":";
  text.insert(text.find(at) + at.size(), "1e400,\"x\":");
  const ParseError e = parse_error_of([&] { parse_turn_json(text); });
  EXPECT_EQ(e.field(), "json");
  const ParseError syntax = parse_error_of([&] { parse_turn_json("{\"format\": tru}"); });
  EXPECT_EQ(syntax.field(), "json");
}

TEST(YawModelJsonLimits, NumberTooLargeForADoubleNamesItsField) {
  const ParseError e = parse_error_of([] { parse_yaw_model_json("{\"form\": 1e400}"); });
  EXPECT_EQ(e.field(), "/form");
}
