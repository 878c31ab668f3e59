#include <gtest/gtest.h>

#include <set>
#include <string>

#include "mission/event_kind.hpp"
#include "mission/helm_mode.hpp"
#include "mission/mission_observer.hpp"

using namespace avk::mission;

TEST(EventKind, EveryKindRoundTripsThroughItsName) {
  ASSERT_FALSE(all_event_kinds().empty());
  for (const EventKind k : all_event_kinds()) {
    ASSERT_FALSE(to_string(k).empty());
    EXPECT_EQ(event_kind_from_string(to_string(k)), k) << to_string(k);
  }
}

TEST(EventKind, ListsEveryEnumeratorOnceAndNamesAreUnique) {
  std::set<std::string> names;
  std::set<EventKind> kinds;
  for (const EventKind k : all_event_kinds()) {
    names.insert(std::string(to_string(k)));
    kinds.insert(k);
  }
  EXPECT_EQ(names.size(), all_event_kinds().size());
  EXPECT_EQ(kinds.size(), all_event_kinds().size());
  // The first and the last enumerator bound the list: nothing is skipped in between.
  EXPECT_EQ(all_event_kinds().front(), EventKind::link);
  EXPECT_EQ(all_event_kinds().back(), EventKind::collision_clear);
  EXPECT_EQ(all_event_kinds().size(), static_cast<std::size_t>(EventKind::collision_clear) + 1);
}

TEST(EventKind, UnknownNamesAreNotKinds) {
  EXPECT_EQ(event_kind_from_string(""), std::nullopt);
  EXPECT_EQ(event_kind_from_string("halt"), std::nullopt);  // written by early versions
  EXPECT_EQ(event_kind_from_string("LINK"), std::nullopt);
  EXPECT_EQ(event_kind_from_string("link "), std::nullopt);
}

TEST(EventKind, NamesAreTheStoredOnes) {
  // These names are in existing databases and in clients: they must not change.
  EXPECT_EQ(to_string(EventKind::link), "link");
  EXPECT_EQ(to_string(EventKind::condition_set_timeout), "condition_set_timeout");
  EXPECT_EQ(to_string(EventKind::turn_given_up), "turn_given_up");
  EXPECT_EQ(to_string(EventKind::mission_attached), "mission_attached");
}

TEST(EventKind, Severities) {
  EXPECT_EQ(severity(EventKind::link), Severity::warning);
  EXPECT_EQ(severity(EventKind::turn_aborted), Severity::warning);
  EXPECT_EQ(severity(EventKind::halted), Severity::warning);
  EXPECT_EQ(severity(EventKind::condition_set_timeout), Severity::warning);
  EXPECT_EQ(severity(EventKind::returning), Severity::info);
  EXPECT_EQ(severity(EventKind::pause), Severity::info);
  EXPECT_EQ(severity(EventKind::mission_attached), Severity::info);
  EXPECT_EQ(to_string(Severity::warning), "warning");
  EXPECT_EQ(to_string(Severity::info), "info");
}

TEST(EventKind, StateChangesHaveTheirStatusKind) {
  EXPECT_EQ(state_change_kind(MissionState::running), EventKind::mission_running);
  EXPECT_EQ(state_change_kind(MissionState::halted), EventKind::mission_halted);
  for (const MissionState s :
       {MissionState::running, MissionState::paused, MissionState::interrupted,
        MissionState::aborted, MissionState::halted, MissionState::done})
    EXPECT_EQ(to_string(state_change_kind(s)), std::string("mission_") + to_string(s));
}

TEST(HelmMode, EveryModeRoundTripsThroughItsName) {
  ASSERT_EQ(all_helm_modes().size(), 11u);
  for (const HelmMode m : all_helm_modes())
    EXPECT_EQ(helm_mode_from_string(to_string(m)), m) << to_string(m);
  EXPECT_EQ(all_helm_modes().back(), HelmMode::stopped);
}
