#pragma once
// Which data of the store a command works on: --mission IDs, the vehicle, the model.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "app/context.hpp"
#include "app/predict.hpp"
#include "server/cli/args.hpp"

namespace avk::server {

// A record id: a positive whole number, else a UsageError naming `what` (an option, "mission id").
std::int64_t parse_id(const std::string& text, const std::string& what);

// --model: a model id, else a UsageError; none when absent.
std::optional<std::int64_t> model_option(const Args& a);

// --method avk|model|instantaneous (default avk), else a UsageError.
app::PredictionMethod method_option(const Args& a);

// --current live (the station's estimate), --current none (through the water) or --current
// EAST,NORTH (m/s toward east and north); absent: the station's default (over ground where it
// knows the current). A UsageError for anything else, or for live when allow_live is false.
struct CurrentOption {
  std::optional<kinematics::WaterCurrent> current;
  bool live = false;
  bool none = false;
};
CurrentOption current_option(const Args& a, bool allow_live = true);

// --speed-reference over_ground|through_water: which speed the vehicle's loop holds (true: over
// ground); none when absent. UsageError for anything else.
std::optional<bool> speed_reference_option(const Args& a);

// --vehicle-id: the id a vehicle is stored under (vehicle::vehicle_id_problem), else a
// UsageError naming the option; `fallback` when absent.
std::string vehicle_id_option(const Args& a, const std::string& fallback);

// Every --mission, each a positive whole number (UsageError otherwise); empty: all missions.
std::vector<std::int64_t> mission_ids(const Args& a);

// --vehicle (or the option named), or the only vehicle of the chosen missions (all missions when
// none are chosen). Mixing vehicles would average different hulls: several vehicles without the
// option is a UsageError naming them; an unknown mission or an empty database an app error.
std::string vehicle_of(const Args& a, app::Context& ctx, const std::vector<std::int64_t>& ids,
                       const std::string& option = "vehicle");

}  // namespace avk::server
