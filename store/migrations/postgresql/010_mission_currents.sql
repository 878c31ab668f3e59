-- The current each mission flew in (app/current.hpp) and its turns in the water frame, the
-- drift of that current removed (kinematics/water_frame.hpp), packed like the normalised
-- form: a table learned in one current then predicts turns in another.
CREATE TABLE mission_currents (
  mission_id       BIGINT PRIMARY KEY REFERENCES missions(id),
  t_s              DOUBLE PRECISION NOT NULL,
  method           TEXT NOT NULL CHECK (method IN ('legs', 'turns')),
  east_mps         DOUBLE PRECISION NOT NULL,
  north_mps        DOUBLE PRECISION NOT NULL,
  cov_ee           DOUBLE PRECISION NOT NULL,
  cov_en           DOUBLE PRECISION NOT NULL,
  cov_nn           DOUBLE PRECISION NOT NULL,
  speed_scale      DOUBLE PRECISION NOT NULL,
  residual_rms_mps DOUBLE PRECISION NOT NULL,
  evidence         BIGINT NOT NULL,
  revision         BIGINT NOT NULL,
  estimated_utc    TEXT NOT NULL DEFAULT (to_char(now() AT TIME ZONE 'UTC', 'YYYY-MM-DD"T"HH24:MI:SS.MS"Z"'))
);
ALTER TABLE turns ADD COLUMN water_samples BYTEA;
ALTER TABLE turns ADD COLUMN water_meta_json TEXT;
