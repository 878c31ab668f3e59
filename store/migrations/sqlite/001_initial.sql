-- The first schema: vehicles, missions, turns (raw and normalised JSON), navigation samples
-- and CKT snapshots.
CREATE TABLE vehicles (
  id            TEXT PRIMARY KEY,
  kind          TEXT NOT NULL,
  max_speed_mps REAL NOT NULL,
  length_m      REAL
);
CREATE TABLE missions (
  id            INTEGER PRIMARY KEY,
  vehicle_id    TEXT NOT NULL REFERENCES vehicles(id),
  name          TEXT NOT NULL,
  config_json   TEXT NOT NULL,
  status        TEXT NOT NULL CHECK (status IN ('created', 'running', 'paused', 'interrupted',
                                                'aborted', 'halted', 'done')),
  created_utc   TEXT NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now')),
  started_s     REAL,
  ended_s       REAL,
  status_reason TEXT NOT NULL DEFAULT ''
);
CREATE TABLE turns (
  id                    INTEGER PRIMARY KEY,
  mission_id            INTEGER NOT NULL REFERENCES missions(id),
  vehicle_id            TEXT NOT NULL,
  cell_speed_mps        REAL NOT NULL,
  cell_dheading_deg     REAL NOT NULL,
  status                TEXT NOT NULL CHECK (status IN ('ok', 'aborted', 'rejected')),
  reason                TEXT NOT NULL,
  commanded_speed_mps   REAL NOT NULL,
  goal_dheading_deg     REAL NOT NULL,
  observed_dheading_deg REAL NOT NULL,
  start_time_s          REAL NOT NULL,
  end_time_s            REAL NOT NULL,
  advance_m             REAL,
  transfer_m            REAL,
  condition_set_time_s  REAL,
  raw_json              TEXT NOT NULL,
  normalized_json       TEXT
);
CREATE INDEX turns_by_mission ON turns (mission_id, id);
CREATE INDEX turns_by_cell ON turns (commanded_speed_mps, goal_dheading_deg, id);
CREATE TABLE nav_samples (
  mission_id          INTEGER NOT NULL REFERENCES missions(id),
  t_s                 REAL NOT NULL,
  x_m                 REAL NOT NULL,
  y_m                 REAL NOT NULL,
  heading_deg         REAL NOT NULL,
  speed_mps           REAL NOT NULL,
  desired_heading_deg REAL,
  desired_speed_mps   REAL,
  helm_mode           TEXT NOT NULL
);
CREATE INDEX nav_by_mission_time ON nav_samples (mission_id, t_s);
CREATE TABLE ckt_snapshots (
  id          INTEGER PRIMARY KEY,
  created_utc TEXT NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now')),
  mission_ids TEXT NOT NULL,
  document    TEXT NOT NULL
);
