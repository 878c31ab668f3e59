#include "app/turns.hpp"

#include "app/context.hpp"

namespace avk::app {

Result<Page<store::TurnRow>> query_turns(Context& ctx, const store::TurnFilter& filter) {
  if (filter.limit < 1) return invalid_argument("limit", "must be at least 1");
  return make_page<store::TurnRow>(ctx.db().turns().list(filter), filter.limit,
                                   [](const store::TurnRow& t) { return t.id; });
}

Result<store::StoredTurn> get_turn(Context& ctx, std::int64_t turn_id) {
  auto t = ctx.db().turns().get(turn_id);
  if (!t) return not_found("no turn " + std::to_string(turn_id));
  return std::move(*t);
}

}  // namespace avk::app
