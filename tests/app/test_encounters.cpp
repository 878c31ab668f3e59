// The encounter bench: the scenario file and its errors, one maneuver flown in the simulator
// against analytic cases, the generator, and the bench on a tiny database (a handful of
// scenarios at a coarse candidate step; never the full file).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>

#include "app/context.hpp"
#include "app/encounters.hpp"
#include "app/store_access.hpp"
#include "kinematics/angles.hpp"
#include "sim/sim_config.hpp"
#include "support/stored_turns.hpp"
#include "support/temp_db.hpp"

namespace {

using namespace avk;
namespace kin = avk::kinematics;

const char* kValid = R"({"schema_version": 1, "standoff_m": 10.0, "horizon_s": 120,
  "scenarios": [
    {"name": "crossing-from-starboard-40m", "own": {"heading_deg": 0, "speed_mps": 1.0},
     "contacts": [{"x_m": 30.0, "y_m": 30.0, "course_deg": 270, "speed_mps": 1.0}],
     "standoff_m": 8.0},
    {"name": "head-on-50m", "own": {"heading_deg": 90, "speed_mps": 1.5},
     "contacts": [{"x_m": 50.0, "y_m": 2.0, "course_deg": 270, "speed_mps": 0.5}]}
  ]})";

std::set<std::string> fields_of(const app::Error& e) {
  std::set<std::string> out;
  for (const auto& f : e.fields)
    out.insert(f.field);
  return out;
}

// The valid document with one replacement made.
std::string with(const std::string& from, const std::string& to) {
  std::string s = kValid;
  const auto at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return s.replace(at, from.size(), to);
}

TEST(EncounterFile, ReadsScenariosAndTheScenarioStandoffOverridesTheFiles) {
  const auto f = app::parse_encounter_file(kValid);
  ASSERT_TRUE(f) << f.error().message;
  EXPECT_EQ(f->schema_version, 1);
  EXPECT_DOUBLE_EQ(f->horizon_s, 120.0);
  ASSERT_EQ(f->scenarios.size(), 2u);
  EXPECT_EQ(f->scenarios[0].name, "crossing-from-starboard-40m");
  EXPECT_DOUBLE_EQ(f->scenarios[0].standoff_m, 8.0);   // its own
  EXPECT_DOUBLE_EQ(f->scenarios[1].standoff_m, 10.0);  // the file's
  EXPECT_DOUBLE_EQ(f->scenarios[1].own_heading_deg, 90.0);
  EXPECT_DOUBLE_EQ(f->scenarios[1].own_speed_mps, 1.5);
  ASSERT_EQ(f->scenarios[0].contacts.size(), 1u);
  EXPECT_DOUBLE_EQ(f->scenarios[0].contacts[0].x_m, 30.0);
  EXPECT_DOUBLE_EQ(f->scenarios[0].contacts[0].course_deg, 270.0);
}

TEST(EncounterFile, EachProblemIsNamedByItsJsonPointer) {
  const std::pair<std::string, std::string> cases[] = {
      {with("\"schema_version\": 1", "\"schema_version\": 2"), "/schema_version"},
      {with("\"standoff_m\": 10.0", "\"standoff_m\": 0"), "/standoff_m"},
      {with("\"horizon_s\": 120", "\"horizon_s\": 1000"), "/horizon_s"},
      {with("\"horizon_s\": 120", "\"horizon_s\": 120, \"colour\": 1"), "/colour"},
      {with("\"course_deg\": 270, \"speed_mps\": 1.0", "\"course_deg\": 270, \"speed_mps\": -1"),
       "/scenarios/0/contacts/0/speed_mps"},
      {with("\"heading_deg\": 90, \"speed_mps\": 1.5", "\"heading_deg\": 90, \"speed_mps\": 0"),
       "/scenarios/1/own/speed_mps"},
      {with("\"heading_deg\": 0,", "\"heading_deg\": \"north\","), "/scenarios/0/own/heading_deg"},
      {with("\"x_m\": 50.0,", ""), "/scenarios/1/contacts/0/x_m"},
      {with("\"standoff_m\": 8.0", "\"standoff_m\": 8.0, \"speed\": 3"), "/scenarios/0/speed"},
      {with("\"head-on-50m\"", "\"crossing-from-starboard-40m\""), "/scenarios/1/name"},
      {with(
           "\"contacts\": [{\"x_m\": 50.0, \"y_m\": 2.0, \"course_deg\": 270, \"speed_mps\": 0.5}]",
           "\"contacts\": []"),
       "/scenarios/1/contacts"},
  };
  for (const auto& [text, pointer] : cases) {
    const auto f = app::parse_encounter_file(text);
    ASSERT_FALSE(f) << pointer;
    EXPECT_EQ(f.error().code, app::ErrorCode::invalid_argument);
    EXPECT_EQ(fields_of(f.error()), std::set<std::string>{pointer}) << text;
  }
  const auto empty = app::parse_encounter_file(R"({"schema_version": 1, "scenarios": []})");
  ASSERT_FALSE(empty);
  EXPECT_EQ(fields_of(empty.error()), std::set<std::string>{"/scenarios"});
  const auto not_json = app::parse_encounter_file("{\"schema_version\": ");
  ASSERT_FALSE(not_json);
  EXPECT_EQ(not_json.error().code, app::ErrorCode::invalid_argument);
}

TEST(EncounterFile, CollectsSeveralFieldErrors) {
  std::string s = with("\"horizon_s\": 120", "\"horizon_s\": -1");
  s.replace(s.find("\"schema_version\": 1"), 19, "\"schema_version\": 3");
  s.replace(s.find("\"speed_mps\": 0.5"), 16, "\"speed_mps\": -0.5");
  const auto f = app::parse_encounter_file(s);
  ASSERT_FALSE(f);
  EXPECT_EQ(fields_of(f.error()), (std::set<std::string>{"/horizon_s", "/schema_version",
                                                         "/scenarios/1/contacts/0/speed_mps"}));
}

// ---- one maneuver flown ---------------------------------------------------------------------

app::SimulatedManeuverQuery calm_usim(double heading, double speed, double dheading,
                                      double horizon) {
  app::SimulatedManeuverQuery q;
  q.setup = sim::default_sim_setup("usim");
  q.seed = 3;
  q.own_heading_deg = heading;
  q.own_speed_mps = speed;
  q.dheading_deg = dheading;
  q.horizon_s = horizon;
  return q;
}

double heading_between(const kin::TimedPoint& a, const kin::TimedPoint& b) {
  return kin::heading_of_deg(b.x_m - a.x_m, b.y_m - a.y_m);
}

TEST(SimulateManeuver, HoldingCourseOnACalmUsimGoesStraightAlongTheHeadingAtTheSpeed) {
  auto q = calm_usim(30.0, 1.0, 0.0, 60.0);
  // A contact standing still 5 m to port of the track, 40 m ahead: CPA 5 m at 40 s.
  const double h = kin::deg_to_rad(30.0);
  q.contacts.push_back(
      {std::sin(h) * 40.0 - std::cos(h) * 5.0, std::cos(h) * 40.0 + std::sin(h) * 5.0, 0.0, 0.0});
  const auto m = app::simulate_maneuver(q);
  ASSERT_TRUE(m) << m.error().message;
  ASSERT_GT(m->track.size(), 100u);
  EXPECT_EQ(m->track.front(), (kin::TimedPoint{0.0, 0.0, 0.0}));
  EXPECT_NEAR(m->track.back().t_s, 60.0, 0.5);
  EXPECT_NEAR(m->heading_at_command_deg, 30.0, 0.5);
  EXPECT_GE(m->settle_s, 20.0);  // the settle leg's minimum
  for (const auto& p : m->track) {
    // Along the heading: cross-track (x cos h - y sin h) stays near zero; along-track at speed.
    EXPECT_NEAR(p.x_m * std::cos(h) - p.y_m * std::sin(h), 0.0, 0.1) << p.t_s;
    EXPECT_NEAR(p.x_m * std::sin(h) + p.y_m * std::cos(h), 1.0 * p.t_s, 0.05 * p.t_s + 0.1)
        << p.t_s;
  }
  ASSERT_EQ(m->cpa.size(), 1u);
  EXPECT_NEAR(m->cpa[0].distance_m, 5.0, 0.15);
  EXPECT_NEAR(m->cpa[0].time_s, 40.0, 2.5);
  EXPECT_DOUBLE_EQ(m->min_cpa_m, m->cpa[0].distance_m);
}

TEST(SimulateManeuver, AFlownNinetyDegreeTurnEndsNearHeadingPlusNinety) {
  for (const double dheading : {90.0, -90.0}) {
    const auto m = app::simulate_maneuver(calm_usim(10.0, 1.0, dheading, 60.0));
    ASSERT_TRUE(m) << m.error().message;
    const auto& t = m->track;
    ASSERT_GT(t.size(), 10u);
    const double final_heading = heading_between(t[t.size() - 5], t.back());
    EXPECT_NEAR(kin::angle180_deg(final_heading - (10.0 + dheading)), 0.0, 2.0) << dheading;
  }
}

TEST(SimulateManeuver, AHalfTurnGoesTheSideItWasAskedFor) {
  for (const double dheading : {180.0, -180.0}) {
    const auto m = app::simulate_maneuver(calm_usim(0.0, 1.0, dheading, 40.0));
    ASSERT_TRUE(m) << m.error().message;
    const auto widest = std::max_element(m->track.begin(), m->track.end(),
                                         [](const kin::TimedPoint& a, const kin::TimedPoint& b) {
                                           return std::abs(a.x_m) < std::abs(b.x_m);
                                         });
    // Heading north, a starboard turn swings east (x > 0), a port turn west.
    EXPECT_GT(widest->x_m * dheading, 0.0) << dheading;
    const auto& t = m->track;
    EXPECT_NEAR(kin::angle180_deg(heading_between(t[t.size() - 5], t.back()) - 180.0), 0.0, 3.0);
  }
}

TEST(SimulateManeuver, IsDeterministicForASeedWithDisturbances) {
  app::SimulatedManeuverQuery q;
  q.setup = sim::parse_sim_config(R"({"vehicle": "catamaran:m200",
      "wind": {"mean_speed_mps": 5.0, "from_deg": 250, "gust_sigma_mps": 1.5},
      "sensors": {"gnss_sigma_m": 0.3, "compass_sigma_deg": 1.0},
      "jitter_fraction": 0.05, "random_phases": true})",
                                  "catamaran:m200");
  q.own_heading_deg = 45.0;
  q.own_speed_mps = 1.0;
  q.dheading_deg = 40.0;
  q.horizon_s = 20.0;
  q.contacts.push_back({10.0, 20.0, 200.0, 0.8});
  q.seed = 7;
  const auto a = app::simulate_maneuver(q);
  const auto b = app::simulate_maneuver(q);
  q.seed = 8;
  const auto c = app::simulate_maneuver(q);
  ASSERT_TRUE(a && b && c);
  EXPECT_EQ(a->track, b->track);
  EXPECT_DOUBLE_EQ(a->min_cpa_m, b->min_cpa_m);
  EXPECT_NE(a->track, c->track);
  EXPECT_NEAR(a->track.back().t_s, 20.0, 0.2);
  // Steady on the scenario heading when commanded, within the ConditionSet's 2 deg (and noise).
  EXPECT_NEAR(kin::angle180_deg(a->heading_at_command_deg - 45.0), 0.0, 4.0);
}

TEST(SimulateManeuver, RejectsBadQueriesNamingTheField) {
  auto q = calm_usim(0.0, 0.0, 10.0, 60.0);
  EXPECT_EQ(app::simulate_maneuver(q).error().field, "own_speed");
  q = calm_usim(0.0, 1.0, 190.0, 60.0);
  EXPECT_EQ(app::simulate_maneuver(q).error().field, "dheading");
  q = calm_usim(0.0, 1.0, 10.0, 0.0);
  EXPECT_EQ(app::simulate_maneuver(q).error().field, "horizon");
  q = calm_usim(0.0, 1.0, 10.0, 60.0);
  q.contacts.push_back({0.0, 10.0, 0.0, -1.0});
  EXPECT_EQ(app::simulate_maneuver(q).error().field, "contacts/0/speed_mps");
}

// ---- the generator --------------------------------------------------------------------------

TEST(GenerateEncounters, IsReproducibleForASeedAndReadsBack) {
  const auto a = app::generate_encounters(11, 60);
  const auto b = app::generate_encounters(11, 60);
  const auto c = app::generate_encounters(12, 60);
  ASSERT_TRUE(a && b && c);
  const std::string text = app::encounter_file_json(*a);
  EXPECT_EQ(text, app::encounter_file_json(*b));
  EXPECT_NE(text, app::encounter_file_json(*c));
  const auto back = app::parse_encounter_file(text);
  ASSERT_TRUE(back) << back.error().message;
  ASSERT_EQ(back->scenarios.size(), 60u);
  for (std::size_t i = 0; i < 60; ++i) {
    EXPECT_EQ(back->scenarios[i].name, a->scenarios[i].name);
    ASSERT_EQ(back->scenarios[i].contacts.size(), a->scenarios[i].contacts.size());
    EXPECT_DOUBLE_EQ(back->scenarios[i].contacts[0].x_m, a->scenarios[i].contacts[0].x_m);
  }
  EXPECT_FALSE(app::generate_encounters(1, 0));
}

TEST(GenerateEncounters, EveryScenarioViolatesTheStandoffWhenKeepingCourse) {
  const auto f = app::generate_encounters(1, 60);
  ASSERT_TRUE(f);
  std::set<std::string> kinds;
  for (const auto& s : f->scenarios) {
    const double h = kin::deg_to_rad(s.own_heading_deg);
    const double run = s.own_speed_mps * f->horizon_s;
    const kin::TimedPath straight{{0.0, 0.0, 0.0},
                                  {f->horizon_s, std::sin(h) * run, std::cos(h) * run}};
    EXPECT_GE(s.own_speed_mps, 0.5);
    EXPECT_LE(s.own_speed_mps, 1.5);
    double nearest = 1e9;
    for (const auto& c : s.contacts) {
      EXPECT_LT(kin::closest_approach(straight, c).distance_m, s.standoff_m) << s.name;
      const double range = std::hypot(c.x_m, c.y_m);
      EXPECT_GE(range, 15.0) << s.name;
      EXPECT_LE(range, 80.0) << s.name;
      EXPECT_GE(c.speed_mps, 0.5) << s.name;
      EXPECT_LE(c.speed_mps, 1.5) << s.name;
      nearest = std::min(nearest, range);
    }
    // Named by type and range.
    EXPECT_NE(s.name.find(std::to_string(static_cast<int>(std::lround(nearest))) + "m"),
              std::string::npos)
        << s.name;
    kinds.insert(s.name.substr(0, s.name.find_first_of("0123456789") - 1));
  }
  EXPECT_EQ(kinds,
            (std::set<std::string>{"head-on", "crossing-from-starboard", "crossing-from-port",
                                   "overtaking", "overtaken", "several-contacts"}));
}

// ---- the bench ------------------------------------------------------------------------------

class EncounterBench : public ::testing::Test {
 protected:
  void SetUp() override { avk::testing::store_arc_turns(app::store_of(ctx_), "alpha"); }

  app::EncounterFile two_scenarios() {
    auto f = app::generate_encounters(5, 2);  // head-on, crossing from starboard
    EXPECT_TRUE(f);
    f->horizon_s = 60.0;
    return *f;
  }
  app::EncounterBenchQuery query(int threads) {
    app::EncounterBenchQuery q;
    q.vehicle_id = "alpha";
    q.setup = sim::default_sim_setup("usim");
    q.seed = 2;
    q.candidate_step_deg = 45.0;
    q.threads = threads;
    return q;
  }

  avk::testing::TempDb db_{"avk_app_encounters"};
  app::Context ctx_{db_.path()};
};

TEST_F(EncounterBench, FliesEveryCandidateOnceAndJudgesEachMethodsChoiceByItsFlight) {
  const auto file = two_scenarios();
  const auto bench = app::run_encounter_bench(ctx_, file, query(2));
  ASSERT_TRUE(bench) << bench.error().message;
  EXPECT_EQ(bench->flights, 2u * 9u);
  ASSERT_EQ(bench->summary.size(), 3u);
  // No model is stored: the model method is skipped with a note, the others answer.
  EXPECT_TRUE(bench->summary[0].available);
  EXPECT_FALSE(bench->summary[1].available);
  EXPECT_FALSE(bench->summary[1].note.empty());
  EXPECT_TRUE(bench->summary[2].available);
  ASSERT_EQ(bench->scenarios.size(), 2u);
  for (const auto& s : bench->scenarios) {
    ASSERT_EQ(s.candidates_deg.size(), 9u);
    ASSERT_EQ(s.flown_cpa_m.size(), 9u);
    // The held course is candidate 0 deg (index 4), and the generator made it violate.
    EXPECT_DOUBLE_EQ(s.course_held_cpa_m, s.flown_cpa_m[4]);
    EXPECT_EQ(s.safe_existed,
              *std::max_element(s.flown_cpa_m.begin(), s.flown_cpa_m.end()) >= s.standoff_m);
    ASSERT_EQ(s.methods.size(), 2u);
    for (const auto& r : s.methods) {
      if (r.chosen_dheading_deg) {
        const auto i =
            std::find(s.candidates_deg.begin(), s.candidates_deg.end(), *r.chosen_dheading_deg) -
            s.candidates_deg.begin();
        EXPECT_DOUBLE_EQ(r.actual_cpa_m, s.flown_cpa_m[static_cast<std::size_t>(i)]);
        ASSERT_TRUE(r.predicted_cpa_m);
      } else {
        EXPECT_DOUBLE_EQ(r.actual_cpa_m, s.course_held_cpa_m);
        EXPECT_EQ(r.no_maneuver_while_one_existed, s.safe_existed);
      }
      EXPECT_EQ(r.violation, r.actual_cpa_m < s.standoff_m);
      EXPECT_EQ(r.unsafe_while_safe_existed,
                r.chosen_dheading_deg && r.violation && s.safe_existed);
    }
    // The instantaneous method has no corridor.
    EXPECT_FALSE(s.methods[1].predicted_edge_cpa_m);
  }
  const auto& inst = bench->summary[2];
  EXPECT_EQ(inst.scenarios, 2);
  int violations = 0;
  for (const auto& s : bench->scenarios)
    violations += s.methods[1].violation ? 1 : 0;
  EXPECT_EQ(inst.violations, violations);
  EXPECT_DOUBLE_EQ(inst.violation_rate, violations / 2.0);
}

TEST_F(EncounterBench, ResultsDoNotDependOnTheThreads) {
  const auto file = two_scenarios();
  auto q = query(1);
  q.methods = {app::PredictionMethod::instantaneous};
  const auto one = app::run_encounter_bench(ctx_, file, q);
  q.threads = 2;
  const auto two = app::run_encounter_bench(ctx_, file, q);
  ASSERT_TRUE(one && two);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(one->scenarios[i].flown_cpa_m, two->scenarios[i].flown_cpa_m);
    EXPECT_EQ(one->scenarios[i].methods[0].chosen_dheading_deg,
              two->scenarios[i].methods[0].chosen_dheading_deg);
  }
}

TEST_F(EncounterBench, RejectsABadQueryNamingTheField) {
  auto q = query(2);
  q.candidate_step_deg = 0.0;
  EXPECT_EQ(app::run_encounter_bench(ctx_, two_scenarios(), q).error().field, "candidate_step");
  q = query(0);
  EXPECT_EQ(app::run_encounter_bench(ctx_, two_scenarios(), q).error().field, "threads");
}

}  // namespace
