#include "server/map_tile_routes.hpp"

#include <string>

#include "server/api_errors.hpp"
#include "server/api_params.hpp"
#include "server/http/problem.hpp"
#include "server/serialize/station.hpp"

namespace avk::server {

namespace {

// A tile coordinate of the path: digits only (no sign, no extension, no dots), so the number is
// all that reaches the tile source.
std::int64_t tile_coordinate(const PathParams& p, const std::string& name) {
  const std::string& v = p.at(name);
  const bool digits =
      !v.empty() && v.size() <= 9 && v.find_first_not_of("0123456789") == std::string::npos;
  if (!digits) {
    std::string why = "must be a whole number, got '";
    why += v;
    why += "'";
    throw bad_parameter(name, why);
  }
  return std::stoll(v);
}

}  // namespace

void add_map_tile_routes(Router& router, std::shared_ptr<const app::tiles::MapTiles> tiles,
                         std::optional<vehicle::LatLon> datum) {
  router.add({"GET", "/api/v1/tiles", Access::read, std::nullopt,
              [tiles, datum](const ApiRequest&, const PathParams&) {
                const auto j = map_tiles_json(tiles ? &tiles->info() : nullptr, datum);
                return ApiResponse{200, "application/json", j.dump(), {}};
              }});
  router.add({"GET", "/api/v1/tiles/{z}/{x}/{y}", Access::image, std::nullopt,
              [tiles](const ApiRequest&, const PathParams& p) {
                const auto z = tile_coordinate(p, "z");
                const auto x = tile_coordinate(p, "x");
                const auto y = tile_coordinate(p, "y");
                if (!tiles)
                  return problem_response(
                      404, "the station has no map tiles (start avk serve with --tiles PATH)");
                // z is at most 9 digits here; the source checks its range.
                const auto t = tiles->tile(static_cast<int>(z), x, y);
                if (!t) return problem_of(t.error(), false);
                ApiResponse r{200, t->media_type, t->bytes, {}};
                r.headers.push_back({"Cache-Control", kTileCacheControl});
                return r;
              }});
}

}  // namespace avk::server
