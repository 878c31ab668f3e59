#include "server/cli/db_selection.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>

#include "server/serialize.hpp"
#include "vehicle/vehicle.hpp"

namespace avk::server {

std::int64_t parse_id(const std::string& text, const std::string& what) {
  const auto id = record_id(text);
  if (!id) throw UsageError(what + " needs a positive whole number, got '" + text + "'");
  return *id;
}

std::optional<std::int64_t> model_option(const Args& a) {
  const auto id = a.number("model");
  if (!id) return std::nullopt;
  if (*id < 1 || std::floor(*id) != *id) throw UsageError("--model needs a model id");
  return static_cast<std::int64_t>(*id);
}

app::PredictionMethod method_option(const Args& a) {
  const std::string method = a.get("method").value_or("avk");
  const auto m = app::prediction_method_from_string(method);
  if (!m) throw UsageError("--method must be avk, model or instantaneous, got '" + method + "'");
  return *m;
}

CurrentOption current_option(const Args& a, bool allow_live) {
  CurrentOption out;
  const auto text = a.get("current");
  if (!text) return out;
  if (*text == "live") {
    if (!allow_live) throw UsageError("--current live needs a station database; give EAST,NORTH");
    out.live = true;
    return out;
  }
  if (*text == "none") {
    out.none = true;
    return out;
  }
  const auto v = a.number_list("current", 2, "EAST,NORTH (m/s), live or none");
  out.current = kinematics::WaterCurrent{(*v)[0], (*v)[1]};
  return out;
}

std::optional<bool> speed_reference_option(const Args& a) {
  const auto ref = a.get("speed-reference");
  if (!ref) return std::nullopt;
  if (*ref != "over_ground" && *ref != "through_water")
    throw UsageError("--speed-reference must be over_ground or through_water");
  return *ref == "over_ground";
}

std::vector<std::int64_t> mission_ids(const Args& a) {
  std::vector<std::int64_t> ids;
  for (const std::string& s : a.all("mission"))
    ids.push_back(parse_id(s, "--mission"));
  return ids;
}

std::string vehicle_of(const Args& a, store::Store& db, const std::vector<std::int64_t>& ids,
                       const std::string& option) {
  if (const auto v = a.get(option)) return *v;
  std::set<std::string> vehicles;
  for (const auto& m : db.missions().list()) {
    if (ids.empty() || std::find(ids.begin(), ids.end(), m.id) != ids.end())
      vehicles.insert(m.vehicle_id);
  }
  for (const auto id : ids) {
    if (!db.missions().get(id)) throw std::runtime_error("no mission " + std::to_string(id));
  }
  if (vehicles.empty()) throw std::runtime_error("the database holds no missions");
  if (vehicles.size() > 1) {
    std::string names;
    for (const auto& v : vehicles)
      names += (names.empty() ? "" : ", ") + v;
    throw UsageError("the missions are of several vehicles (" + names + "): choose one with --" +
                     option);
  }
  return *vehicles.begin();
}

std::string vehicle_id_option(const Args& a, const std::string& fallback) {
  const std::string id = a.get("vehicle-id").value_or(fallback);
  if (const auto why = vehicle::vehicle_id_problem(id)) throw UsageError("--vehicle-id " + *why);
  return id;
}

}  // namespace avk::server
