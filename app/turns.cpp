#include "app/turns.hpp"

#include "app/context.hpp"
#include "app/store_access.hpp"

namespace avk::app {

Result<Page<TurnView>> query_turns(Context& ctx, const TurnQuery& query) {
  if (query.limit < 1) return invalid_argument("limit", "must be at least 1");
  return make_page<TurnView>(views_of(store_of(ctx).turns().list(to_store(query))), query.limit,
                             [](const TurnView& t) { return t.id; });
}

Result<TurnDetail> get_turn(Context& ctx, std::int64_t turn_id) {
  auto t = store_of(ctx).turns().get(turn_id);
  if (!t) return not_found("no turn " + std::to_string(turn_id));
  return view_of(std::move(*t));
}

}  // namespace avk::app
