-- normalized_samples (packed float64, see pack_samples) and normalized_meta_json (the
-- normalised turn's JSON without samples) let the CKT load thousands of turns without
-- parsing their full JSON; normalized_json stays the turn's document of record.
ALTER TABLE missions ADD COLUMN runner_pid INTEGER;
ALTER TABLE turns ADD COLUMN normalized_samples BLOB;
ALTER TABLE turns ADD COLUMN normalized_meta_json TEXT;
CREATE INDEX turns_by_mission_end ON turns (mission_id, end_time_s);
CREATE TABLE condition_sets (
  id               INTEGER PRIMARY KEY,
  mission_id       INTEGER NOT NULL REFERENCES missions(id),
  start_s          REAL NOT NULL,
  end_s            REAL NOT NULL,
  target_speed_mps REAL NOT NULL,
  outcome          TEXT NOT NULL CHECK (outcome IN ('set', 'timeout', 'interrupted')),
  CHECK (end_s >= start_s)
);
CREATE INDEX condition_sets_by_mission ON condition_sets (mission_id, start_s);
CREATE TABLE mission_events (
  id         INTEGER PRIMARY KEY,
  mission_id INTEGER NOT NULL REFERENCES missions(id),
  t_s        REAL NOT NULL,
  kind       TEXT NOT NULL,
  message    TEXT NOT NULL
);
CREATE INDEX mission_events_by_mission ON mission_events (mission_id, id);
