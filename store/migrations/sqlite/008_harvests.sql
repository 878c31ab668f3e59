-- Turns harvested from ordinary navigation logs: each turn's source and
-- quality, and a record of every harvest run with its counts. Older turns are collection.
ALTER TABLE turns ADD COLUMN source TEXT NOT NULL DEFAULT 'collection'
  CHECK (source IN ('collection', 'harvested'));
ALTER TABLE turns ADD COLUMN quality REAL;
CREATE TABLE harvests (
  id               INTEGER PRIMARY KEY,
  mission_id       INTEGER NOT NULL REFERENCES missions(id),
  created_utc      TEXT NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now')),
  steps            INTEGER NOT NULL,
  harvested        INTEGER NOT NULL,
  already_recorded INTEGER NOT NULL,
  rejected_json    TEXT NOT NULL
);
CREATE INDEX harvests_by_mission ON harvests (mission_id, id);
