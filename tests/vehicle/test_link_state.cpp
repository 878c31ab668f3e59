#include <gtest/gtest.h>

#include "vehicle/vehicle.hpp"

using namespace avk::vehicle;

TEST(LinkState, LiveStaleDisconnected) {
  NavSample n;
  n.t_s = 10.0;
  EXPECT_EQ(link_state_from(n, true, 11.9, 2.0), LinkState::live);
  EXPECT_EQ(link_state_from(n, true, 12.1, 2.0), LinkState::stale);
  EXPECT_EQ(link_state_from(n, false, 10.5, 2.0), LinkState::disconnected);
  EXPECT_EQ(link_state_from(std::nullopt, true, 10.5, 2.0), LinkState::disconnected);
  EXPECT_STREQ(to_string(LinkState::stale), "STALE");
}

TEST(LinkState, EveryStateRoundTripsThroughItsName) {
  ASSERT_EQ(all_link_states().size(), 3u);
  for (const LinkState s : all_link_states())
    EXPECT_EQ(link_state_from_string(to_string(s)), s) << to_string(s);
  EXPECT_EQ(link_state_from_string("live"), std::nullopt);  // names are upper case, as sent
  EXPECT_EQ(link_state_from_string(""), std::nullopt);
}
