#pragma once
// The map background's routes (`avk serve --tiles`): GET /api/v1/tiles says what there is, GET
// /api/v1/tiles/{z}/{x}/{y} sends one tile image. Without tiles the first answers
// `available: false` and the second 404s, so the page asks once and hides its Map switch.

#include <memory>
#include <optional>

#include "app/tiles/map_tiles.hpp"
#include "server/http/router.hpp"
#include "vehicle/local_grid.hpp"

namespace avk::server {

// How long a browser may keep a tile: an offline map changes only when the operator restarts the
// station with another one. private: the URL may carry the token.
inline constexpr const char* kTileCacheControl = "private, max-age=3600";

void add_map_tile_routes(Router& router, std::shared_ptr<const app::tiles::MapTiles> tiles,
                         std::optional<vehicle::LatLon> datum);

}  // namespace avk::server
