#pragma once
// The collision watch (app/collision_watch.hpp) as GET /api/v1/collision-watch answers: its
// settings, every watched pair's predicted closest approach with its alarm, and each party's
// predicted path.

#include <nlohmann/json.hpp>

#include "app/collision_watch.hpp"

namespace avk::server {

nlohmann::json collision_watch_json(const app::CollisionWatchView& v);

}  // namespace avk::server
