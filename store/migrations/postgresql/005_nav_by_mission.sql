-- Navigation pages by (mission, rowid): a range scan of this index, not a sort of the whole
-- mission. PostgreSQL's index on mission_id alone would not hold the rowid, so it is named.
CREATE INDEX nav_by_mission ON nav_samples (mission_id, rowid);
