#pragma once
// Stored turns: filtered pages (keyset pagination by id) and one turn with its trajectories.

#include <cstdint>

#include "app/missions.hpp"
#include "app/result.hpp"
#include "app/turn_views.hpp"

namespace avk::app {

class Context;

Result<Page<TurnView>> query_turns(Context& ctx, const TurnQuery& query);
Result<TurnDetail> get_turn(Context& ctx, std::int64_t turn_id);

}  // namespace avk::app
