-- A vehicle's latest imported table is looked up by vehicle: a database holding several
-- vehicles must not answer one vehicle's question with another's table. No PostgreSQL database
-- predates this step (the engine came at schema 13), so there are no rows to fill in.
ALTER TABLE ckt_snapshots ADD COLUMN vehicle_id TEXT;
CREATE INDEX ckt_snapshots_by_vehicle ON ckt_snapshots (vehicle_id, id);
