-- Identified yaw models: the model document (kinematics/yaw_model_json.hpp), what it was
-- trained on, and how well it did on data it did not see.
CREATE TABLE yaw_models (
  id                      INTEGER PRIMARY KEY,
  created_utc             TEXT NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now')),
  vehicle_id              TEXT NOT NULL,
  form                    TEXT NOT NULL,
  history                 INTEGER NOT NULL,
  rate_hz                 REAL NOT NULL,
  refined                 INTEGER NOT NULL,
  training_missions       TEXT NOT NULL,
  train_one_step_rms_deg  REAL,
  validation_mse_m2       REAL,
  validation_heading_rms_deg REAL,
  document                TEXT NOT NULL
);
CREATE INDEX yaw_models_by_vehicle ON yaw_models (vehicle_id, id);
