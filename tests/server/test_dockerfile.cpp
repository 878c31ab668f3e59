// No Docker engine runs on the build machines: this checks that the Dockerfile builds with the
// same scripts CI proves, in their lean mode (no test or browser tooling in the build stage), and
// serves as the issue asks. web/tests/docker_netns.test.mjs runs its ENTRYPOINT for real.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>
#include <string>

namespace {

std::string read_source(const std::string& relative) {
  std::ifstream f(std::string(AVK_SOURCE_DIR) + "/" + relative);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

std::string dockerfile() {
  return read_source("Dockerfile");
}

// The packages scripts/setup would install with these arguments (its dry run installs nothing).
std::set<std::string> setup_packages(const std::string& args) {
  const std::string cmd =
      "AVK_SETUP_DRY_RUN=1 bash '" + std::string(AVK_SOURCE_DIR) + "/scripts/setup' " + args;
  std::set<std::string> out;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return out;
  char line[256];
  while (fgets(line, sizeof line, p)) {
    std::string s(line);
    while (!s.empty() && (s.back() == '\n' || s.back() == '\r'))
      s.pop_back();
    if (!s.empty()) out.insert(s);
  }
  EXPECT_EQ(pclose(p), 0) << cmd;
  return out;
}

TEST(Dockerfile, BuildsWithTheProjectScriptsAndServesAsANonRootUser) {
  const std::string d = dockerfile();
  ASSERT_FALSE(d.empty());
  EXPECT_NE(d.find("FROM debian:12 AS build"), std::string::npos);
  // Multi-stage: a build stage and a runtime stage, both Debian 12.
  std::regex from(R"(\nFROM debian:12)");
  EXPECT_EQ(std::distance(std::sregex_iterator(d.begin(), d.end(), from), std::sregex_iterator()),
            2);
  EXPECT_NE(d.find("COPY --from=build /src/build/server/avk"), std::string::npos);
  EXPECT_NE(d.find("\nUSER avk"), std::string::npos);
  EXPECT_NE(d.find("HEALTHCHECK"), std::string::npos);
  EXPECT_NE(d.find("/api/v1/health"), std::string::npos);
  EXPECT_NE(d.find("VOLUME [\"/var/lib/avk\"]"), std::string::npos);
  EXPECT_NE(d.find(R"("--sim", "--bind", "0.0.0.0", "--port", "8080")"), std::string::npos);
}

// The build stage ran the full setup (Chromium, test frameworks, Node's test tooling) and built
// every test and benchmark although the image runs none: 13 minutes and 376 MB for nothing.
TEST(Dockerfile, TheBuildStageInstallsAndBuildsOnlyWhatTheImageRuns) {
  const std::string d = dockerfile();
  EXPECT_NE(d.find("RUN bash scripts/setup --runtime-build"), std::string::npos);
  EXPECT_NE(d.find("AVK_WEB_DEPS=runtime bash scripts/build -DAVK_BUILD_TESTS=OFF "
                   "-DAVK_BUILD_BENCH=OFF"),
            std::string::npos);
  EXPECT_EQ(d.find("RUN bash scripts/setup &&"), std::string::npos) << "the full setup";
}

TEST(Dockerfile, TheLeanSetupInstallsNoTestOrBrowserTooling) {
  const auto lean = setup_packages("--runtime-build");
  ASSERT_FALSE(lean.empty());
  for (const char* needed :
       {"build-essential", "cmake", "ninja-build", "pkg-config", "libeigen3-dev",
        "libboost1.81-dev", "nlohmann-json3-dev", "libsqlite3-dev"})
    EXPECT_TRUE(lean.count(needed)) << needed;
  for (const char* unwanted : {"chromium", "googletest", "libgtest-dev", "libgmock-dev",
                               "libbenchmark-dev", "clang", "clang-format", "ccache"})
    EXPECT_FALSE(lean.count(unwanted)) << unwanted;
  // The full setup (README, CI) still has everything the tests need.
  const auto full = setup_packages("");
  for (const char* needed : {"chromium", "libgtest-dev", "libbenchmark-dev"})
    EXPECT_TRUE(full.count(needed)) << needed;
}

TEST(Dockerfile, ADevOnlyNpmInstallKeepsPlaywrightOutOfTheImage) {
  const auto pkg = nlohmann::json::parse(read_source("web/package.json"));
  EXPECT_TRUE(pkg["dependencies"].contains("plotly.js-dist-min"));
  EXPECT_FALSE(pkg["dependencies"].contains("playwright-core")) << "a test tool in the runtime";
  EXPECT_TRUE(pkg["devDependencies"].contains("playwright-core"));
  EXPECT_NE(read_source("scripts/web-deps").find("--omit=dev"), std::string::npos);
}

// The runtime stage serves the dashboard's own files, not its tests or npm manifests.
TEST(Dockerfile, TheImageHoldsOnlyTheDashboardsFiles) {
  const std::string d = dockerfile();
  EXPECT_EQ(d.find("COPY --from=build /src/web /"), std::string::npos) << "the whole web/";
  for (const char* part : {"/src/web/index.html", "/src/web/css", "/src/web/js",
                           "/src/web/node_modules/plotly.js-dist-min"})
    EXPECT_NE(d.find(part), std::string::npos) << part;
  EXPECT_EQ(d.find("web/tests"), std::string::npos);
  EXPECT_EQ(d.find("package.json"), std::string::npos);
  EXPECT_EQ(d.find("package-lock"), std::string::npos);
}

TEST(Dockerfile, TheScriptsItRunsExist) {
  for (const char* script :
       {"/scripts/setup", "/scripts/build", "/scripts/web-deps", "/web/index.html"}) {
    std::ifstream f(std::string(AVK_SOURCE_DIR) + script);
    EXPECT_TRUE(f.good()) << script;
  }
}

}  // namespace
