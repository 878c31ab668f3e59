// Sim config input limits: a number JSON cannot hold as a double is a ParseError naming its field,
// not nlohmann's out_of_range escaping a parser documented to throw ParseError.
#include <gtest/gtest.h>

#include <string>

#include "kinematics/parse_error.hpp"
#include "sim/sim_config.hpp"

using avk::kinematics::ParseError;
using avk::sim::parse_sim_config;

namespace {

ParseError error_of(const std::string& text) {
  try {
    parse_sim_config(text, "usim");
  } catch (const ParseError& e) {
    EXPECT_EQ(std::string(e.what()).find("json.exception"), std::string::npos) << e.what();
    return e;
  } catch (const std::exception& e) {
    ADD_FAILURE() << "threw something other than ParseError: " << e.what();
    return ParseError("<other>", 0, "");
  }
  ADD_FAILURE() << "accepted";
  return ParseError("<accepted>", 0, "");
}

}  // namespace

TEST(SimConfigLimits, NumberTooLargeForADoubleNamesItsField) {
  EXPECT_EQ(error_of(R"({"seed": 1e400})").field(), "/seed");
  EXPECT_EQ(error_of(R"({"wind": {"mean_speed_mps": -1e999}})").field(), "/wind/mean_speed_mps");
}

TEST(SimConfigLimits, SyntaxErrorsAndDeepNestingAreParseErrors) {
  EXPECT_EQ(error_of(R"({"seed": tru})").field(), "json");
  const ParseError deep =
      error_of("{\"wind\": " + std::string(100000, '[') + std::string(100000, ']') + "}");
  EXPECT_EQ(deep.field().rfind("/wind", 0), 0u) << deep.field();
  EXPECT_NE(std::string(deep.what()).find("nested"), std::string::npos) << deep.what();
}

// A vehicle id names the vehicle in every list and file name: bounded, and without control
// characters (it goes into headers and CSV).
TEST(SimConfigLimits, AVehicleIdIsBoundedAndPrintable) {
  const ParseError long_id = error_of(R"({"vehicle_id": ")" + std::string(65, 'v') + R"("})");
  EXPECT_EQ(long_id.field(), "/vehicle_id");
  EXPECT_NE(std::string(long_id.what()).find("at most 64 bytes"), std::string::npos)
      << long_id.what();
  EXPECT_EQ(error_of(R"({"vehicle_id": ""})").field(), "/vehicle_id");
  EXPECT_EQ(error_of(R"({"vehicle_id": "boat\r\nX-Evil: 1"})").field(), "/vehicle_id");
  EXPECT_EQ(
      parse_sim_config(R"({"vehicle_id": ")" + std::string(64, 'v') + R"("})", "usim").vehicle.id,
      std::string(64, 'v'));
}
