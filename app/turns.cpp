#include "app/turns.hpp"

#include "app/context.hpp"

namespace avk::app {

Result<Page<store::TurnRow>> query_turns(Context& ctx, const store::TurnFilter& filter) {
  if (filter.limit < 1) return invalid_argument("limit", "must be at least 1");
  Page<store::TurnRow> page;
  page.items = ctx.db().list_turns(filter);
  if (static_cast<int>(page.items.size()) == filter.limit) page.next = page.items.back().id;
  return page;
}

Result<store::StoredTurn> get_turn(Context& ctx, std::int64_t turn_id) {
  auto t = ctx.db().get_turn(turn_id);
  if (!t) return not_found("no turn " + std::to_string(turn_id));
  return std::move(*t);
}

}  // namespace avk::app
