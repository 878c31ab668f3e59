// The route table alone: patterns with parameters, 404 against 405 with Allow, HEAD as GET, the
// token rule per route (and before the route is told to anyone from afar), each route's body
// limit, and a handler's RequestError as problem+json.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "server/http/router.hpp"

namespace {

using avk::server::Access;
using avk::server::ApiRequest;
using avk::server::ApiResponse;
using avk::server::PathParams;
using avk::server::Representation;
using avk::server::RequestError;
using avk::server::Router;
using nlohmann::json;

Router make_router() {
  Router r("secret-token");
  r.add({"GET", "/api/v1/things/{id}", Access::read, std::nullopt,
         [](const ApiRequest& q, const PathParams& p) {
           return ApiResponse{
               200, "application/json", json{{"id", p.at("id")}, {"m", q.method}}.dump(), {}};
         }});
  r.add({"POST", "/api/v1/things/{id}", Access::control, std::size_t{4096},
         [](const ApiRequest&, const PathParams&) {
           return ApiResponse{201, "", "", {}};
         }});
  r.add({"GET", "/api/v1/things/{id}/bad", Access::read, std::nullopt,
         [](const ApiRequest&, const PathParams&) -> ApiResponse {
           throw RequestError(400, "parameter 'x': missing", {{"parameter", "x"}});
         }});
  return r;
}

ApiRequest request(const std::string& method, const std::string& path, bool loopback = true,
                   const std::string& auth = "") {
  ApiRequest q;
  q.method = method;
  q.path = path;
  q.remote_is_loopback = loopback;
  q.authorization = auth;
  return q;
}

std::string header(const ApiResponse& r, const std::string& name) {
  for (const auto& [k, v] : r.headers)
    if (k == name) return v;
  return "";
}

TEST(Router, MatchesPatternsAndCapturesParameters) {
  Router r = make_router();
  const auto res = r.handle(request("GET", "/api/v1/things/a%20b"));
  ASSERT_EQ(res.status, 200);
  EXPECT_EQ(json::parse(res.body)["id"], "a%20b");
  // HEAD is answered by the GET route (the transport drops the body).
  const auto head = r.handle(request("HEAD", "/api/v1/things/7"));
  EXPECT_EQ(head.status, 200);
  EXPECT_EQ(json::parse(head.body)["m"], "HEAD");
}

TEST(Router, NoRouteIs404AndAWrongMethodIs405WithAllow) {
  Router r = make_router();
  EXPECT_EQ(r.handle(request("GET", "/api/v1/things")).status, 404);
  EXPECT_EQ(r.handle(request("GET", "/api/v1/things/7/8/9")).status, 404);
  const auto res = r.handle(request("DELETE", "/api/v1/things/7"));
  EXPECT_EQ(res.status, 405);
  EXPECT_EQ(header(res, "Allow"), "GET, POST");
  EXPECT_EQ(res.content_type, "application/problem+json");
}

TEST(Router, ControlNeedsTheTokenEverywhereAndReadsOnlyFromAfar) {
  Router r = make_router();
  EXPECT_EQ(r.handle(request("POST", "/api/v1/things/7")).status, 401);
  EXPECT_EQ(header(r.handle(request("POST", "/api/v1/things/7")), "WWW-Authenticate"), "Bearer");
  EXPECT_EQ(r.handle(request("POST", "/api/v1/things/7", true, "Bearer secret-token")).status, 201);
  EXPECT_EQ(r.handle(request("GET", "/api/v1/things/7", false)).status, 401);
  EXPECT_EQ(r.handle(request("GET", "/api/v1/things/7", false, "bearer  secret-token")).status,
            200);
  // From afar without the token, a path that is no route is a 401 too: routes are not told.
  EXPECT_EQ(r.handle(request("GET", "/api/v1/nothing", false)).status, 401);
  EXPECT_EQ(r.handle(request("GET", "/api/v1/nothing", false, "Bearer secret-token")).status, 404);
}

TEST(Router, AdmissionGivesTheRoutesBodyLimitAndRefusesBeforeTheBody) {
  Router r = make_router();
  const auto post = r.admit(request("POST", "/api/v1/things/7", true, "Bearer secret-token"));
  EXPECT_FALSE(post.refusal);
  EXPECT_EQ(post.body_limit_bytes, std::size_t{4096});
  const auto refused = r.admit(request("POST", "/api/v1/things/7"));
  ASSERT_TRUE(refused.refusal);
  EXPECT_EQ(refused.refusal->status, 401);
  const auto get = r.admit(request("GET", "/api/v1/things/7"));
  EXPECT_FALSE(get.refusal);
  EXPECT_FALSE(get.body_limit_bytes);
  EXPECT_TRUE(r.admit(request("GET", "/api/v1/things/7", false)).refusal);
}

TEST(Router, AHandlersRequestErrorIsAProblem) {
  Router r = make_router();
  const auto res = r.handle(request("GET", "/api/v1/things/7/bad"));
  EXPECT_EQ(res.status, 400);
  EXPECT_EQ(res.content_type, "application/problem+json");
  const json p = json::parse(res.body);
  EXPECT_EQ(p["parameter"], "x");
  EXPECT_EQ(p["title"], "Bad Request");
}

// Content negotiation: ?format= wins; q weights count, q=0 excludes; a type is
// weighed by the most specific range covering it; a tie goes to the more specific range, then
// to the first offered; nothing acceptable is a 406 naming what is offered.
TEST(Router, ChoosesARepresentationByFormatThenAccept) {
  const std::vector<Representation> offered{avk::server::kJsonRepresentation,
                                            avk::server::kCsvRepresentation};
  const auto pick = [&](const std::string& accept, const std::string& format = "") {
    ApiRequest q = request("GET", "/x");
    q.accept = accept;
    if (!format.empty()) q.query["format"] = format;
    return avk::server::choose_representation(q, offered).format;
  };
  EXPECT_EQ(pick(""), "json");
  EXPECT_EQ(pick("*/*"), "json");
  EXPECT_EQ(pick("text/csv"), "csv");
  EXPECT_EQ(pick("text/csv, */*"), "csv") << "the named type beats the wildcard";
  EXPECT_EQ(pick("application/json;q=0.5, text/csv"), "csv");
  EXPECT_EQ(pick("text/*;q=0.2, application/*;q=0.9"), "json");
  EXPECT_EQ(pick("*/*, text/csv;q=0"), "json") << "q=0 on the specific range excludes it";
  EXPECT_EQ(pick("TEXT/CSV ; Q=1"), "csv") << "case-insensitive";
  EXPECT_EQ(pick("image/png", "csv"), "csv") << "?format= wins over Accept";
  try {
    pick("image/png, application/json;q=0");
    ADD_FAILURE() << "no 406";
  } catch (const RequestError& e) {
    EXPECT_EQ(e.status(), 406);
    EXPECT_EQ(e.extra()["acceptable"], json::array({"application/json", "text/csv"}));
  }
  try {
    pick("", "xml");
    ADD_FAILURE() << "no 400";
  } catch (const RequestError& e) {
    EXPECT_EQ(e.status(), 400);
    EXPECT_EQ(e.extra()["parameter"], "format");
    EXPECT_NE(std::string(e.what()).find("json or csv"), std::string::npos) << e.what();
  }
}

TEST(Router, AdmissionSaysHowMuchWorkTheRouteTakes) {
  using avk::server::RouteCost;
  using avk::server::Workload;
  Router r("secret-token");
  const auto ok = [](const ApiRequest&, const PathParams&) { return ApiResponse{}; };
  r.add({"GET", "/api/v1/ping", Access::read, std::nullopt, ok}, RouteCost{Workload::immediate});
  r.add({"GET", "/api/v1/answer", Access::read, std::nullopt, ok},
        RouteCost{Workload::cheap, {"deep"}});
  r.add({"GET", "/api/v1/study", Access::read, std::nullopt, ok}, RouteCost{Workload::expensive});
  r.add({"GET", "/api/v1/plain", Access::read, std::nullopt, ok});
  EXPECT_EQ(r.admit(request("GET", "/api/v1/ping")).workload, Workload::immediate);
  EXPECT_EQ(r.admit(request("GET", "/api/v1/answer")).workload, Workload::cheap);
  auto deep = request("GET", "/api/v1/answer");
  deep.query["deep"] = "1";
  EXPECT_EQ(r.admit(deep).workload, Workload::expensive);
  EXPECT_EQ(r.admit(request("GET", "/api/v1/study")).workload, Workload::expensive);
  EXPECT_EQ(r.admit(request("HEAD", "/api/v1/study")).workload, Workload::expensive);
  EXPECT_EQ(r.admit(request("GET", "/api/v1/plain")).workload, Workload::cheap);
}

}  // namespace
