// No Docker engine runs on the build machines: this checks that the Dockerfile builds with the
// same scripts CI proves, and serves as the issue asks.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>

namespace {

std::string dockerfile() {
  std::ifstream f(std::string(AVK_SOURCE_DIR) + "/Dockerfile");
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

TEST(Dockerfile, BuildsWithTheProjectScriptsAndServesAsANonRootUser) {
  const std::string d = dockerfile();
  ASSERT_FALSE(d.empty());
  EXPECT_NE(d.find("FROM debian:12 AS build"), std::string::npos);
  EXPECT_NE(d.find("RUN bash scripts/setup && bash scripts/build"), std::string::npos);
  // Multi-stage: a build stage and a runtime stage, both Debian 12.
  std::regex from(R"(\nFROM debian:12)");
  EXPECT_EQ(std::distance(std::sregex_iterator(d.begin(), d.end(), from), std::sregex_iterator()),
            2);
  EXPECT_NE(d.find("COPY --from=build /src/build/server/avk"), std::string::npos);
  EXPECT_NE(d.find("COPY --from=build /src/web"), std::string::npos);
  EXPECT_NE(d.find("\nUSER avk"), std::string::npos);
  EXPECT_NE(d.find("HEALTHCHECK"), std::string::npos);
  EXPECT_NE(d.find("/api/v1/health"), std::string::npos);
  EXPECT_NE(d.find("VOLUME [\"/var/lib/avk\"]"), std::string::npos);
  EXPECT_NE(d.find(R"("--sim", "--bind", "0.0.0.0", "--port", "8080")"), std::string::npos);
}

TEST(Dockerfile, TheScriptsItRunsExist) {
  for (const char* script : {"/scripts/setup", "/scripts/build", "/web/index.html"}) {
    std::ifstream f(std::string(AVK_SOURCE_DIR) + script);
    EXPECT_TRUE(f.good()) << script;
  }
}

}  // namespace
