-- Several stations share one database: each mission records the station that ran it, and each
-- turn a key its station gave it, so a turn written again (a spool replayed after an outage whose
-- last commit's fate was unknown) is recognised instead of stored twice. NULL for every row
-- stored before.
ALTER TABLE missions ADD COLUMN station_id TEXT;
ALTER TABLE turns ADD COLUMN record_key TEXT;
CREATE UNIQUE INDEX turns_by_record_key ON turns (record_key);
