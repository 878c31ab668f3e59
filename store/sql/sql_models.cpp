#include "store/sql/sql_models.hpp"

#include <exception>

#include <nlohmann/json.hpp>

#include "kinematics/yaw_model_json.hpp"
#include "store/sql/columns.hpp"

namespace avk::store::sql {

namespace {

// The database sets id and created_utc; a read returns them with the model's data, and a write
// adds the model's form, history, rate and refinement, kept beside the document so that models can
// be told apart without parsing it.
constexpr auto kModelKeys = columns("id", "created_utc");
constexpr auto kModelData = columns("vehicle_id", "training_missions", "train_one_step_rms_deg",
                                    "validation_mse_m2", "validation_heading_rms_deg", "document");
constexpr auto kModel = kModelKeys + kModelData;
constexpr auto kModelWrite = kModelData + columns("form", "history", "rate_hz", "refined");

StoredModel read_model(const Statement& s) {
  StoredModel m;
  m.id = s.column_int64(kModel["id"]);
  m.created_utc = s.column_text(kModel["created_utc"]);
  m.vehicle_id = s.column_text(kModel["vehicle_id"]);
  m.train_one_step_rms_deg = s.column_optional_double(kModel["train_one_step_rms_deg"]);
  m.validation_mse_m2 = s.column_optional_double(kModel["validation_mse_m2"]);
  m.validation_heading_rms_deg = s.column_optional_double(kModel["validation_heading_rms_deg"]);
  try {
    m.training_missions = nlohmann::json::parse(s.column_text(kModel["training_missions"]))
                              .get<std::vector<std::int64_t>>();
    m.model = kinematics::parse_yaw_model_json(s.column_text(kModel["document"]));
  } catch (const std::exception& e) {
    throw StoreError("yaw model " + std::to_string(m.id) + " is corrupt: " + e.what());
  }
  return m;
}

}  // namespace

std::int64_t SqlModels::save(const StoredModel& m) {
  auto s = db_.prepare("INSERT INTO yaw_models (" + kModelWrite.list() + ") VALUES (" +
                       kModelWrite.placeholders() + ") RETURNING id");
  s.bind(kModelWrite.param("vehicle_id"), m.vehicle_id);
  s.bind(kModelWrite.param("form"), kinematics::to_string(m.model.form));
  s.bind(kModelWrite.param("history"), static_cast<std::int64_t>(m.model.history));
  s.bind(kModelWrite.param("rate_hz"), m.model.rate_hz);
  s.bind(kModelWrite.param("refined"), static_cast<std::int64_t>(m.model.refined ? 1 : 0));
  s.bind(kModelWrite.param("training_missions"), nlohmann::json(m.training_missions).dump());
  s.bind(kModelWrite.param("train_one_step_rms_deg"), m.train_one_step_rms_deg);
  s.bind(kModelWrite.param("validation_mse_m2"), m.validation_mse_m2);
  s.bind(kModelWrite.param("validation_heading_rms_deg"), m.validation_heading_rms_deg);
  s.bind(kModelWrite.param("document"), kinematics::yaw_model_to_json(m.model));
  return inserted_id(s);
}

std::optional<StoredModel> SqlModels::get(std::int64_t id) {
  auto s = db_.prepare("SELECT " + kModel.list() + " FROM yaw_models WHERE id = ?");
  s.bind(1, id);
  if (!s.step()) return std::nullopt;
  return read_model(s);
}

std::vector<StoredModel> SqlModels::list(const std::optional<std::string>& vehicle_id) {
  auto s = db_.prepare("SELECT " + kModel.list() +
                       " FROM yaw_models WHERE ?1 IS NULL OR vehicle_id = ?1 ORDER BY id");
  s.bind(1, vehicle_id);
  std::vector<StoredModel> out;
  while (s.step())
    out.push_back(read_model(s));
  return out;
}

std::optional<StoredModel> SqlModels::latest(const std::optional<std::string>& vehicle_id) {
  auto s = db_.prepare("SELECT " + kModel.list() +
                       " FROM yaw_models WHERE ?1 IS NULL OR vehicle_id = ?1 "
                       "ORDER BY id DESC LIMIT 1");
  s.bind(1, vehicle_id);
  if (!s.step()) return std::nullopt;
  return read_model(s);
}

}  // namespace avk::store::sql
