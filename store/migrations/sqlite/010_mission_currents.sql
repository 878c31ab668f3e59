-- The current each mission flew in (app/current.hpp) and its turns in the water frame, the
-- drift of that current removed (kinematics/water_frame.hpp), packed like the normalised
-- form: a table learned in one current then predicts turns in another.
CREATE TABLE mission_currents (
  mission_id       INTEGER PRIMARY KEY REFERENCES missions(id),
  t_s              REAL NOT NULL,
  method           TEXT NOT NULL CHECK (method IN ('legs', 'turns')),
  east_mps         REAL NOT NULL,
  north_mps        REAL NOT NULL,
  cov_ee           REAL NOT NULL,
  cov_en           REAL NOT NULL,
  cov_nn           REAL NOT NULL,
  speed_scale      REAL NOT NULL,
  residual_rms_mps REAL NOT NULL,
  evidence         INTEGER NOT NULL,
  revision         INTEGER NOT NULL,
  estimated_utc    TEXT NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now'))
);
ALTER TABLE turns ADD COLUMN water_samples BLOB;
ALTER TABLE turns ADD COLUMN water_meta_json TEXT;
