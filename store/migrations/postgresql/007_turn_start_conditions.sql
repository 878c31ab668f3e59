-- How steady each turn began (the ConditionSet's heading error and yaw rate): a turn begun
-- in the middle of a swing is visible in the report. Older turns have none.
ALTER TABLE turns ADD COLUMN start_heading_error_deg DOUBLE PRECISION;
ALTER TABLE turns ADD COLUMN start_yaw_rate_dps DOUBLE PRECISION;
