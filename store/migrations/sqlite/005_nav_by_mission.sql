-- Navigation pages by (mission, rowid): an index on mission_id holds the rowid in order, so
-- a page is a range scan, not a sort of the whole mission.
CREATE INDEX nav_by_mission ON nav_samples (mission_id);
