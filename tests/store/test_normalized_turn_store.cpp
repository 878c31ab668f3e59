// The packed normalised turns the CKT is built from, as the store writes and reads them, and the
// yaw models and newest turn kept per vehicle.
#include <gtest/gtest.h>

#include "support/store_engines.hpp"

#include "store/mission_rows.hpp"

using namespace avk::testing::mission_rows;

class NormalizedTurnsOnEngine : public avk::testing::OnEachEngine {};
AVK_ON_EACH_ENGINE(NormalizedTurnsOnEngine);

TEST_P(NormalizedTurnsOnEngine, LoadNormalizedTurnsEqualsGetTurn) {
  Store s(db());
  const auto m1 = make_mission(s, "usim-1");
  const auto m2 = make_mission(s, "usim-2");
  TurnSequence warned = arc(1.5, -160.0, 4);
  warned.add_warning("NAV_X stream cut by 1 value");
  TurnSequence pre_normalized = arc(0.5, 70.0, 5).normalized();
  std::vector<std::int64_t> ok_m1, ok_m2;
  ok_m1.push_back(s.turns().add(m1, arc(1.0, 90.0, 1), TurnStatus::ok, "", {3.0, {}, {}}));
  ok_m1.push_back(s.turns().add(m1, arc(1.0, -40.0, 2), TurnStatus::ok, "kept despite drift"));
  s.turns().add(m1, arc(1.0, 90.0, 3), TurnStatus::aborted, "halt");
  ok_m1.push_back(s.turns().add(m1, warned, TurnStatus::ok, ""));
  ok_m2.push_back(s.turns().add(m2, arc(0.5, 10.0, 6, "usim-2"), TurnStatus::ok, ""));
  s.turns().add(m2, arc(0.5, 10.0, 7, "usim-2"), TurnStatus::rejected, "noisy");
  ok_m1.push_back(s.turns().add(m1, pre_normalized, TurnStatus::ok, ""));
  // The turn's own vehicle, not the mission's, is what the vehicle filter matches.
  ok_m2.push_back(s.turns().add(m2, arc(1.5, 130.0, 8, "usim-1"), TurnStatus::ok, ""));

  const auto expect_turns = [&](const std::vector<TurnSequence>& got,
                                const std::vector<std::int64_t>& ids) {
    ASSERT_EQ(got.size(), ids.size());
    for (std::size_t i = 0; i < ids.size(); ++i) {
      const auto stored = s.turns().get(ids[i]);
      ASSERT_TRUE(stored && stored->normalized);
      EXPECT_EQ(got[i], *stored->normalized) << "turn " << ids[i];
      EXPECT_EQ(got[i].warnings(), stored->normalized->warnings()) << "turn " << ids[i];
      EXPECT_EQ(avk::kinematics::to_json_string(got[i]),
                avk::kinematics::to_json_string(*stored->normalized));
    }
  };
  const std::vector<std::int64_t> all = {ok_m1[0], ok_m1[1], ok_m1[2],
                                         ok_m2[0], ok_m1[3], ok_m2[1]};
  expect_turns(s.turns().load_normalized({}), all);
  expect_turns(s.turns().load_normalized({m1, m2}), all);
  expect_turns(s.turns().load_normalized({m2, m1, m1}), all);
  expect_turns(s.turns().load_normalized({m1}), ok_m1);
  expect_turns(s.turns().load_normalized({m2}), ok_m2);
  expect_turns(s.turns().load_normalized({}, "usim-2"), {ok_m2[0]});
  expect_turns(s.turns().load_normalized({}, "usim-1"),
               {ok_m1[0], ok_m1[1], ok_m1[2], ok_m1[3], ok_m2[1]});
  expect_turns(s.turns().load_normalized({m2}, "usim-1"), {ok_m2[1]});
  EXPECT_TRUE(s.turns().load_normalized({m1}, "usim-2").empty());
  EXPECT_TRUE(s.turns().load_normalized({}, "ghost").empty());
  EXPECT_TRUE(s.turns().load_normalized({m2 + 10}).empty());
  // Left out: one mission's turns, one turn, or both; with or without a mission list.
  TurnsLeftOut no_m1;
  no_m1.mission_id = m1;
  expect_turns(s.turns().load_normalized({}, std::nullopt, false, TurnFrameChoice::ground, no_m1),
               ok_m2);
  expect_turns(s.turns().load_normalized({m1}, std::nullopt, false, TurnFrameChoice::ground, no_m1),
               {});
  TurnsLeftOut no_turn;
  no_turn.turn_id = ok_m1[1];
  expect_turns(s.turns().load_normalized({m1}, "usim-1", false, TurnFrameChoice::ground, no_turn),
               {ok_m1[0], ok_m1[2], ok_m1[3]});
  no_turn.mission_id = m2;
  expect_turns(s.turns().load_normalized({}, std::nullopt, false, TurnFrameChoice::ground, no_turn),
               {ok_m1[0], ok_m1[2], ok_m1[3]});
  // A turn's row alone equals the row turns().get reads with its documents.
  const auto row = s.turns().get_row(ok_m2[1]);
  ASSERT_TRUE(row.has_value());
  EXPECT_EQ(row->mission_id, m2);
  EXPECT_EQ(row->vehicle_id, "usim-1");
  EXPECT_EQ(row->goal_dheading_deg, s.turns().get(ok_m2[1])->row.goal_dheading_deg);
  EXPECT_FALSE(s.turns().get_row(ok_m2[1] + 100).has_value());

  const auto loaded = s.turns().load_normalized({m1});
  EXPECT_EQ(loaded[0], arc(1.0, 90.0, 1).normalized());
  EXPECT_EQ(loaded[3], pre_normalized);
  EXPECT_EQ(loaded[1].meta().status_reason, "kept despite drift");
  for (const auto& t : loaded) {
    EXPECT_TRUE(t.meta().normalized);
    EXPECT_EQ(t.meta().status, TurnStatus::ok);
  }
}

TEST_P(NormalizedTurnsOnEngine, LoadNormalizedTurnsEmptyDatabase) {
  Store s(db());
  EXPECT_TRUE(s.turns().load_normalized({}).empty());
  EXPECT_TRUE(s.turns().load_normalized({1, 2}).empty());
  EXPECT_TRUE(s.turns().load_normalized({}, "usim-1").empty());
}

TEST_P(NormalizedTurnsOnEngine, NormalizedSamplesArePackedLittleEndianFloat64) {
  std::int64_t id = 0;
  TurnSequence norm;
  {
    Store s(db());
    const auto m = make_mission(s);
    id = s.turns().add(m, arc(1.0, -70.0, 9), TurnStatus::ok, "");
    norm = *s.turns().get(id)->normalized;
  }
  {
    Store raw(db());
    Database& c = raw.database();
    auto q = c.prepare("SELECT normalized_samples FROM turns WHERE id = ?");
    q.bind(1, id);
    ASSERT_TRUE(q.step());
    const auto blob = q.column_blob(0);
    ASSERT_EQ(blob.size(), norm.samples().size() * 5 * 8);
    const auto value = [&](std::size_t k) {
      std::uint64_t bits = 0;
      for (std::size_t b = 0; b < 8; ++b)
        bits |= static_cast<std::uint64_t>(blob[8 * k + b]) << (8 * b);
      return std::bit_cast<double>(bits);
    };
    for (std::size_t i = 0; i < norm.samples().size(); ++i) {
      const auto& p = norm.samples()[i];
      EXPECT_EQ(value(5 * i + 0), p.t_s);
      EXPECT_EQ(value(5 * i + 1), p.x_m);
      EXPECT_EQ(value(5 * i + 2), p.y_m);
      EXPECT_EQ(value(5 * i + 3), p.heading_deg);
      EXPECT_EQ(value(5 * i + 4), p.speed_mps);
    }
    // With the JSON document broken, only the packed path can still produce the turn.
    c.exec("UPDATE turns SET normalized_json = '{'");
  }
  Store s(db());
  const auto loaded = s.turns().load_normalized({});
  ASSERT_EQ(loaded.size(), 1u);
  EXPECT_EQ(loaded[0], norm);
  EXPECT_THROW(s.turns().get(id), StoreError);
}

TEST_P(NormalizedTurnsOnEngine, CorruptPackedSamplesNameTheTurn) {
  std::int64_t id = 0;
  {
    Store s(db());
    id = s.turns().add(make_mission(s), arc(1.0, 90.0), TurnStatus::ok, "");
  }
  {
    Store raw(db());
    const unsigned char truncated[] = {0, 1, 2, 3};
    raw.database().prepare("UPDATE turns SET normalized_samples = ?").bind_blob(1, truncated).run();
  }
  Store s(db());
  try {
    s.turns().load_normalized({});
    FAIL() << "a truncated sample blob was read";
  } catch (const StoreError& e) {
    EXPECT_NE(std::string(e.what()).find("turn " + std::to_string(id)), std::string::npos)
        << e.what();
  }
}

TEST_P(NormalizedTurnsOnEngine, YawModelsRoundTripAndAreFoundByVehicle) {
  Store s(db());
  EXPECT_FALSE(s.models().latest().has_value());
  StoredModel m;
  m.vehicle_id = "cat-1";
  m.training_missions = {3, 5};
  m.model.form = avk::kinematics::YawModelForm::thesis;
  m.model.history = 2;
  m.model.error_coeffs = {0.25, -0.125};
  m.model.heading_coeffs = {1.5, -0.5};
  m.model.ridge_lambda = 1e-4;
  m.model.refined = true;
  m.model.speed = avk::kinematics::SpeedModel{0.2, 0.01, -0.001};
  m.train_one_step_rms_deg = 1.25;
  m.validation_mse_m2 = 2.5;
  const auto a = s.models().save(m);
  m.vehicle_id = "usim-1";
  m.validation_mse_m2.reset();
  const auto b = s.models().save(m);
  const auto got = s.models().get(a);
  ASSERT_TRUE(got.has_value());
  EXPECT_EQ(got->vehicle_id, "cat-1");
  EXPECT_EQ(got->training_missions, (std::vector<std::int64_t>{3, 5}));
  EXPECT_EQ(got->model.error_coeffs, m.model.error_coeffs);
  EXPECT_EQ(got->model.heading_coeffs, m.model.heading_coeffs);
  EXPECT_EQ(got->model.form, avk::kinematics::YawModelForm::thesis);
  EXPECT_TRUE(got->model.refined);
  ASSERT_TRUE(got->model.speed.has_value());
  EXPECT_DOUBLE_EQ(got->model.speed->sag_per_deg, 0.01);
  EXPECT_EQ(got->validation_mse_m2, std::optional<double>(2.5));
  EXPECT_FALSE(s.models().get(b)->validation_mse_m2.has_value());
  EXPECT_FALSE(s.models().get(99).has_value());
  EXPECT_EQ(s.models().latest()->id, b);
  EXPECT_EQ(s.models().latest(std::string("cat-1"))->id, a);
  EXPECT_FALSE(s.models().latest(std::string("otter")).has_value());
  EXPECT_EQ(s.models().list().size(), 2u);
  EXPECT_EQ(s.models().list(std::string("usim-1")).size(), 1u);
}

TEST_P(NormalizedTurnsOnEngine, NewestOkTurnIdPerVehicle) {
  Store s(db());
  EXPECT_EQ(s.turns().newest_ok_id("usim-1"), 0);
  const auto m = make_mission(s);
  const auto a = s.turns().add(m, arc(1.0, 40.0, 1), TurnStatus::ok, "");
  s.turns().add(m, arc(1.0, 40.0, 2), TurnStatus::aborted, "containment");
  EXPECT_EQ(s.turns().newest_ok_id("usim-1"), a);
  EXPECT_EQ(s.turns().newest_ok_id("other"), 0);
}
