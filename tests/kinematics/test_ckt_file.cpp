#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "kinematics/ckt_file.hpp"
#include "kinematics/parse_error.hpp"
#include "support/synthetic_turns.hpp"

using namespace avk::kinematics;
using nlohmann::json;

namespace {

Ckt sample_table() {
  std::vector<TurnSequence> turns;
  unsigned seed = 1;
  for (double u : {0.5, 1.0}) {
    for (double d : {30.0, 90.0, 150.0}) {
      for (int r = 0; r < (d == 150.0 ? 1 : 2); ++r) {
        avk::testing::ArcTurnSpec s;
        s.speed_mps = u;
        s.dheading_deg = r ? -d : d;
        s.lead_in_m = 1 + u;
        s.radius_m = 2 + u;
        s.position_noise_m = 0.03;
        s.seed = seed++;
        turns.push_back(avk::testing::make_arc_turn(s));
      }
    }
  }
  Ckt t = Ckt::build(turns);
  t.vehicle_id = "m200-01";
  t.vehicle_length_m = 1.35;
  t.created_utc = "2026-11-22T04:00:00Z";
  return t;
}

// Parses a mutated document and returns the field the error names.
std::string error_field(const json& doc) {
  try {
    ckt_from_json(doc);
  } catch (const ParseError& e) {
    return e.field();
  }
  return "<no error>";
}

}  // namespace

TEST(CktFile, JsonTableJsonIsIdentical) {
  const Ckt t = sample_table();
  const std::string first = ckt_to_json_string(t);
  const Ckt loaded = parse_ckt_json(first);
  EXPECT_EQ(ckt_to_json_string(loaded), first);
  EXPECT_EQ(loaded.grid(), t.grid());
  EXPECT_EQ(loaded.options(), t.options());
  EXPECT_EQ(loaded.vehicle_id, "m200-01");
  ASSERT_TRUE(loaded.vehicle_length_m.has_value());
  // A loaded table answers queries exactly as the table it was written from.
  for (double u : {0.5, 0.7, 1.0}) {
    for (double d : {-150.0, 30.0, 61.0, 120.0}) {
      const auto a = t.query(u, d), b = loaded.query(u, d);
      EXPECT_EQ(a.trajectory, b.trajectory);
      EXPECT_EQ(a.advance_m, b.advance_m);
      EXPECT_EQ(a.transfer_m, b.transfer_m);
    }
  }
}

TEST(CktFile, SingleTurnCellsHaveNoAvkError) {
  const json doc = ckt_to_json(sample_table());
  bool found = false;
  for (const auto& c : doc["cells"]) {
    if (c["n_turns"] == 1) {
      EXPECT_TRUE(c["stats"]["avk_error_m2"].is_null());
      found = true;
    }
  }
  EXPECT_TRUE(found);
}

TEST(CktFile, WrongVersionOrFormatIsRefused) {
  json doc = ckt_to_json(sample_table());
  doc["schema_version"] = kCktSchemaVersion + 1;
  try {
    ckt_from_json(doc);
    FAIL();
  } catch (const ParseError& e) {
    EXPECT_EQ(e.field(), "/schema_version");
    EXPECT_NE(std::string(e.what()).find("unsupported schema_version " +
                                         std::to_string(kCktSchemaVersion + 1)),
              std::string::npos);
  }
  doc = ckt_to_json(sample_table());
  doc["format"] = "something-else";
  EXPECT_EQ(error_field(doc), "/format");
}

TEST(CktFile, CorruptFieldsAreNamed) {
  const json good = ckt_to_json(sample_table());
  json doc = good;
  doc["cells"][1]["trajectory"][3][1] = "x";
  EXPECT_EQ(error_field(doc), "/cells/1/trajectory/3/1");
  doc = good;
  doc["cells"][0].erase("stats");
  EXPECT_EQ(error_field(doc), "/cells/0/stats");
  doc = good;
  doc["cells"][2]["speed_mps"] = 0.75;
  EXPECT_EQ(error_field(doc), "/cells/2/speed_mps");
  doc = good;
  doc["cells"][0]["fit"]["kind"] = "spline9";
  EXPECT_EQ(error_field(doc), "/cells/0/fit/kind");
  doc = good;
  doc["cells"][0]["fit"]["knots"] = json::array({1.0, 0.0});
  EXPECT_EQ(error_field(doc), "/cells/0/fit");
  doc = good;
  doc["grid"]["dheadings_deg"][1] = 200.0;
  EXPECT_NE(error_field(doc).find("/grid/dheadings_deg"), std::string::npos);
  doc = good;
  doc["cells"][1] = good["cells"][0];
  EXPECT_EQ(error_field(doc), "/cells/1");
  doc = good;
  doc["cells"].push_back(good["cells"][0]);
  EXPECT_EQ(error_field(doc), "/cells");  // more cells than the grid holds
  doc = good;
  doc["cells"][0]["n_turns"] = -1;
  EXPECT_EQ(error_field(doc), "/cells/0/n_turns");
  doc = good;
  doc["cells"][0]["bogus"] = 1;
  EXPECT_EQ(error_field(doc), "/cells/0/bogus");
  doc = good;
  doc["cells"][0]["trajectory"] = json::array({json::array({0.0, 0.0})});
  EXPECT_EQ(error_field(doc), "/cells/0/trajectory");
}

TEST(CktFile, SyntaxErrorNamesLineAndColumn) {
  std::string text = ckt_to_json_string(sample_table());
  text = text.substr(0, text.size() / 2);  // truncated file
  try {
    parse_ckt_json(text);
    FAIL();
  } catch (const ParseError& e) {
    EXPECT_EQ(e.field(), "json");
    EXPECT_NE(std::string(e.what()).find("line "), std::string::npos);
  }
  try {
    parse_ckt_json("{\n \"format\": \"avk-ckt\",\n \"x\": nope\n}");
    FAIL();
  } catch (const ParseError& e) {
    EXPECT_NE(std::string(e.what()).find("line 3"), std::string::npos) << e.what();
  }
}

TEST(CktFile, CsvHasOneRowPerVertex) {
  const Ckt t = sample_table();
  const std::string csv = ckt_to_csv(t);
  std::size_t vertices = 0;
  for (const auto& c : t.cells())
    vertices += c.trajectory.size();
  EXPECT_EQ(static_cast<std::size_t>(std::count(csv.begin(), csv.end(), '\n')), vertices + 1);
  EXPECT_EQ(csv.rfind("speed_mps,dheading_deg,vertex_index,x_m,y_m\n", 0), 0u);
}
