-- A vehicle's latest imported table is looked up by vehicle: a database holding several
-- vehicles must not answer one vehicle's question with another's table.
ALTER TABLE ckt_snapshots ADD COLUMN vehicle_id TEXT;
UPDATE ckt_snapshots SET vehicle_id = json_extract(document, '$.vehicle.id')
  WHERE json_valid(document);
CREATE INDEX ckt_snapshots_by_vehicle ON ckt_snapshots (vehicle_id, id);
