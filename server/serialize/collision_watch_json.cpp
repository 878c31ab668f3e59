#include "server/serialize/collision_watch.hpp"

namespace avk::server {

using nlohmann::json;

namespace {

json pair_json(const app::WatchPair& p) {
  return {{"a", p.a},
          {"b", p.b},
          {"a_name", p.a_name},
          {"b_name", p.b_name},
          {"a_basis", p.a_basis},
          {"b_basis", p.b_basis},
          {"distance_now_m", p.distance_now_m},
          {"cpa_m", p.cpa_m},
          {"cpa_t_s", p.cpa_t_s},
          {"alarm", p.alarm}};
}

json party_json(const app::WatchedParty& p) {
  json path = json::array();
  for (const auto& q : p.path)
    path.push_back({q.t_s, q.x_m, q.y_m});
  return {{"id", p.id},       {"name", p.name},          {"vehicle", p.vehicle},
          {"basis", p.basis}, {"path", std::move(path)}, {"half_width_m", p.half_width_m}};
}

}  // namespace

json collision_watch_json(const app::CollisionWatchView& v) {
  json pairs = json::array();
  for (const auto& p : v.pairs)
    pairs.push_back(pair_json(p));
  json parties = json::array();
  for (const auto& p : v.parties)
    parties.push_back(party_json(p));
  return {{"enabled", v.enabled},
          {"standoff_m", v.options.standoff_m},
          {"horizon_s", v.options.horizon_s},
          {"period_s", v.options.period_s},
          {"t_s", v.t_s ? json(*v.t_s) : json()},
          {"alarms", std::count_if(v.pairs.begin(), v.pairs.end(),
                                   [](const app::WatchPair& p) { return p.alarm; })},
          {"pairs", std::move(pairs)},
          {"parties", std::move(parties)}};
}

}  // namespace avk::server
