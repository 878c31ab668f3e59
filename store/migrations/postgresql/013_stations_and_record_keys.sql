-- Several stations share one database: each mission records the station that ran it, and each
-- turn a key its station gave it, so a turn written again (a spool replayed after an outage whose
-- last commit's fate was unknown) is recognised instead of stored twice. NULL for every row
-- stored before. Every write that can change a vehicle's table (a turn, an imported table, a
-- model, a current) notifies channel avk_table_change with the vehicle's id ('' when the row
-- does not name one), so stations that cache tables drop them without polling.
ALTER TABLE missions ADD COLUMN station_id TEXT;
ALTER TABLE turns ADD COLUMN record_key TEXT;
CREATE UNIQUE INDEX turns_by_record_key ON turns (record_key);
CREATE FUNCTION avk_notify_table_change() RETURNS trigger LANGUAGE plpgsql AS $$
BEGIN
  PERFORM pg_notify('avk_table_change', coalesce(to_jsonb(NEW) ->> 'vehicle_id', ''));
  RETURN NULL;
END
$$;
CREATE TRIGGER turns_notify AFTER INSERT OR UPDATE ON turns
  FOR EACH ROW EXECUTE FUNCTION avk_notify_table_change();
CREATE TRIGGER ckt_snapshots_notify AFTER INSERT ON ckt_snapshots
  FOR EACH ROW EXECUTE FUNCTION avk_notify_table_change();
CREATE TRIGGER yaw_models_notify AFTER INSERT ON yaw_models
  FOR EACH ROW EXECUTE FUNCTION avk_notify_table_change();
CREATE TRIGGER mission_currents_notify AFTER INSERT OR UPDATE ON mission_currents
  FOR EACH ROW EXECUTE FUNCTION avk_notify_table_change();
