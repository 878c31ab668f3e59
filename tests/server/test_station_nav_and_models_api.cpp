// The station's REST API for the navigation track, model headings (one step and simulated), and
// harvesting as a control endpoint.
#include <gtest/gtest.h>

#include "server/station_api_fixture.hpp"

namespace {

using namespace avk::testing::station_api;

TEST_F(StationApi, NavPagesConcatenateToTheStoredTrack) {
  const std::int64_t id = start_mission();
  wait_for(id, {"done"});
  const auto stored = avk::store::Store(db_.path()).navigation().for_mission(id);
  ASSERT_GT(stored.size(), 1000u);
  const std::string path = "/api/v1/missions/" + std::to_string(id) + "/nav";
  std::vector<json> rows;
  std::map<std::string, std::string> q = {{"limit", "400"}};
  int pages = 0;
  for (;;) {
    const ApiResponse r = call(get(path, q));
    ASSERT_EQ(r.status, 200) << r.body;
    const json page = body(r);
    ++pages;
    ASSERT_LE(page["items"].size(), 400u);
    for (const auto& item : page["items"])
      rows.push_back(item);
    if (page["next"].is_null()) break;
    q["after"] = page["next"].dump();
  }
  EXPECT_EQ(pages, static_cast<int>(stored.size() / 400 + 1));
  ASSERT_EQ(rows.size(), stored.size());
  // Insertion order is the recorder's time order for one run: the same rows as
  // navigation().for_mission.
  for (std::size_t i = 0; i < rows.size(); i += 97) {
    EXPECT_EQ(rows[i]["t_s"].get<double>(), stored[i].t_s);
    EXPECT_EQ(rows[i]["x_m"].get<double>(), stored[i].x_m);
    EXPECT_EQ(rows[i]["helm_mode"].get<std::string>(), stored[i].helm_mode);
    for (const char* k :
         {"y_m", "heading_deg", "speed_mps", "desired_heading_deg", "desired_speed_mps"})
      EXPECT_TRUE(rows[i].contains(k)) << k;
  }
  // The track as CSV, paged by X-Next-After, is the same rows as the JSON pages.
  const auto split = [](const std::string& text, char sep) {
    std::vector<std::string> out;
    std::string cell;
    std::istringstream in(text);
    while (std::getline(in, cell, sep))
      out.push_back(cell);
    return out;
  };
  std::vector<std::string> csv_rows;
  std::map<std::string, std::string> cq = {{"limit", "400"}, {"format", "csv"}};
  for (int page = 0; page < 1000; ++page) {
    const ApiResponse r = call(get(path, cq));
    ASSERT_EQ(r.status, 200) << r.body;
    ASSERT_EQ(r.content_type.rfind("text/csv", 0), 0u);
    const auto lines = split(r.body, '\n');
    ASSERT_FALSE(lines.empty());
    EXPECT_EQ(lines[0],
              "t_s,x_m,y_m,heading_deg,speed_mps,desired_heading_deg,desired_speed_mps,helm_mode");
    csv_rows.insert(csv_rows.end(), lines.begin() + 1, lines.end());
    const std::string next = header(r, "X-Next-After");
    if (next.empty()) break;
    cq["after"] = next;
  }
  ASSERT_EQ(csv_rows.size(), rows.size());
  for (std::size_t i = 0; i < rows.size(); i += 97) {
    const auto cells = split(csv_rows[i], ',');
    ASSERT_EQ(cells.size(), 8u) << csv_rows[i];
    EXPECT_EQ(std::stod(cells[0]), rows[i]["t_s"].get<double>());
    EXPECT_EQ(std::stod(cells[1]), rows[i]["x_m"].get<double>());
    EXPECT_EQ(std::stod(cells[3]), rows[i]["heading_deg"].get<double>());
    EXPECT_EQ(cells[5].empty(), rows[i]["desired_heading_deg"].is_null());
    EXPECT_EQ(cells[7], rows[i]["helm_mode"].get<std::string>());
  }
  // The event log likewise, with Accept instead of ?format=.
  const std::string events_path = "/api/v1/missions/" + std::to_string(id) + "/events";
  const json events = body(call(get(events_path, {{"limit", "1000"}})));
  ApiRequest events_csv = get(events_path, {{"limit", "1000"}});
  events_csv.accept = "text/csv";
  const auto event_lines = split(call(events_csv).body, '\n');
  ASSERT_EQ(event_lines.size(), events["items"].size() + 1);
  EXPECT_EQ(event_lines[0], "id,t_s,kind,message");
  for (std::size_t i = 0; i < events["items"].size(); ++i) {
    const json& e = events["items"][i];
    EXPECT_EQ(event_lines[i + 1].rfind(std::to_string(e["id"].get<std::int64_t>()) + ",", 0), 0u);
    EXPECT_NE(event_lines[i + 1].find("," + e["kind"].get<std::string>() + ","), std::string::npos);
  }
  ApiRequest vehicles_csv = get("/api/v1/vehicles");
  vehicles_csv.accept = "text/csv";
  const auto vehicle_lines = split(call(vehicles_csv).body, '\n');
  ASSERT_EQ(vehicle_lines.size(), 2u);
  EXPECT_EQ(vehicle_lines[0].rfind("id,kind,max_speed_mps,link,helm_mode,", 0), 0u);
  EXPECT_EQ(vehicle_lines[1].rfind("sim-usim,usim,", 0), 0u) << vehicle_lines[1];
  // The default page is 5000 rows.
  EXPECT_EQ(body(call(get(path)))["items"].size(), std::min<std::size_t>(stored.size(), 5000));
  EXPECT_EQ(call(get("/api/v1/missions/999/nav")).status, 404);
  // Where the vehicle was last seen: the track's latest row.
  const ApiResponse last = call(get("/api/v1/missions/" + std::to_string(id) + "/last-position"));
  ASSERT_EQ(last.status, 200) << last.body;
  EXPECT_EQ(body(last), rows.back());
  EXPECT_EQ(call(get("/api/v1/missions/999/last-position")).status, 404);
  for (const auto& [k, v] : std::vector<std::pair<std::string, std::string>>{
           {"limit", "0"}, {"limit", "10001"}, {"limit", "2.5"}, {"after", "-1"}, {"after", "x"}}) {
    const ApiResponse bad = call(get(path, {{k, v}}));
    EXPECT_EQ(bad.status, 400) << k << "=" << v;
    EXPECT_EQ(body(bad)["parameter"], k);
  }
}

TEST_F(StationApi, ModelHeadingsOneStepAndSimulated) {
  const std::int64_t id = start_mission();
  wait_for(id, {"done"});
  const ApiResponse fitted = call(
      post("/api/v1/vehicles/sim-usim/models", json{{"missions", {id}}, {"history_s", 3}}.dump()));
  ASSERT_EQ(fitted.status, 201) << fitted.body;
  const auto model_id = body(fitted)["id"].get<std::int64_t>();
  const std::string path = "/api/v1/models/" + std::to_string(model_id) + "/headings";
  const ApiResponse r = call(get(path, {{"mission", std::to_string(id)}}));
  ASSERT_EQ(r.status, 200) << r.body;
  const json h = body(r);
  EXPECT_DOUBLE_EQ(h["dt_s"].get<double>(), 0.25);
  const std::size_t warmup = 13;  // 3 s at 4 Hz, + 1 for the invariant form's increments
  EXPECT_EQ(h["warmup_samples"], warmup);
  ASSERT_FALSE(h["segments"].empty());
  std::size_t total = 0, compared = 0;
  double one_sq = 0.0, sim_sq = 0.0;
  for (const auto& s : h["segments"]) {
    const std::size_t n = s["heading_deg"].size();
    total += n;
    for (const char* k : {"desired_heading_deg", "one_step_deg", "simulated_deg"})
      ASSERT_EQ(s[k].size(), n) << k;
    for (std::size_t k = 0; k < n; ++k) {
      if (k < warmup) {
        EXPECT_TRUE(s["one_step_deg"][k].is_null()) << k;
        EXPECT_TRUE(s["simulated_deg"][k].is_null()) << k;
        continue;
      }
      ASSERT_TRUE(s["one_step_deg"][k].is_number()) << k;
      ASSERT_TRUE(s["simulated_deg"][k].is_number()) << k;
      const double measured = s["heading_deg"][k].get<double>();
      one_sq += std::pow(s["one_step_deg"][k].get<double>() - measured, 2);
      sim_sq += std::pow(s["simulated_deg"][k].get<double>() - measured, 2);
      ++compared;
    }
  }
  EXPECT_LE(total, 2400u);
  ASSERT_GT(compared, 100u);
  // One step from measured history is the easier problem: it must be closer on average.
  EXPECT_LT(one_sq, sim_sq);
  EXPECT_LT(std::sqrt(one_sq / compared), 2.0);

  const json capped = body(call(get(path, {{"mission", std::to_string(id)}, {"limit", "50"}})));
  std::size_t capped_total = 0;
  for (const auto& s : capped["segments"])
    capped_total += s["heading_deg"].size();
  EXPECT_EQ(capped_total, std::min<std::size_t>(total, 50));
  EXPECT_EQ(capped["segments"][0]["heading_deg"],
            json(std::vector<double>(h["segments"][0]["heading_deg"].begin(),
                                     h["segments"][0]["heading_deg"].begin() +
                                         static_cast<long>(std::min<std::size_t>(
                                             50, h["segments"][0]["heading_deg"].size())))));

  EXPECT_EQ(call(get("/api/v1/models/999/headings", {{"mission", std::to_string(id)}})).status,
            404);
  EXPECT_EQ(call(get(path, {{"mission", "999"}})).status, 404);
  EXPECT_EQ(call(get(path)).status, 400);
  EXPECT_EQ(call(get(path, {{"mission", std::to_string(id)}, {"limit", "0"}})).status, 400);
  std::int64_t empty = 0;
  {
    avk::store::Store s(db_.path());
    empty = s.missions().create("sim-usim", "no nav", "{}");
  }
  const ApiResponse none = call(get(path, {{"mission", std::to_string(empty)}}));
  EXPECT_EQ(none.status, 422) << none.body;
}

// Harvesting is a write (the token always), and its counts come back; the CKT
// endpoints take include=collection|harvested.
TEST_F(StationApi, HarvestIsAControlEndpointAndTheTableSaysWhatItIncludes) {
  const std::int64_t id = start_mission();
  wait_for(id, {"done"});
  const std::string path = "/api/v1/missions/" + std::to_string(id) + "/harvest";
  EXPECT_EQ(call(post(path, "", "")).status, 401);
  const ApiResponse r = call(post(path, ""));
  ASSERT_EQ(r.status, 200) << r.body;
  const json h = body(r);
  EXPECT_EQ(h["mission_id"], id);
  EXPECT_GE(h["already_recorded"].get<int>(), 4);  // the mission's own turns, not twice
  EXPECT_EQ(h["steps"].get<int>(), h["harvested"].get<int>() + h["already_recorded"].get<int>() +
                                       h["rejected"].get<int>());
  EXPECT_EQ(h["rejected_by_reason"].size(), 13u);
  EXPECT_EQ(call(post("/api/v1/missions/999/harvest", "")).status, 404);
  EXPECT_EQ(body(call(get("/api/v1/vehicles/sim-usim/ckt")))["include"], "collection");
  EXPECT_EQ(body(call(get("/api/v1/vehicles/sim-usim/ckt", {{"include", "harvested"}})))["include"],
            "harvested");
  const ApiResponse bad = call(get("/api/v1/vehicles/sim-usim/ckt", {{"include", "all"}}));
  EXPECT_EQ(bad.status, 400);
  EXPECT_NE(bad.body.find("include"), std::string::npos);
  EXPECT_EQ(call(get("/api/v1/vehicles/sim-usim/predict",
                     {{"speed", "0.5"}, {"dheading", "40"}, {"include", "harvested"}}))
                .status,
            200);
}

}  // namespace
