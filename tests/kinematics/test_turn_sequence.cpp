#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "kinematics/angles.hpp"
#include "kinematics/turn_sequence.hpp"
#include "support/synthetic_turns.hpp"

using namespace avk::kinematics;
using avk::testing::ArcTurnSpec;
using avk::testing::make_arc_turn;

TEST(Angles, WrapAndAngle180) {
  EXPECT_DOUBLE_EQ(wrap360_deg(-10.0), 350.0);
  EXPECT_DOUBLE_EQ(wrap360_deg(720.0), 0.0);
  EXPECT_DOUBLE_EQ(angle180_deg(190.0), -170.0);
  EXPECT_DOUBLE_EQ(angle180_deg(-180.0), 180.0);
  EXPECT_DOUBLE_EQ(angle180_deg(40.0 - 350.0), 50.0);
  EXPECT_NEAR(heading_of_deg(1.0, 0.0), 90.0, 1e-12);
  EXPECT_NEAR(heading_of_deg(0.0, -1.0), 180.0, 1e-12);
  EXPECT_NEAR(heading_of_deg(-1.0, 0.0), 270.0, 1e-12);
}

TEST(Angles, UnwrapAcrossNorth) {
  const auto u = unwrap_deg({350.0, 355.0, 5.0, 20.0, 40.0});
  ASSERT_EQ(u.size(), 5u);
  EXPECT_DOUBLE_EQ(u[4] - u[0], 50.0);
}

TEST(TurnSequence, HeadingWrapIsA50DegreeRightTurn) {
  TurnMeta meta;
  meta.goal_dheading_deg = 50.0;
  TurnSequence t(meta,
                 {{0, 0, 0, 350, 1}, {1, 0, 1, 10, 1}, {2, 0.5, 1.8, 30, 1}, {3, 1, 2.5, 40, 1}});
  t.fill_derived_metadata();
  EXPECT_DOUBLE_EQ(t.meta().observed_dheading_deg, 50.0);
  EXPECT_NO_THROW(t.validate());
  const auto n = t.normalized();
  EXPECT_DOUBLE_EQ(n.samples().back().heading_deg, 50.0);
  EXPECT_DOUBLE_EQ(n.samples().front().heading_deg, 0.0);
}

TEST(TurnSequence, ValidationErrorsAreTyped) {
  TurnMeta meta;
  meta.goal_dheading_deg = 30.0;
  auto code_of = [](const TurnSequence& t) {
    try {
      t.validate();
    } catch (const TurnError& e) {
      return e.code();
    }
    return TurnErrorCode::bad_metadata;  // sentinel: no error
  };
  EXPECT_EQ(code_of(TurnSequence(meta, {{0, 0, 0, 0, 1}, {1, 0, 1, 10, 1}})),
            TurnErrorCode::too_few_samples);
  EXPECT_EQ(code_of(TurnSequence(meta, {{0, 0, 0, 0, 1},
                                        {1, std::numeric_limits<double>::quiet_NaN(), 1, 10, 1},
                                        {2, 0, 2, 20, 1}})),
            TurnErrorCode::non_finite);
  EXPECT_EQ(code_of(TurnSequence(meta, {{0, 0, 0, 0, 1}, {1, 0, 1, 10, 1}, {1, 0, 2, 20, 1}})),
            TurnErrorCode::time_not_increasing);
  EXPECT_EQ(code_of(TurnSequence(meta, {{0, 0, 0, 10, 1}, {1, 0, 1, 12, 1}, {2, 0, 2, 10, 1}})),
            TurnErrorCode::instantaneous_turn);
  try {
    TurnSequence(meta, {{0, 0, 0, 0, 1}, {1, 0, 1, 10, 1}, {0.5, 0, 2, 20, 1}}).validate();
    FAIL() << "expected a TurnError";
  } catch (const TurnError& e) {
    ASSERT_TRUE(e.sample_index().has_value());
    EXPECT_EQ(*e.sample_index(), 2u);
  }
}

TEST(TurnSequence, MismatchedStreamsDropTrailingValuesWithWarning) {
  TurnMeta meta;
  meta.goal_dheading_deg = 40.0;
  const auto t = TurnSequence::from_streams(meta, {0, 1, 2, 3}, {0, 0.1, 0.5, 1.0, 9.9},
                                            {0, 1, 2, 2.8}, {0, 10, 25, 38}, {1, 1, 1, 1});
  ASSERT_EQ(t.samples().size(), 4u);
  EXPECT_DOUBLE_EQ(t.samples().back().x_m, 1.0);
  ASSERT_EQ(t.warnings().size(), 1u);
  EXPECT_NE(t.warnings()[0].find("x"), std::string::npos);
  EXPECT_DOUBLE_EQ(t.meta().observed_dheading_deg, 38.0);
}

// Normalising the same analytic turn placed anywhere, on any course, to either side gives the
// same normalised geometry.
TEST(TurnSequence, NormalizationInvariantUnderRotationTranslationReflection) {
  ArcTurnSpec base;
  base.dheading_deg = 70.0;
  const auto reference = make_arc_turn(base).normalized();
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> pos(-500.0, 500.0), hdg(0.0, 360.0);
  for (int trial = 0; trial < 50; ++trial) {
    ArcTurnSpec spec = base;
    spec.start = {pos(rng), pos(rng), hdg(rng)};
    spec.dheading_deg = trial % 2 == 0 ? 70.0 : -70.0;
    const auto n = make_arc_turn(spec).normalized();
    ASSERT_EQ(n.samples().size(), reference.samples().size());
    for (std::size_t i = 0; i < n.samples().size(); ++i) {
      EXPECT_NEAR(n.samples()[i].x_m, reference.samples()[i].x_m, 1e-9);
      EXPECT_NEAR(n.samples()[i].y_m, reference.samples()[i].y_m, 1e-9);
      EXPECT_NEAR(n.samples()[i].heading_deg, reference.samples()[i].heading_deg, 1e-9);
    }
  }
}

TEST(TurnSequence, NormalizedTurnStartsNorthAndTurnsRight) {
  ArcTurnSpec spec;
  spec.dheading_deg = -120.0;
  spec.start = {10, -4, 300};
  const auto n = make_arc_turn(spec).normalized();
  EXPECT_NEAR(n.samples().front().x_m, 0.0, 1e-12);
  EXPECT_NEAR(n.samples().front().y_m, 0.0, 1e-12);
  EXPECT_NEAR(n.samples()[1].x_m, 0.0, 1e-9);  // still in the lead-in: due north
  EXPECT_GT(n.samples()[1].y_m, 0.0);
  EXPECT_GT(n.samples().back().x_m, 0.0);  // ended to starboard
  EXPECT_NEAR(n.samples().back().heading_deg, 120.0, 1e-9);
}

// Placing a normalised turn back at its start pose and side recovers the recorded track.
TEST(TurnSequence, PlaceNormalizedIsTheInverse) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> pos(-100.0, 100.0), hdg(0.0, 360.0), dpsi(-170, 170);
  for (int trial = 0; trial < 30; ++trial) {
    ArcTurnSpec spec;
    spec.dheading_deg = dpsi(rng);
    if (std::abs(spec.dheading_deg) < 5) spec.dheading_deg = 5;
    spec.start = {pos(rng), pos(rng), hdg(rng)};
    const auto turn = make_arc_turn(spec);
    const auto placed =
        place_normalized(turn.normalized().points(), spec.start, side_of(spec.dheading_deg));
    const auto original = turn.points();
    ASSERT_EQ(placed.size(), original.size());
    for (std::size_t i = 0; i < placed.size(); ++i) {
      EXPECT_NEAR(placed[i].x_m, original[i].x_m, 1e-9);
      EXPECT_NEAR(placed[i].y_m, original[i].y_m, 1e-9);
    }
  }
}

TEST(TurnSequence, LeftAndRightTurnsAreMirrorImages) {
  ArcTurnSpec right;
  right.dheading_deg = 100.0;
  right.start = {3, 4, 45};
  ArcTurnSpec left = right;
  left.dheading_deg = -100.0;
  const auto r = make_arc_turn(right).points();
  const auto l = make_arc_turn(left).points();
  ASSERT_EQ(r.size(), l.size());
  for (std::size_t i = 0; i < r.size(); ++i) {
    // Mirror across the initial course line through the start.
    const Point nr = normalize_point(r[i], right.start, TurnSide::right);
    const Point nl = normalize_point(l[i], left.start, TurnSide::right);
    EXPECT_NEAR(nr.x_m, -nl.x_m, 1e-9);
    EXPECT_NEAR(nr.y_m, nl.y_m, 1e-9);
  }
}
