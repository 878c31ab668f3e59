// No Docker engine runs on the build machines: this checks that the Dockerfile builds with the
// same scripts CI proves, in their lean mode (no test or browser tooling in the build stage), that
// each of its steps copies in only what it reads (so Docker's cache keeps the dependencies, the
// npm package and the compile apart), that the build context holds only what it copies, and that
// it serves as the issue asks. web/tests/docker_netns.test.mjs runs its ENTRYPOINT for real.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

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

// One Dockerfile instruction: its keyword (upper case) and its arguments, continuation lines
// joined; comments and blank lines dropped.
struct Instruction {
  std::string keyword;
  std::string args;
};

// A build stage: its name (`AS name`, else its index), the stage or image it starts from and its
// instructions in order.
struct Stage {
  std::string name;
  std::string from;
  std::vector<Instruction> steps;
};

std::vector<std::string> words(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> out;
  for (std::string w; in >> w;)
    out.push_back(w);
  return out;
}

std::vector<Stage> stages(const std::string& dockerfile) {
  std::vector<Stage> out;
  std::istringstream in(dockerfile);
  std::string line, joined;
  const auto finish = [&] {
    const auto w = words(joined);
    joined.clear();
    if (w.empty()) return;
    Instruction i;
    i.keyword = w[0];
    for (auto& c : i.keyword)
      c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    for (std::size_t k = 1; k < w.size(); ++k)
      i.args += (k > 1 ? " " : "") + w[k];
    if (i.keyword == "FROM") {
      Stage s;
      s.from = w.size() > 1 ? w[1] : "";
      s.name = w.size() > 3 ? w[3] : std::to_string(out.size());
      out.push_back(s);
    } else if (!out.empty()) {
      out.back().steps.push_back(i);
    }
  };
  while (std::getline(in, line)) {
    const auto first = line.find_first_not_of(" \t");
    if (joined.empty() && (first == std::string::npos || line[first] == '#')) continue;
    if (!line.empty() && line.back() == '\\') {
      joined += line.substr(0, line.size() - 1) + " ";
      continue;
    }
    joined += line;
    finish();
  }
  finish();
  return out;
}

// What a RUN sees: the steps of the stages it builds on (FROM <stage>), then its own stage's steps
// before it. Docker rebuilds a step when any of these changed.
std::vector<Instruction> steps_before(const std::vector<Stage>& all, const std::string& stage,
                                      const Instruction* upto) {
  for (const auto& s : all) {
    if (s.name != stage) continue;
    auto out = steps_before(all, s.from, nullptr);
    for (const auto& i : s.steps) {
      if (&i == upto) break;
      out.push_back(i);
    }
    return out;
  }
  return {};
}

// The context paths a COPY without --from takes (its last word is the destination).
std::vector<std::string> context_sources(const Instruction& copy) {
  if (copy.keyword != "COPY" || copy.args.find("--from=") != std::string::npos) return {};
  auto w = words(copy.args);
  std::erase_if(w, [](const std::string& x) { return x.starts_with("--"); });
  if (!w.empty()) w.pop_back();
  return w;
}

// The context paths copied in before a step of a stage (the stages it builds on included).
std::set<std::string> copied_before(const std::vector<Stage>& all, const std::string& stage,
                                    const Instruction* upto) {
  std::set<std::string> out;
  for (const auto& i : steps_before(all, stage, upto))
    for (const auto& src : context_sources(i))
      out.insert(src);
  return out;
}

// The stage and step of the only RUN holding `text`.
std::pair<std::string, const Instruction*> run_with(const std::vector<Stage>& all,
                                                    const std::string& text) {
  std::pair<std::string, const Instruction*> found{"", nullptr};
  for (const auto& s : all)
    for (const auto& i : s.steps)
      if (i.keyword == "RUN" && i.args.find(text) != std::string::npos) {
        EXPECT_EQ(found.second, nullptr) << "two RUNs hold " << text;
        found = {s.name, &i};
      }
  return found;
}

// The folders CMakeLists.txt always builds (add_subdirectory outside an if: not tests/bench).
std::vector<std::string> built_folders() {
  std::istringstream in(read_source("CMakeLists.txt"));
  std::vector<std::string> out;
  int depth = 0;
  const std::regex sub(R"(^\s*add_subdirectory\((\w+)\))");
  for (std::string line; std::getline(in, line);) {
    if (std::regex_search(line, std::regex(R"(^\s*if\s*\()"))) ++depth;
    if (std::regex_search(line, std::regex(R"(^\s*endif\s*\()"))) --depth;
    std::smatch m;
    if (depth == 0 && std::regex_search(line, m, sub)) out.push_back(m[1]);
  }
  return out;
}

// The re-included paths of a .dockerignore that excludes everything first ("*", then "!path").
std::set<std::string> dockerignore_included(bool& excludes_all_first) {
  std::istringstream in(read_source(".dockerignore"));
  std::set<std::string> out;
  excludes_all_first = false;
  bool first = true;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    if (first) excludes_all_first = line == "*";
    first = false;
    if (line[0] == '!') out.insert(line.substr(1));
  }
  return out;
}

TEST(Dockerfile, BuildsWithTheProjectScriptsAndServesAsANonRootUser) {
  const std::string d = dockerfile();
  ASSERT_FALSE(d.empty());
  EXPECT_NE(d.find("FROM debian:12 AS deps"), std::string::npos);
  // Multi-stage: the build stages on Debian 12, the runtime stage on Debian 12 slim.
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
  EXPECT_NE(d.find("AVK_WEB_DEPS=none bash scripts/build -DAVK_BUILD_TESTS=OFF "
                   "-DAVK_BUILD_BENCH=OFF"),
            std::string::npos);
  EXPECT_NE(d.find("AVK_WEB_DEPS=runtime bash scripts/web-deps"), std::string::npos);
  EXPECT_EQ(d.find("RUN bash scripts/setup &&"), std::string::npos) << "the full setup";
}

// One RUN did apt, the compile and `npm ci` after `COPY . .`: any file changed, or a failed
// `npm ci`, redid the 12-minute compile. Each RUN now sees only what it needs, so Docker's cache
// keeps the dependencies, the npm package and the compile apart, and only sources recompile.
TEST(Dockerfile, DependenciesTheNpmPackageAndTheCompileAreCachedApart) {
  const auto all = stages(dockerfile());
  ASSERT_GE(all.size(), 2u);
  for (const auto& st : all)
    for (const auto& i : st.steps)
      for (const auto& src : context_sources(i))
        EXPECT_NE(src, ".") << "COPY . . in stage " << st.name << ": every file is in every layer";

  const auto [setup_stage, setup] = run_with(all, "bash scripts/setup");
  ASSERT_NE(setup, nullptr);
  EXPECT_EQ(copied_before(all, setup_stage, setup), (std::set<std::string>{"scripts/setup"}))
      << "the dependencies are installed from the setup script alone";

  const auto [npm_stage, npm] = run_with(all, "bash scripts/web-deps");
  ASSERT_NE(npm, nullptr);
  const auto npm_sees = copied_before(all, npm_stage, npm);
  EXPECT_TRUE(npm_sees.count("web/package.json") && npm_sees.count("web/package-lock.json"));
  for (const auto& src : npm_sees)
    EXPECT_TRUE(src == "scripts/setup" || src == "scripts/web-deps" ||
                src.starts_with("web/package"))
        << src << " is copied before the npm install: a change to it reinstalls the package";

  const auto [build_stage, build] = run_with(all, "bash scripts/build");
  ASSERT_NE(build, nullptr);
  EXPECT_EQ(build_stage, "build") << "the runtime stage copies the binary from it";
  EXPECT_NE(build->args.find("AVK_WEB_DEPS=none"), std::string::npos)
      << "the compile installs no npm package (its stage has no package manifests)";
  const auto build_sees = copied_before(all, build_stage, build);
  std::set<std::string> compile_needs = {"scripts/setup", "scripts/build", "CMakeLists.txt"};
  const auto folders = built_folders();
  ASSERT_GE(folders.size(), 7u);
  for (const auto& folder : folders) {
    EXPECT_TRUE(build_sees.count(folder)) << folder << " is built but not copied";
    compile_needs.insert(folder);
  }
  for (const auto& src : build_sees)
    EXPECT_TRUE(compile_needs.count(src))
        << src << " is copied before the compile: a change to it recompiles";
}

// AVK_WEB_DEPS=none builds without touching npm: the compile stage has no package manifests.
TEST(Dockerfile, TheBuildScriptSkipsTheNpmPackagesWhenAskedTo) {
  const std::filesystem::path bin =
      std::filesystem::temp_directory_path() / ("avk_docker_bin_" + std::to_string(::getpid()));
  std::filesystem::create_directories(bin);
  const auto script = [&](const std::string& name, const std::string& body) {
    std::ofstream(bin / name) << "#!/bin/sh\n" << body << "\n";
    std::filesystem::permissions(bin / name, std::filesystem::perms::owner_all);
  };
  // Stand-ins for cmake (nothing to build) and npm (it must not be run), first on the PATH.
  script("cmake", "exit 0");
  script("npm", "touch '" + (bin / "npm-ran").string() + "'; exit 1");
  const std::string cmd = "PATH='" + bin.string() +
                          "':\"$PATH\" AVK_WEB_DEPS=none AVK_BUILD_DIR='" +
                          (bin / "build").string() + "' bash '" + std::string(AVK_SOURCE_DIR) +
                          "/scripts/build' >/dev/null 2>&1";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
  EXPECT_FALSE(std::filesystem::exists(bin / "npm-ran")) << "scripts/build ran npm";
  std::filesystem::remove_all(bin);
}

// Docs, README, tests and benchmarks were in the build context, so a change to any of them sent
// a new context (and, with COPY . ., rebuilt everything). The context holds only what the
// Dockerfile copies: .dockerignore excludes everything, then re-includes exactly those paths.
TEST(Dockerfile, TheContextHoldsOnlyWhatTheDockerfileCopies) {
  bool excludes_all_first = false;
  const auto included = dockerignore_included(excludes_all_first);
  EXPECT_TRUE(excludes_all_first) << ".dockerignore must start with '*'";
  std::set<std::string> copied;
  for (const auto& st : stages(dockerfile()))
    for (const auto& i : st.steps)
      for (const auto& src : context_sources(i))
        copied.insert(src);
  EXPECT_EQ(included, copied) << "re-include what the Dockerfile copies, and nothing else";
  for (const char* never : {"docs", "README.md", "tests", "bench", "web/tests", "web/bench",
                            "web/node_modules", ".git", "build"})
    EXPECT_FALSE(included.count(never)) << never;
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
  const auto all = stages(dockerfile());
  ASSERT_FALSE(all.empty());
  std::string runtime;  // the last stage's COPY lines
  for (const auto& i : all.back().steps)
    if (i.keyword == "COPY") runtime += i.args + "\n";
  EXPECT_EQ(runtime.find("/src/web /"), std::string::npos) << "the whole web/";
  for (const char* part : {"web/index.html", "web/favicon.svg", "web/css", "web/js",
                           "--from=web /src/web/node_modules/plotly.js-dist-min"})
    EXPECT_NE(runtime.find(part), std::string::npos) << part;
  EXPECT_EQ(runtime.find("web/tests"), std::string::npos);
  EXPECT_EQ(runtime.find("package.json"), std::string::npos);
  EXPECT_EQ(runtime.find("package-lock"), std::string::npos);
}

// A bind mount must belong to the image's user, so its uid is fixed (999, what `useradd --system`
// gave it before, so existing volumes keep their owner) and the README says which it is.
TEST(Dockerfile, TheImageUserHasAFixedUidTheReadmeNames) {
  const std::string d = dockerfile();
  std::smatch uid;
  ASSERT_TRUE(std::regex_search(d, uid, std::regex(R"(useradd [^\n]*--uid (\d+))")));
  EXPECT_EQ(uid[1], "999");
  EXPECT_TRUE(std::regex_search(d, std::regex(R"(groupadd [^\n]*--gid 999)")));
  const std::string readme = read_source("README.md");
  const auto docker = readme.find("## Docker");
  ASSERT_NE(docker, std::string::npos);
  const std::string section = readme.substr(docker, readme.find("\n## ", docker + 1) - docker);
  EXPECT_NE(section.find("chown " + uid[1].str()), std::string::npos) << section;
  EXPECT_NE(section.find("AVK_ALLOW_HOSTS"), std::string::npos) << section;
}

TEST(Dockerfile, TheScriptsItRunsExist) {
  for (const char* script :
       {"/scripts/setup", "/scripts/build", "/scripts/web-deps", "/web/index.html"}) {
    std::ifstream f(std::string(AVK_SOURCE_DIR) + script);
    EXPECT_TRUE(f.good()) << script;
  }
}

}  // namespace
