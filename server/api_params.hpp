#pragma once
// Reading an API request's parameters: numbers and ids from the query and the path, the format a
// client accepts, the body's media type. Each throws RequestError (400, 404, 406, 415) naming
// what is wrong.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "app/predict.hpp"
#include "server/api_types.hpp"
#include "server/http/router.hpp"

namespace avk::server {

std::optional<double> number_param(const ApiRequest& r, const std::string& name, double min,
                                   double max);
double required_number(const ApiRequest& r, const std::string& name, double min, double max);
// Required numbers read together: every one missing, malformed or out of range is named (400
// with `parameter` the first, `errors` [{field, message}] each, `detail` listing all), not only
// the first; else their values in the order asked.
struct NumberSpec {
  std::string name;
  double min = 0.0;
  double max = 0.0;
};
std::vector<double> required_numbers(const ApiRequest& r, const std::vector<NumberSpec>& specs);
// A whole number in [min, max].
std::optional<std::int64_t> whole_param(const ApiRequest& r, const std::string& name,
                                        std::int64_t min, std::int64_t max);
std::optional<std::int64_t> id_param(const ApiRequest& r, const std::string& name);
// A record id in the path: 404 naming `what` unless a positive whole number.
std::int64_t path_id(const PathParams& p, const std::string& key, const std::string& what);

// ?method=avk|model|instantaneous; none when absent.
std::optional<app::PredictionMethod> method_param(const ApiRequest& r);

// ?current=live (the station's estimate), ?current=none (through the water) or
// ?current=EAST,NORTH (m/s toward east and north); absent: over ground wherever the station
// knows the current. 400 naming `current` for anything else.
struct CurrentParam {
  std::optional<kinematics::WaterCurrent> current;
  bool live = false;
  bool none = false;
};
CurrentParam current_param(const ApiRequest& r);

// ?speed_reference=over_ground|through_water: which speed the vehicle's loop holds, overriding
// the station's; none when absent. 400 for anything else.
std::optional<bool> speed_reference_param(const ApiRequest& r);

// ?include=harvested: the vehicle's table of collection and harvested turns; absent or
// ?include=collection: collection turns only. Anything else is 400.
bool include_harvested_param(const ApiRequest& r);
// ?pool=class: a vehicle class's pooled table (app::class_table); absent or "vehicle": the
// vehicle's own. 400 otherwise.
bool pool_param(const ApiRequest& r);

enum class Format { json, csv };
// JSON or CSV as choose_representation (router.hpp) picks it: ?format= wins, otherwise Accept.
// Anything the resource cannot produce is 406 (400 for a bad ?format=).
Format negotiate(const ApiRequest& r, bool csv_available);

// 415 unless the body is sent as the media type (parameters such as charset are ignored).
void require_media_type(const ApiRequest& r, const std::string& type, const std::string& what);

RequestError bad_parameter(const std::string& name, const std::string& why);

// A request document's optional number fields: the body as an object (an empty body is an empty
// object, so a command without parameters needs no document), then each named field as a number
// (absent or null: none). A field of another type, or one not in `names` (a misspelt
// "radius" must not be ignored in favour of a default), is 422 naming its JSON pointer.
struct BodyNumbers {
  std::map<std::string, double> values;
  std::optional<double> get(const std::string& name) const;
};
BodyNumbers body_numbers(const ApiRequest& r, const std::vector<std::string>& names,
                         const std::string& what);

}  // namespace avk::server
