#pragma once
// Stored turns: filtered pages (keyset pagination by id) and one turn with its trajectories.

#include <cstdint>

#include "app/missions.hpp"
#include "app/result.hpp"
#include "store/store.hpp"

namespace avk::app {

class Context;

Result<Page<store::TurnRow>> query_turns(Context& ctx, const store::TurnFilter& filter);
Result<store::StoredTurn> get_turn(Context& ctx, std::int64_t turn_id);

}  // namespace avk::app
