// The dashboard's static files over HTTP: types, the root and what is served under it, the
// security headers, validators and conditional requests, and edits made while serving.
#include <gtest/gtest.h>

#include "server/http_server_fixture.hpp"

namespace {

using namespace avk::testing::http_transport;

// --- static files --------------------------------------------------------------------------

class StaticFilesTest : public HttpServerTest {
 protected:
  void SetUp() override {
    base = fs::temp_directory_path() /
           ("avk_http_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    fs::remove_all(base);
    // The dashboard's layout, and what else lies in web/ in a checkout.
    fs::create_directories(base / "web" / "js" / "sub");
    fs::create_directories(base / "web" / "css");
    fs::create_directories(base / "web" / "tests");
    fs::create_directories(base / "web" / "node_modules" / "plotly.js-dist-min");
    write(base / "web" / "index.html", "<html>dashboard</html>");
    write(base / "web" / "js" / "app.js", "console.log(1);");
    write(base / "web" / "css" / "style.css", "body{}");
    write(base / "web" / "favicon.svg", "<svg/>");
    write(base / "web" / "node_modules" / "plotly.js-dist-min" / "plotly.min.js", "plotly");
    write(base / "web" / "node_modules" / "plotly.js-dist-min" / "package.json", "{}");
    write(base / "web" / "node_modules" / ".package-lock.json", "{}");
    write(base / "web" / "tests" / "e2e.test.mjs", "test");
    write(base / "web" / "package.json", "{}");
    write(base / "web" / "package-lock.json", "{}");
    write(base / "secret", "TOPSECRET");
    fs::create_symlink(base / "secret", base / "web" / "js" / "link.js");
  }
  void TearDown() override {
    server.reset();
    std::error_code ec;
    fs::remove_all(base, ec);
  }
  static void write(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

  fs::path base;
  static inline int counter = 0;
};

TEST_F(StaticFilesTest, ServesFilesWithTheirTypes) {
  HttpServerOptions o;
  o.web_root = (base / "web").string();
  start(o);
  auto res = get(port, "/");
  ASSERT_EQ(res.result_int(), 200);
  EXPECT_TRUE(res[http::field::content_type].starts_with("text/html"));
  EXPECT_EQ(res.body(), "<html>dashboard</html>");
  res = get(port, "/js/app.js?v=3");
  ASSERT_EQ(res.result_int(), 200);
  EXPECT_TRUE(res[http::field::content_type].starts_with("text/javascript"));
  EXPECT_EQ(res.body(), "console.log(1);");
  res = get(port, "/css/style.css");
  EXPECT_TRUE(res[http::field::content_type].starts_with("text/css"));
  EXPECT_EQ(get(port, "/favicon.svg").result_int(), 200);
  EXPECT_EQ(get(port, "/node_modules/plotly.js-dist-min/plotly.min.js").body(), "plotly");
  res = HttpClient(port).request(http::verb::head, "/js/app.js");
  EXPECT_EQ(res.result_int(), 200);
  EXPECT_EQ(res[http::field::content_length], "15");
  EXPECT_TRUE(res.body().empty());
}

TEST_F(StaticFilesTest, NothingOutsideTheRoot) {
  HttpServerOptions o;
  o.web_root = (base / "web").string();
  start(o);
  for (const std::string target :
       {"/../secret", "/%2e%2e/secret", "/%2E%2E%2fsecret", "/a/../../secret", "/js/../../secret",
        "/..%5csecret", "/js/link.js", "/js/app.js%00.html", "/missing.html", "/js/sub",
        "/js/sub/"}) {
    const auto res = get(port, target);
    EXPECT_EQ(res.result_int(), 404) << target;
    EXPECT_EQ(res.body().find("TOPSECRET"), std::string::npos) << target;
    EXPECT_EQ(res[http::field::content_type], "application/problem+json") << target;
  }
}

// Regression: the test suite, package files and node_modules' bookkeeping were served.
TEST_F(StaticFilesTest, OnlyTheDashboardsFilesAreServed) {
  HttpServerOptions o;
  o.web_root = (base / "web").string();
  start(o);
  for (const std::string target :
       {"/tests/e2e.test.mjs", "/package-lock.json", "/package.json",
        "/node_modules/.package-lock.json", "/node_modules/plotly.js-dist-min/package.json",
        "/node_modules/", "/tests/"}) {
    const auto res = get(port, target);
    EXPECT_EQ(res.result_int(), 404) << target;
    EXPECT_EQ(res[http::field::content_type], "application/problem+json") << target;
  }
}

// Regression: responses had no Content-Security-Policy and no framing protection.
TEST_F(StaticFilesTest, EveryResponseCarriesTheSecurityHeaders) {
  HttpServerOptions o;
  o.web_root = (base / "web").string();
  start(o);
  for (const std::string target : {"/", "/js/app.js", "/missing", "/api/v1/echo"}) {
    const auto res = get(port, target);
    const std::string csp(res["Content-Security-Policy"]);
    EXPECT_NE(csp.find("default-src 'self'"), std::string::npos) << target;
    EXPECT_NE(csp.find("frame-ancestors 'none'"), std::string::npos) << target;
    EXPECT_EQ(res["X-Content-Type-Options"], "nosniff") << target;
    EXPECT_EQ(res["X-Frame-Options"], "DENY") << target;
  }
}

TEST_F(StaticFilesTest, OnlyGetAndHead) {
  HttpServerOptions o;
  o.web_root = (base / "web").string();
  start(o);
  const auto res = HttpClient(port).request(http::verb::post, "/index.html", "x");
  EXPECT_EQ(res.result_int(), 405);
  EXPECT_EQ(res[http::field::allow], "GET, HEAD");
}

// Regression: files came without validators, so every page load read and sent them again.
TEST_F(StaticFilesTest, ConditionalRequestsAreAnsweredWith304) {
  HttpServerOptions o;
  o.web_root = (base / "web").string();
  start(o);
  HttpClient c(port);
  const auto full = c.request(http::verb::get, "/js/app.js");
  ASSERT_EQ(full.result_int(), 200);
  const std::string etag(full[http::field::etag]);
  const std::string modified(full[http::field::last_modified]);
  ASSERT_FALSE(etag.empty());
  EXPECT_EQ(etag.front(), '"');
  ASSERT_TRUE(avk::server::StaticFiles::parse_http_date(modified)) << modified;
  EXPECT_EQ(full[http::field::cache_control], "no-cache");

  // The same connection: a 304 has no body, so keep-alive framing must hold.
  for (const std::string& tag : {etag, "W/" + etag, "\"other\", " + etag, std::string("*")}) {
    const auto again = c.request(http::verb::get, "/js/app.js", "", {{"If-None-Match", tag}});
    EXPECT_EQ(again.result_int(), 304) << tag;
    EXPECT_TRUE(again.body().empty());
    EXPECT_EQ(again[http::field::etag], etag);
    EXPECT_EQ(again["X-Content-Type-Options"], "nosniff");
  }
  EXPECT_EQ(
      c.request(http::verb::get, "/js/app.js", "", {{"If-None-Match", "\"other\""}}).result_int(),
      200);
  EXPECT_EQ(c.request(http::verb::head, "/js/app.js", "", {{"If-None-Match", etag}}).result_int(),
            304);
  EXPECT_EQ(
      c.request(http::verb::get, "/js/app.js", "", {{"If-Modified-Since", modified}}).result_int(),
      304);
  EXPECT_EQ(c.request(http::verb::get, "/js/app.js", "",
                      {{"If-Modified-Since", "Sat, 01 Jan 2000 00:00:00 GMT"}})
                .result_int(),
            200);
  // If-None-Match decides alone when both are sent (RFC 9110 13.1.3).
  EXPECT_EQ(c.request(http::verb::get, "/js/app.js", "",
                      {{"If-None-Match", "\"other\""}, {"If-Modified-Since", modified}})
                .result_int(),
            200);
  // An unreadable date is ignored.
  EXPECT_EQ(c.request(http::verb::get, "/js/app.js", "", {{"If-Modified-Since", "yesterday"}})
                .result_int(),
            200);
  // Validators differ between files.
  EXPECT_EQ(
      c.request(http::verb::get, "/css/style.css", "", {{"If-None-Match", etag}}).result_int(),
      200);
}

// The file list is read at the start, each file's bytes when it changes: an edited file is served
// as it is now, with a new ETag; one that became a symlink since is not followed.
TEST_F(StaticFilesTest, AnEditedFileIsServedAnewAndALinkPutInItsPlaceIsNot) {
  HttpServerOptions o;
  o.web_root = (base / "web").string();
  start(o);
  const auto before = get(port, "/js/app.js");
  ASSERT_EQ(before.body(), "console.log(1);");
  write(base / "web" / "js" / "app.js", "console.log('edited');");
  const auto after = get(port, "/js/app.js");
  EXPECT_EQ(after.body(), "console.log('edited');");
  EXPECT_NE(after[http::field::etag], before[http::field::etag]);
  // Added after the start: not in the list.
  write(base / "web" / "js" / "new.js", "new");
  EXPECT_EQ(get(port, "/js/new.js").result_int(), 404);
  fs::remove(base / "web" / "css" / "style.css");
  fs::create_symlink(base / "secret", base / "web" / "css" / "style.css");
  const auto swapped = get(port, "/css/style.css");
  EXPECT_EQ(swapped.result_int(), 404);
  EXPECT_EQ(swapped.body().find("TOPSECRET"), std::string::npos);
}

TEST(HttpDate, FormatsAndParsesImfFixdate) {
  using avk::server::StaticFiles;
  EXPECT_EQ(StaticFiles::http_date(784111777), "Sun, 06 Nov 1994 08:49:37 GMT");
  EXPECT_EQ(StaticFiles::parse_http_date("Sun, 06 Nov 1994 08:49:37 GMT"), 784111777);
  EXPECT_EQ(StaticFiles::parse_http_date(StaticFiles::http_date(1700000000)), 1700000000);
  for (const char* bad : {"", "Sunday, 06-Nov-94 08:49:37 GMT", "Sun Nov  6 08:49:37 1994",
                          "Sun, 31 Feb 1994 08:49:37 GMT", "Sun, 06 Nov 1994 25:49:37 GMT",
                          "Sun, 06 Xyz 1994 08:49:37 GMT", "Sun, 06 Nov 1994 08:49:37 UTC"})
    EXPECT_FALSE(StaticFiles::parse_http_date(bad)) << bad;
}

TEST_F(StaticFilesTest, WithoutAWebRootOnlyTheApi) {
  start();
  EXPECT_EQ(get(port, "/").result_int(), 404);
  EXPECT_EQ(get(port, "/index.html").result_int(), 404);
  EXPECT_EQ(get(port, "/api/v1/echo").result_int(), 200);
}

TEST_F(StaticFilesTest, MissingWebRootIsAnError) {
  HttpServerOptions o;
  o.web_root = (base / "nope").string();
  EXPECT_THROW(HttpServer(o, api, hub), std::runtime_error);
}

}  // namespace
